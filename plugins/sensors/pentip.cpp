/// `pentip` (simtwo-format.md §4.11): 1 when a `canvas` face is within 0.1 mm of the tip
/// (the sensor origin) along the beam; `x`, `y` give the touched point (world frame) so that
/// the viewer can paint the dot on the canvas.
#include "kinds.hpp"

namespace s2sim::sensors {

void PenTip::configure(ConfigureContext& ctx) {
  s_.read(ctx);
  s_.schedule(ctx);
  value_ = ctx.declare_signal("value", "1");
  x_ = ctx.declare_signal("x", "m");
  y_ = ctx.declare_signal("y", "m");
}

void PenTip::update(StepContext& ctx) {
  constexpr double kTouch = 1e-4;
  const Pose w = s_.world_pose(ctx);
  const RayHit h = ctx.cast_ray(w.position, w.rotation.column(0), s_.spec.beam.length_m, s_.ignore);
  const bool touching = h.hit && (h.material & material_canvas) && h.distance_m <= kTouch;
  ctx.publish(value_, touching ? 1.0 : 0.0);
  if (touching) {
    ctx.publish(x_, h.point_m.x);
    ctx.publish(y_, h.point_m.y);
  }
}

}  // namespace s2sim::sensors
