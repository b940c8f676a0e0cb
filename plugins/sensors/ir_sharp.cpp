/// `IRSharp` (simtwo-format.md §4.11, §12.3): the distance to the first surface along the
/// beam, -1 when nothing is within the beam length.
#include "kinds.hpp"

namespace s2sim::sensors {

void IRSharp::configure(ConfigureContext& ctx) {
  s_.read(ctx);
  const SensorNoise& n = s_.spec.noise;
  if (n.present && !(n.var_k >= 0))
    fail(ctx.params(), "noise", "var_k", "must be >= 0, got " + num(n.var_k));
  if (n.present && !(n.var_d >= 0))
    fail(ctx.params(), "noise", "var_d", "must be >= 0, got " + num(n.var_d));
  if (n.present && n.gain == 0) fail(ctx.params(), "noise", "gain", "must not be 0");
  s_.schedule(ctx);
  value_ = ctx.declare_signal("value", "m");
  valid_ = ctx.declare_signal("valid", "1");
}

void IRSharp::update(StepContext& ctx) {
  const Pose w = s_.world_pose(ctx);
  const RayHit h = ctx.cast_ray(w.position, w.rotation.column(0), s_.spec.beam.length_m, s_.ignore);
  if (!h.hit) {
    ctx.publish(value_, -1.0);
    ctx.publish(valid_, 0.0);
    return;
  }
  double d = h.distance_m;
  if (s_.spec.noise.present) {
    const double sigma = ir_sigma(s_.spec.noise, d);
    RandomStream r = ctx.random();
    if (sigma > 0) d += r.normal(0, sigma);
  }
  ctx.publish(value_, d);
  ctx.publish(valid_, 1.0);
}

}  // namespace s2sim::sensors
