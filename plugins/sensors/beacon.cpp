/// `beacon` (simtwo-format.md §4.11): a visual marker with no measurement in SimTwo; S2Sim
/// publishes where it is (world frame) so that a localisation controller can use it.
#include "kinds.hpp"

namespace s2sim::sensors {

void Beacon::configure(ConfigureContext& ctx) {
  s_.read(ctx);
  s_.schedule(ctx);
  x_ = ctx.declare_signal("x", "m");
  y_ = ctx.declare_signal("y", "m");
  z_ = ctx.declare_signal("z", "m");
}

void Beacon::update(StepContext& ctx) {
  const Pose w = s_.world_pose(ctx);
  ctx.publish(x_, w.position.x);
  ctx.publish(y_, w.position.y);
  ctx.publish(z_, w.position.z);
}

}  // namespace s2sim::sensors
