#include "kinds.hpp"

namespace rover {

void Compass::configure(s2sim::ConfigureContext& ctx) {
  const s2sim::Params& p = ctx.params();
  body_ = ctx.body(p.text("solid"));  // throws, located, when the robot has no such solid
  noise_stdev_rad_ = p.number("noise_stdev_rad", 0.0, s2sim::Range::non_negative());
  heading_ = ctx.declare_signal("heading", "rad");
}

void Compass::update(s2sim::StepContext& ctx) {
  double heading = s2sim::yaw_of(ctx.body_pose(body_).rotation);
  if (noise_stdev_rad_ > 0) heading += ctx.random().normal(0.0, noise_stdev_rad_);
  ctx.publish(heading_, heading);
}

}  // namespace rover
