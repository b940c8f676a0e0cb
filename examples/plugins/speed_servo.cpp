#include "kinds.hpp"

namespace rover {

void SpeedServo::configure(s2sim::ConfigureContext& ctx) {
  const s2sim::Params& p = ctx.params();
  axis_ = ctx.axis(p.text("axis"));
  gain_ = p.number("gain_Nms_rad", 0.05, s2sim::Range::positive());
  max_torque_ = p.number("max_torque_Nm", 0.5, s2sim::Range::positive());
  ref_speed_ = ctx.declare_input("ref_speed", "rad/s", 0.0);
  speed_ = ctx.declare_signal("speed", "rad/s");
}

void SpeedServo::update(s2sim::StepContext& ctx) {
  const double speed = ctx.axis_velocity(axis_);
  // f(v) = clamp(gain·(ref − speed) − gain·(v − speed), ±max): the kernel solves it at the
  // step's end speed, so a stiff gain does not ring (docs/plugins.md, axis drives).
  ctx.apply_axis_drive(axis_, gain_ * (ctx.input(ref_speed_) - speed), gain_, -max_torque_,
                       max_torque_);
  ctx.publish(speed_, speed);
}

}  // namespace rover
