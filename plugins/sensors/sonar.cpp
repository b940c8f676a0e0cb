/// `sonar`: the nearest echo in a cone of half angle beam.angle/2 sampled by beam.rays rays
/// (the axis, then a golden-angle spiral over the cone), -1 when nothing is within the beam
/// length. Generic noise on a hit.
#include "kinds.hpp"

namespace s2sim::sensors {

void Sonar::configure(ConfigureContext& ctx) {
  s_.read(ctx);
  s_.schedule(ctx);
  const int n = s_.spec.beam.rays;
  const double half = s_.spec.beam.angle_rad / 2;
  const double golden = kPi * (3 - std::sqrt(5.0));
  dirs_.push_back({1, 0, 0});
  for (int k = 1; k < n; ++k) {
    const double th = half * std::sqrt(static_cast<double>(k) / (n - 1));
    const double az = golden * k;
    dirs_.push_back({std::cos(th), std::sin(th) * std::cos(az), std::sin(th) * std::sin(az)});
  }
  value_ = ctx.declare_signal("value", "m");
}

void Sonar::update(StepContext& ctx) {
  const Pose w = s_.world_pose(ctx);
  double best = -1;
  for (const Vec3& d : dirs_) {
    const RayHit h = ctx.cast_ray(w.position, w.rotation * d, s_.spec.beam.length_m, s_.ignore);
    if (h.hit && (best < 0 || h.distance_m < best)) best = h.distance_m;
  }
  if (best >= 0) {
    RandomStream r = ctx.random();
    best = s_.noise.apply(r, best);
  }
  ctx.publish(value_, best);
}

}  // namespace s2sim::sensors
