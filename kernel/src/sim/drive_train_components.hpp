#pragma once
/// \file
/// The drive train of every axis as plugin components (docs/models/dc-motor.md).
///
/// For each degree of freedom of a hinge, slider or universal joint (articulations and
/// `<wheels>`; fixed and ball joints have none) the kernel instantiates three components of
/// the first-party `drive_train` plugin: an `encoder` (sensor), a `motor_controller` (stage
/// motor_control, at the controller's period) and a `dc_motor` (actuator, every tick). Their
/// parameters are the joint's drive-train elements as the loader kept them (SimTwo's
/// inheritance resolved, nothing interpreted: the defaults are the plugin's), under an element
/// located at the joint that says which axis they drive, so that the plugins read e.g.
/// `motor.ri` through the normal Params API and every error names the scene file, the element
/// the value is written in and the attribute.

#include <s2sim/kernel/scene.hpp>

#include <string>
#include <vector>

namespace s2sim::sim {

/// The component kinds put on every axis, in the order they are created.
inline constexpr const char* kDriveTrainKinds[] = {"encoder", "motor_controller", "dc_motor"};

/// One axis component the kernel must create.
struct AxisComponent {
  std::string kind;
  std::string id;      ///< `<axis>/<kind>`
  std::string prefix;  ///< the component's own prefix: `<axis prefix>/<kind>`
  int robot = -1;
  scene::ParamSource params;
  Location where;  ///< the joint
};

/// An axis of the multibody model, as far as the drive train needs it.
struct DriveAxis {
  std::string name;    ///< joint ID, `<ID>:2` for a Universal joint's second axis
  std::string prefix;  ///< `robots/<robot>/axes/<axis>`
  int robot = -1;
  int joint = -1;
  int which = 0;  ///< 0 = first axis, 1 = a Universal joint's second
  bool linear = false;
};

/// The parameter element of one axis:
///
///     <drive_train axis='robots/r/axes/a' linear='0' wheel='0' wrap='1' control_period='40'>
///       the joint's <motor>, <gear>, <rotor>, <encoder>, <controller>, <friction>, <spring>
///       as written (a Universal joint's second axis: its `motor2`... named `motor`...)
///     </drive_train>
///
/// `wheel` says the joint was made by `<wheels>` (its own controller defaults), `wrap` that
/// the shortest-way rule of `pidposition` applies (rotational, `wrap` set, no engaging stop),
/// `control_period` is the scene's control period in ms (the encoder's default period).
scene::ParamSource drive_train_params(const scene::Scene& scene, const DriveAxis& axis);

/// The components of every axis, in axis order then kDriveTrainKinds order.
std::vector<AxisComponent> drive_train_components(const scene::Scene& scene,
                                                  const std::vector<DriveAxis>& axes);

}  // namespace s2sim::sim
