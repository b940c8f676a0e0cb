#include "kinds.hpp"

#include <cmath>
#include <string>

namespace rover {

void HeadingController::configure(s2sim::ConfigureContext& ctx) {
  const s2sim::Params& p = ctx.params();
  // A controller reads a sensor through its published signal, and drives an actuator through
  // the actuator's input: both by full name, resolved here once.
  compass_ = ctx.published_signal(p.text("compass"));
  left_ = ctx.declare_input_at(p.text("left") + "/ref_speed", "rad/s", 0.0);
  right_ = ctx.declare_input_at(p.text("right") + "/ref_speed", "rad/s", 0.0);
  const double heading_rad = p.number("heading_deg", 0.0) * s2sim::kPi / 180.0;
  target_ = ctx.declare_input("heading", "rad", heading_rad);
  forward_ = p.number("forward_rad_s", 5.0);
  kp_ = p.number("kp", 4.0, s2sim::Range::non_negative());
  // Which way each wheel turns to roll forward: +1 or −1 (wheels on either side usually
  // turn opposite ways about their own outward axes).
  left_sign_ = p.number("left_sign", 1.0);
  right_sign_ = p.number("right_sign", 1.0);
  error_ = ctx.declare_signal("error", "rad");
}

void HeadingController::update(s2sim::StepContext& ctx) {
  // The heading error wrapped to (−π, π], so the rover turns the short way.
  const double error = std::remainder(ctx.input(target_) - ctx.signal(compass_), 2.0 * s2sim::kPi);
  const double turn = kp_ * error;  // rad/s of wheel speed difference, + turns left (CCW)
  ctx.set_input(left_, left_sign_ * (forward_ - turn));
  ctx.set_input(right_, right_sign_ * (forward_ + turn));
  ctx.publish(error_, error);
}

}  // namespace rover
