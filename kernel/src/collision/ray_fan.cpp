// Fan culling of the ray query (ray_caster.hpp): rays sharing an origin visit only the geoms
// whose boxes cover their azimuth sector as seen from that origin.
#include "collision/ray_caster.hpp"

#include "collision/ray_primitives.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace s2sim::collision {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// A fan is kept while its origin stays within kFanOriginMargin (in x and y) of where it was
// built and every moving geom's box within kFanGeomMargin of its box then: it sorted the
// boxes grown by both margins, which covers every direction a ray from the new origin can
// meet the moved geoms in. (The margins trade rebuilds against a few more geoms per sector.)
constexpr double kFanOriginMargin = 0.01;
constexpr double kFanGeomMargin = 0.02;

/// A monotonic stand-in for atan2(y, x), in [0, 4): 1 per quarter turn, no trigonometry.
double pseudo_angle(double x, double y) {
  const double ax = std::abs(x), ay = std::abs(y);
  const double r = ay / (ax + ay);  // 0 along x, 1 along y
  if (x >= 0) return y >= 0 ? r : (r == 0 ? 0.0 : 4 - r);
  return y >= 0 ? 2 - r : 2 + r;
}

Vec3 inverse_direction(const Vec3& d) {
  return {d.x != 0 ? 1 / d.x : kInf, d.y != 0 ? 1 / d.y : kInf, d.z != 0 ? 1 / d.z : kInf};
}

}  // namespace

bool RayCaster::use_fan(const Vec3& o, const Vec3& d) {
  if (!fan_enabled_ || (d.x == 0 && d.y == 0)) return false;
  if (!(fan_active_ && o == active_origin_)) {
    if (has_last_origin_ && o == last_origin_) {
      prepare_fan(o);  // the second ray from this origin in this tick
    } else {
      last_origin_ = o;
      has_last_origin_ = true;
    }
  }
  return fan_active_ && o == active_origin_;
}

void RayCaster::prepare_fan(const Vec3& o) {
  if (moving_dirty_) update_moving();
  bool keep = fan_valid_ && std::abs(o.x - fan_origin_.x) <= kFanOriginMargin &&
              std::abs(o.y - fan_origin_.y) <= kFanOriginMargin;
  const double* box = fan_box_.data();
  const Aabb* boxes = placement_.boxes();
  for (std::size_t i = 0; keep && i < n_moving_; ++i) {
    const Aabb& e = boxes[moving_[i]];
    const double* b = box + 4 * i;
    keep = e.min.x >= b[0] - kFanGeomMargin && e.max.x <= b[1] + kFanGeomMargin &&
           e.min.y >= b[2] - kFanGeomMargin && e.max.y <= b[3] + kFanGeomMargin;
  }
  if (!keep) build_fan(o);
  fan_active_ = true;
  active_origin_ = o;
}

void RayCaster::build_fan(const Vec3& o) {
  const std::size_t total = n_static_ + n_moving_;
  constexpr double kEps = 1e-9;
  std::fill(fan_start_.begin(), fan_start_.end(), 0);
  auto sector = [](double a) {
    a = a < 0 ? a + 4 : (a >= 4 ? a - 4 : a);
    return std::min(kFanSectors - 1, static_cast<int>(a * (kFanSectors / 4.0)));
  };
  const Aabb* boxes = placement_.boxes();
  for (std::size_t g = 0; g < total; ++g) {
    const Aabb& e = boxes[fan_shape_[g]];
    int first = 0, last = kFanSectors - 1;  // the whole circle unless narrowed below
    double m = kFanOriginMargin;
    if (g >= n_static_) {
      double* b = &fan_box_[4 * (g - n_static_)];
      b[0] = e.min.x;
      b[1] = e.max.x;
      b[2] = e.min.y;
      b[3] = e.max.y;
      m += kFanGeomMargin;
    }
    const double x0 = e.min.x - m - o.x, x1 = e.max.x + m - o.x;
    const double y0 = e.min.y - m - o.y, y1 = e.max.y + m - o.y;
    const bool around = x0 <= kEps && x1 >= -kEps && y0 <= kEps && y1 >= -kEps;
    if (!around) {
      // The box's footprint seen from outside spans less than half a turn: the corners'
      // pseudo-angles relative to the first one, each within (-2, 2], bound the interval.
      const double ref = pseudo_angle(x0, y0);
      double lo = 0, hi = 0;
      const double cx[3] = {x1, x0, x1}, cy[3] = {y0, y1, y1};
      for (int k = 0; k < 3; ++k) {
        double delta = pseudo_angle(cx[k], cy[k]) - ref;
        if (delta > 2) delta -= 4;
        if (delta <= -2) delta += 4;
        lo = std::min(lo, delta);
        hi = std::max(hi, delta);
      }
      if (hi - lo < 1.9) {  // else (nearly half a turn) keep the whole circle
        first = sector(ref + lo - kEps);
        last = sector(ref + hi + kEps);
      }
    }
    fan_first_[g] = first;
    fan_last_[g] = last;
    for (int k = first;; k = (k + 1) % kFanSectors) {
      ++fan_start_[static_cast<std::size_t>(k) + 1];
      if (k == last) break;
    }
  }
  for (int k = 0; k < kFanSectors; ++k)
    fan_start_[static_cast<std::size_t>(k) + 1] += fan_start_[static_cast<std::size_t>(k)];
  // Fill, using the start offsets as cursors, then shift them back.
  for (std::size_t g = 0; g < total; ++g)
    for (int k = fan_first_[g];; k = (k + 1) % kFanSectors) {
      fan_items_[static_cast<std::size_t>(fan_start_[static_cast<std::size_t>(k)]++)] =
          static_cast<std::int32_t>(g);
      if (k == fan_last_[g]) break;
    }
  for (int k = kFanSectors; k > 0; --k)
    fan_start_[static_cast<std::size_t>(k)] = fan_start_[static_cast<std::size_t>(k) - 1];
  fan_start_[0] = 0;
  fan_origin_ = o;
  fan_valid_ = true;
  ++fan_builds_;
}

void RayCaster::cast_fan(const Vec3& o, const Vec3& d, double max_distance,
                         std::int32_t ignore_body, RayHit& best) const {
  const int k =
      std::min(kFanSectors - 1, static_cast<int>(pseudo_angle(d.x, d.y) * (kFanSectors / 4.0)));
  const std::int32_t* items = fan_items_.data();
  const std::int32_t a = fan_start_[static_cast<std::size_t>(k)];
  const std::int32_t b = fan_start_[static_cast<std::size_t>(k) + 1];
  double s0 = 0, s1 = 0;
  // The segment's bounding box (z first) before the slab test, as in the sweep.
  const Vec3 end = o + d * (best.hit ? best.distance_m : max_distance);
  const double xa = std::min(o.x, end.x), xb = std::max(o.x, end.x);
  const double ya = std::min(o.y, end.y), yb = std::max(o.y, end.y);
  const double za = std::min(o.z, end.z), zb = std::max(o.z, end.z);
  // The packed boxes first; the shape, and the inverse direction of the slab test, only for
  // the geoms the segment's box meets.
  const double* packed = fan_geom_box_.data();
  const std::int32_t* shape = fan_shape_.data();
  const std::int32_t* body = table_.bodies().data();
  const Aabb* boxes = placement_.boxes();
  const std::size_t n_static = n_static_;
  Vec3 inv;
  bool have_inv = false;
  for (std::int32_t i = a; i < b; ++i) {
    const auto g = static_cast<std::size_t>(items[i]);
    const double* box = packed + 6 * g;
    if (box[0] > zb || box[1] < za || box[2] > xb || box[3] < xa || box[4] > yb || box[5] < ya)
      continue;
    const std::int32_t s = shape[g];
    if (g >= n_static && ignore_body > 0 && body[s] == ignore_body) continue;
    if (!have_inv) {
      inv = inverse_direction(d);
      have_inv = true;
    }
    const double t_lim = best.hit ? best.distance_m : max_distance;
    if (!ray_aabb(o, inv, boxes[s].min, boxes[s].max, t_lim, s0, s1)) continue;
    test_shape(s, o, d, t_lim, best);
  }
}

}  // namespace s2sim::collision
