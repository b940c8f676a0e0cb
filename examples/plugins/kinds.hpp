#pragma once
// The example plugin's three kinds, declared here and registered in descriptor.cpp.
#include <s2sim/sdk.hpp>

namespace rover {

/// Sensor `compass`: the heading (yaw, rad) of a solid, with optional Gaussian noise.
/// Parameters: `solid` (required), `noise_stdev_rad` (default 0). Signal: `heading` (rad).
class Compass : public s2sim::Component {
 public:
  void configure(s2sim::ConfigureContext& ctx) override;
  void update(s2sim::StepContext& ctx) override;

 private:
  s2sim::BodyHandle body_;
  double noise_stdev_rad_ = 0;
  s2sim::SignalHandle heading_;
};

/// Actuator `speed_servo`: holds an axis at the speed of its input `ref_speed` (rad/s) with a
/// torque gain·(ref − ω) bounded by ±max_torque, solved implicitly by the kernel (an axis
/// drive). Parameters: `axis` (required), `gain_Nms_rad` (> 0), `max_torque_Nm` (> 0).
/// Input: `ref_speed` (rad/s). Signal: `speed` (rad/s).
class SpeedServo : public s2sim::Component {
 public:
  void configure(s2sim::ConfigureContext& ctx) override;
  void update(s2sim::StepContext& ctx) override;

 private:
  s2sim::AxisHandle axis_;
  double gain_ = 0, max_torque_ = 0;
  s2sim::InputHandle ref_speed_;
  s2sim::SignalHandle speed_;
};

/// Controller `heading_controller`: drives a differential robot along a heading. Reads a
/// compass's `heading` signal and writes the `ref_speed` inputs of the two wheel servos:
/// forward ± kp·error. Parameters: `compass` (the compass's signal, full name), `left` and
/// `right` (the servos' input prefixes), `heading_deg`, `forward_rad_s`, `kp`, `left_sign`
/// and `right_sign` (±1: the wheel's forward direction).
/// Input: `heading` (rad, starts at heading_deg). Signal: `error` (rad).
class HeadingController : public s2sim::Component {
 public:
  void configure(s2sim::ConfigureContext& ctx) override;
  void update(s2sim::StepContext& ctx) override;

 private:
  s2sim::SignalHandle compass_, error_;
  s2sim::InputHandle target_, left_, right_;
  double forward_ = 0, kp_ = 0, left_sign_ = 1, right_sign_ = 1;
};

}  // namespace rover
