/// `ranger2d` (simtwo-format.md §4.11): N = max(3, rays) rays fanned in the sensor's XY
/// plane from -angle/2 (ray 0) to +angle/2. Swept mode (SimTwo's, the default): every tick
/// casts the slice of rays [round(N·j/P), round(N·(j+1)/P)) of tick j of the period's P ticks,
/// and the whole scan is published at the end of the period (one sweep per period). Instant
/// mode (`<scan mode='instant'/>`): every ray at once, at the period. A ray without a hit
/// reads -1 (noise is not added to it).
#include "kinds.hpp"

#include <algorithm>
#include <string>

namespace s2sim::sensors {

void Ranger2D::configure(ConfigureContext& ctx) {
  s_.read(ctx);
  const Params& p = ctx.params();
  const std::string mode = p.text("scan.mode", "sweep");
  if (mode == "sweep")
    sweep_ = true;
  else if (mode == "instant")
    sweep_ = false;
  else
    fail(p, "scan", "mode", "must be 'sweep' or 'instant', got '" + mode + "'");
  n_ = std::max(3, s_.spec.beam.rays);
  const double a = s_.spec.beam.angle_rad;
  for (int i = 0; i < n_; ++i) {
    const double phi = -a / 2 + a * i / (n_ - 1);
    dirs_.push_back({std::cos(phi), std::sin(phi), 0});
  }
  for (int i = 0; i < n_; ++i)
    rays_.push_back(ctx.declare_signal("ray/" + std::to_string(i), "m"));
  sweeps_ = ctx.declare_signal("sweeps", "1");
  sweep_count_ = ctx.declare_state("sweep_count", 1, 0.0);
  if (sweep_) {
    pending_ = ctx.declare_state("pending", n_, -1.0);
    ctx.set_schedule(Stage::sense, ctx.tick_s());
  } else {
    s_.schedule(ctx);
  }
}

void Ranger2D::initialize(StepContext& ctx) {
  for (int i = 0; i < n_; ++i)
    ctx.publish(rays_[static_cast<std::size_t>(i)], -1.0);
}

double Ranger2D::cast(StepContext& ctx, const Pose& w, int i) const {
  const RayHit h = ctx.cast_ray(w.position, w.rotation * dirs_[static_cast<std::size_t>(i)],
                                s_.spec.beam.length_m, s_.ignore);
  if (!h.hit) return -1;
  RandomStream r = ctx.random();
  return s_.noise.apply(r, h.distance_m);
}

void Ranger2D::update(StepContext& ctx) {
  const Pose w = s_.world_pose(ctx);
  double& count = ctx.state(sweep_count_)[0];
  if (!sweep_) {
    for (int i = 0; i < n_; ++i)
      ctx.publish(rays_[static_cast<std::size_t>(i)], cast(ctx, w, i));
    ctx.publish(sweeps_, ++count);
    return;
  }
  const std::int64_t p = s_.period_ticks;
  const std::int64_t j = ctx.tick() % p;
  const auto first = static_cast<int>((static_cast<std::int64_t>(n_) * j + p / 2) / p);
  const auto last = static_cast<int>((static_cast<std::int64_t>(n_) * (j + 1) + p / 2) / p);
  double* pending = ctx.state(pending_);
  for (int i = first; i < last && i < n_; ++i)
    pending[i] = cast(ctx, w, i);
  if (j == p - 1) {
    for (int i = 0; i < n_; ++i)
      ctx.publish(rays_[static_cast<std::size_t>(i)], pending[i]);
    ctx.publish(sweeps_, ++count);
  }
}

}  // namespace s2sim::sensors
