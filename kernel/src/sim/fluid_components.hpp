#pragma once
/// \file
/// SimTwo's `<drag>`, `<buoyant>`/`<buoyance>` and `<propeller>` solids (simtwo-format.md §4.4)
/// as components of the first-party `fluids` plugin (docs/models/fluids.md).
///
/// For each solid with an explicit `<drag>`, a non-zero buoyant mass or of the `<propeller>`
/// kind, the kernel instantiates a `drag`, `buoyancy` or `propeller` component in SimTwo's
/// semantics (`semantics='simtwo'`). Their parameter element is synthesised from the solid as
/// the loader kept it (values already checked there, located at the solid), with what the
/// plugin cannot see through the SDK: the projected areas of the primitive, the body's mass,
/// centre of mass and inertia, the scene's wind.
///
/// SimTwo applies the quadratic drag, the buoyancy and the thrust to robot solids only: on a
/// thing they are left out with a warning, as SimTwo leaves them out (its per-step damping
/// applies to things too). SimTwo's default damping (stokes 1e-5, roll 1e-3 on every solid) is
/// applied only where `<drag>` is written (docs/models/fluids.md says why).

#include <s2sim/kernel/scene.hpp>

#include <string>
#include <vector>

namespace s2sim::sim {

/// One fluid component the kernel must create.
struct FluidComponent {
  std::string kind;    ///< drag, buoyancy, propeller
  std::string id;      ///< `<solid>/<kind>`
  std::string prefix;  ///< its signals': `robots/<robot>/solids/<solid>/<kind>`
  int robot = -1;
  scene::ParamSource params;
  Location where;  ///< the solid
};

/// The components of every body in body order, drag then buoyancy then propeller; `warnings`
/// gets a located line for each SimTwo value left out on a thing. `robot_prefixes[r]` is
/// robot r's signal prefix (`robots/<robot>`).
std::vector<FluidComponent> fluid_components(const scene::Scene& scene,
                                             const std::vector<std::string>& robot_prefixes,
                                             std::vector<std::string>& warnings);

}  // namespace s2sim::sim
