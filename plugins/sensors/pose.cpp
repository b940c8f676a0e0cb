/// `pose`: GPS-like ground truth of the sensor frame with noise: x, y, z through SimTwo's
/// generic noise (gain·v + offset + N(0, stdev) + N(0, stdev_p·|v|)), yaw + N(0, yaw_stdev)
/// (`<noise yaw_stdev>`, rad), wrapped to (−π, π].
#include "kinds.hpp"

namespace s2sim::sensors {

void PoseSensor::configure(ConfigureContext& ctx) {
  ctx.declare_local();  // its own body (and joint): stepped in that body's part
  s_.read(ctx);
  s_.schedule(ctx);
  yaw_stdev_ = ctx.params().number("noise.yaw_stdev", 0.0, Range::non_negative());
  x_ = ctx.declare_signal("x", "m");
  y_ = ctx.declare_signal("y", "m");
  z_ = ctx.declare_signal("z", "m");
  yaw_ = ctx.declare_signal("yaw", "rad");
}

void PoseSensor::update(StepContext& ctx) {
  const Pose w = s_.world_pose(ctx);
  RandomStream r = ctx.random();
  ctx.publish(x_, s_.noise.apply(r, w.position.x));
  ctx.publish(y_, s_.noise.apply(r, w.position.y));
  ctx.publish(z_, s_.noise.apply(r, w.position.z));
  double yaw = yaw_of(w.rotation);
  if (s_.noise.on && yaw_stdev_ > 0) yaw = std::remainder(yaw + r.normal(0, yaw_stdev_), 2 * kPi);
  ctx.publish(yaw_, yaw);
}

}  // namespace s2sim::sensors
