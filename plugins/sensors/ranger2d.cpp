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
  sweep_ = p.choice("scan.mode", {"sweep", "instant"}, "sweep") == "sweep";
  n_ = std::max(3, s_.spec.beam.rays);
  zig_ = &ziggurat_tables();
  const double a = s_.spec.beam.angle_rad;
  for (int i = 0; i < n_; ++i) {
    const double phi = -a / 2 + a * i / (n_ - 1);
    dirs_.push_back({std::cos(phi), std::sin(phi), 0});
  }
  for (int i = 0; i < n_; ++i)
    rays_.push_back(ctx.declare_signal("ray/" + std::to_string(i), "m"));
  sweeps_ = ctx.declare_signal("sweeps", "1");
  sweep_count_ = ctx.declare_state("sweep_count", 1, 0.0);
  pending_ = ctx.declare_state("pending", n_, -1.0);
  if (sweep_) {
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
  return h.hit ? h.distance_m : -1.0;
}

void Ranger2D::add_noise(StepContext& ctx, double* d, int first, int last) const {
  // SimTwo's generic noise on every hit (-1 stays -1); Gaussian draws by the ziggurat (one
  // per ray: the SDK's Box-Muller would be a third of a ray's cost).
  if (!s_.noise.on) return;
  const GenericNoise& n = s_.noise;
  RandomStream r = ctx.random();
  auto normal = [&]() { return ziggurat_normal(r, *zig_); };
  for (int i = first; i < last; ++i) {
    if (d[i] < 0) continue;
    double v = n.gain * d[i] + n.offset;
    if (n.stdev > 0) v += n.stdev * normal();
    if (n.stdev_p > 0) v += n.stdev_p * std::abs(d[i]) * normal();
    d[i] = v;
  }
}

void Ranger2D::update(StepContext& ctx) {
  const Pose w = s_.world_pose(ctx);
  double& count = ctx.state(sweep_count_)[0];
  const Span<double> pending = ctx.state(pending_);
  if (!sweep_) {
    for (int i = 0; i < n_; ++i)
      pending[i] = cast(ctx, w, i);
    add_noise(ctx, pending.data(), 0, n_);
    for (int i = 0; i < n_; ++i)
      ctx.publish(rays_[static_cast<std::size_t>(i)], pending[i]);
    ctx.publish(sweeps_, ++count);
    return;
  }
  const std::int64_t p = s_.period_ticks;
  const std::int64_t j = ctx.tick() % p;
  const auto first = static_cast<int>((static_cast<std::int64_t>(n_) * j + p / 2) / p);
  const auto last =
      std::min(n_, static_cast<int>((static_cast<std::int64_t>(n_) * (j + 1) + p / 2) / p));
  for (int i = first; i < last; ++i)
    pending[i] = cast(ctx, w, i);
  add_noise(ctx, pending.data(), first, last);
  if (j == p - 1) {
    for (int i = 0; i < n_; ++i)
      ctx.publish(rays_[static_cast<std::size_t>(i)], pending[i]);
    ctx.publish(sweeps_, ++count);
  }
}

}  // namespace s2sim::sensors
