/// `floorline` (simtwo-format.md §4.11, §7): a side×side grid of parallel rays, side =
/// round(√rays), pitch final_width/2 across the beam; the value is the fraction of rays whose
/// ground point lies inside a track polygon carrying one of the sensor's tags (even-odd rule).
#include "kinds.hpp"

#include <algorithm>
#include <set>

namespace s2sim::sensors {

void FloorLine::configure(ConfigureContext& ctx) {
  s_.read(ctx);
  s_.schedule(ctx);
  side_ = std::max(1, static_cast<int>(std::lround(std::sqrt(s_.spec.beam.rays))));
  pitch_ = s_.spec.beam.final_width_m / 2;
  const std::vector<FloorPolygon> polys = ctx.floor_polygons();
  std::set<std::string> known;
  for (const auto& poly : polys)
    known.insert(poly.tag);
  // SimTwo accepts a tag no polygon carries (one shipped project has one): the sensor then
  // never sees that tag. A warning, not an error, so such a scene loads as in SimTwo.
  for (const auto& tag : s_.spec.simtwo.tags) {
    if (known.count(tag)) continue;
    std::string have;
    for (const auto& k : known)
      have += (have.empty() ? "" : ", ") + ("'" + k + "'");
    ctx.warn("no track polygon has the tag '" + tag + "' (" +
             (have.empty() ? std::string("the scene has no track") : "tags: " + have) +
             "): it reads 0 for that tag");
  }
  poly_start_.push_back(0);
  for (const auto& poly : polys) {
    if (std::find(s_.spec.simtwo.tags.begin(), s_.spec.simtwo.tags.end(), poly.tag) ==
            s_.spec.simtwo.tags.end() ||
        poly.x_m.size() < 3)
      continue;
    vx_.insert(vx_.end(), poly.x_m.begin(), poly.x_m.end());
    vy_.insert(vy_.end(), poly.y_m.begin(), poly.y_m.end());
    poly_start_.push_back(vx_.size());
    bx0_.push_back(*std::min_element(poly.x_m.begin(), poly.x_m.end()));
    bx1_.push_back(*std::max_element(poly.x_m.begin(), poly.x_m.end()));
    by0_.push_back(*std::min_element(poly.y_m.begin(), poly.y_m.end()));
    by1_.push_back(*std::max_element(poly.y_m.begin(), poly.y_m.end()));
  }
  value_ = ctx.declare_signal("value", "1");
}

bool FloorLine::inside(double x, double y) const {
  for (std::size_t k = 0; k + 1 < poly_start_.size(); ++k) {
    if (x < bx0_[k] || x > bx1_[k] || y < by0_[k] || y > by1_[k]) continue;
    bool in = false;
    const std::size_t a = poly_start_[k], b = poly_start_[k + 1];
    for (std::size_t i = a, j = b - 1; i < b; j = i++) {
      if ((vy_[i] > y) != (vy_[j] > y) &&
          x < (vx_[j] - vx_[i]) * (y - vy_[i]) / (vy_[j] - vy_[i]) + vx_[i])
        in = !in;
    }
    if (in) return true;
  }
  return false;
}

void FloorLine::update(StepContext& ctx) {
  const Pose w = s_.world_pose(ctx);
  const Vec3 dir = w.rotation.column(0), ay = w.rotation.column(1), az = w.rotation.column(2);
  int on = 0;
  const double c = 0.5 * (side_ - 1);
  for (int i = 0; i < side_; ++i)
    for (int j = 0; j < side_; ++j) {
      const Vec3 o = w.position + ay * ((i - c) * pitch_) + az * ((j - c) * pitch_);
      const RayHit h = ctx.cast_ray(o, dir, s_.spec.beam.length_m, s_.ignore);
      // The ray must reach the ground plane itself (not an obstacle or a body on it).
      if (!h.hit || h.body.index != 0 || h.normal.z < 0.999 || std::abs(h.point_m.z) > 1e-6)
        continue;
      if (inside(h.point_m.x, h.point_m.y)) ++on;
    }
  RandomStream r = ctx.random();
  ctx.publish(value_, s_.noise.apply(r, static_cast<double>(on) / (side_ * side_)));
}

}  // namespace s2sim::sensors
