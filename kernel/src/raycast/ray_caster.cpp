#include "raycast/ray_caster.hpp"

#include "raycast/primitives.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace s2sim::raycast {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPad = 1e-9;  // AABB padding against round-off on cell and box edges
constexpr int kMaxCellsPerAxis = 256;
constexpr std::size_t kSmallStatic = 16;   // up to this many obstacles: no grid walk
constexpr std::size_t kFanMaxGeoms = 256;  // fan culling up to this many geoms
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

Mat3 abs_matrix(const Mat3& r) {
  Mat3 a;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      a.m[i][j] = std::abs(r.m[i][j]);
  return a;
}

Vec3 inverse_direction(const Vec3& d) {
  return {d.x != 0 ? 1 / d.x : kInf, d.y != 0 ? 1 / d.y : kInf, d.z != 0 ? 1 / d.z : kInf};
}

/// A surface exactly at the ray's end counts: round-off must not decide whether a wall at
/// the beam length is seen.
double reach(double max_distance) {
  return max_distance * (1 + 1e-12) + 1e-12;
}

}  // namespace

RayCaster::RayCaster(const scene::Scene& scene, const Pose* poses) : poses_(poses) {
  walls_ = scene.settings.world_walls;
  wall_distance_ = scene.settings.world_wall_distance_m;
  for (const auto& g : scene.obstacles)
    add_geom(g, 0);
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    for (const auto& g : scene.bodies[b].geoms)
      add_geom(g, static_cast<std::int32_t>(b + 1));

  // Static grid over the obstacles' XY bounds.
  for (auto& e : statics_) {
    e.world = e.local;
    compute_aabb(e);
  }
  stamp_.assign(statics_.size(), 0);
  for (const auto& e : statics_)
    static_box_.insert(static_box_.end(), {e.lo.x, e.hi.x, e.lo.y, e.hi.y, e.lo.z, e.hi.z});
  if (!statics_.empty()) {
    double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
    for (const auto& e : statics_) {
      x0 = std::min(x0, e.lo.x);
      y0 = std::min(y0, e.lo.y);
      x1 = std::max(x1, e.hi.x);
      y1 = std::max(y1, e.hi.y);
    }
    const double ex = std::max(x1 - x0, 1e-6), ey = std::max(y1 - y0, 1e-6);
    const double n = static_cast<double>(statics_.size());
    cell_ = std::sqrt(ex * ey / (2 * n));  // about two cells per obstacle
    cell_ = std::max({cell_, ex / kMaxCellsPerAxis, ey / kMaxCellsPerAxis, 1e-6});
    nx_ = std::clamp(static_cast<int>(std::ceil(ex / cell_)), 1, kMaxCellsPerAxis);
    ny_ = std::clamp(static_cast<int>(std::ceil(ey / cell_)), 1, kMaxCellsPerAxis);
    grid_x0_ = x0;
    grid_y0_ = y0;
    auto cell_range = [&](const GeomEntry& e, int& ix0, int& ix1, int& iy0, int& iy1) {
      ix0 = std::clamp(static_cast<int>(std::floor((e.lo.x - x0) / cell_)), 0, nx_ - 1);
      ix1 = std::clamp(static_cast<int>(std::floor((e.hi.x - x0) / cell_)), 0, nx_ - 1);
      iy0 = std::clamp(static_cast<int>(std::floor((e.lo.y - y0) / cell_)), 0, ny_ - 1);
      iy1 = std::clamp(static_cast<int>(std::floor((e.hi.y - y0) / cell_)), 0, ny_ - 1);
    };
    cell_start_.assign(static_cast<std::size_t>(nx_ * ny_ + 1), 0);
    int ix0, ix1, iy0, iy1;
    for (const auto& e : statics_) {
      cell_range(e, ix0, ix1, iy0, iy1);
      for (int iy = iy0; iy <= iy1; ++iy)
        for (int ix = ix0; ix <= ix1; ++ix)
          ++cell_start_[static_cast<std::size_t>(iy * nx_ + ix + 1)];
    }
    for (std::size_t c = 1; c < cell_start_.size(); ++c)
      cell_start_[c] += cell_start_[c - 1];
    cell_items_.assign(static_cast<std::size_t>(cell_start_.back()), 0);
    std::vector<std::int32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < statics_.size(); ++i) {
      cell_range(statics_[i], ix0, ix1, iy0, iy1);
      for (int iy = iy0; iy <= iy1; ++iy)
        for (int ix = ix0; ix <= ix1; ++ix)
          cell_items_[static_cast<std::size_t>(fill[static_cast<std::size_t>(iy * nx_ + ix)]++)] =
              static_cast<std::int32_t>(i);
    }
  }
  const std::size_t total = statics_.size() + moving_.size();
  fan_enabled_ = statics_.size() <= kSmallStatic && total > 0 && total <= kFanMaxGeoms;
  if (fan_enabled_) {
    fan_start_.assign(kFanSectors + 1, 0);
    fan_items_.assign(kFanSectors * total, 0);
    fan_first_.assign(total, 0);
    fan_last_.assign(total, 0);
    fan_box_.assign(4 * moving_.size(), 0.0);
    fan_geom_box_.assign(6 * total, 0.0);
    for (std::size_t g = 0; g < statics_.size(); ++g) {
      const GeomEntry& e = statics_[g];
      double* fb = &fan_geom_box_[6 * g];
      fb[0] = e.lo.z;
      fb[1] = e.hi.z;
      fb[2] = e.lo.x;
      fb[3] = e.hi.x;
      fb[4] = e.lo.y;
      fb[5] = e.hi.y;
    }
  }
  order_.resize(moving_.size());
  for (std::size_t i = 0; i < order_.size(); ++i)
    order_[i] = static_cast<std::int32_t>(i);
  order_lo_x_.assign(moving_.size(), 0.0);
  order_box_.assign(5 * moving_.size(), 0.0);
}

void RayCaster::add_geom(const scene::Geom& g, std::int32_t body) {
  GeomEntry e;
  e.body = body;
  e.type = g.shape.type;
  e.half = g.shape.size_m * 0.5;
  e.radius = g.shape.radius_m;
  e.half_length = 0.5 * g.shape.length_m;
  if (g.material.metallic) e.material |= material_metallic;
  if (g.material.ferromagnetic) e.material |= material_ferromagnetic;
  if (g.material.rfid_tag) e.material |= material_rfid_tag;
  if (g.visual.canvas) e.material |= material_canvas;
  e.local = g.pose;
  e.local_identity = g.pose.position == Vec3{} && g.pose.rotation == Mat3::identity();
  (body == 0 ? statics_ : moving_).push_back(e);
}

void RayCaster::compute_aabb(GeomEntry& e) {
  Vec3 half;
  switch (e.type) {
    case scene::ShapeType::box:
      half = abs_matrix(e.world.rotation) * e.half;
      break;
    case scene::ShapeType::sphere:
      half = {e.radius, e.radius, e.radius};
      break;
    case scene::ShapeType::cylinder:
      half = abs_matrix(e.world.rotation) * Vec3{e.radius, e.radius, e.half_length};
      break;
  }
  half += Vec3{kPad, kPad, kPad};
  e.lo = e.world.position - half;
  e.hi = e.world.position + half;
}

void RayCaster::update_moving() const {
  for (auto& e : moving_) {
    e.world = e.local_identity ? poses_[e.body] : poses_[e.body] * e.local;
    compute_aabb(e);
  }
  // Insertion sort by lo.x: nearly sorted from the previous tick, so about linear.
  for (std::size_t i = 1; i < order_.size(); ++i) {
    const std::int32_t k = order_[i];
    const double x = moving_[static_cast<std::size_t>(k)].lo.x;
    std::size_t j = i;
    for (; j > 0 && moving_[static_cast<std::size_t>(order_[j - 1])].lo.x > x; --j)
      order_[j] = order_[j - 1];
    order_[j] = k;
  }
  max_width_x_ = 0;
  for (std::size_t i = 0; i < order_.size(); ++i) {
    const GeomEntry& e = moving_[static_cast<std::size_t>(order_[i])];
    order_lo_x_[i] = e.lo.x;
    double* box = &order_box_[5 * i];
    box[0] = e.hi.x;
    box[1] = e.lo.y;
    box[2] = e.hi.y;
    box[3] = e.lo.z;
    box[4] = e.hi.z;
    max_width_x_ = std::max(max_width_x_, e.hi.x - e.lo.x);
  }
  if (fan_enabled_) {
    double* fb = fan_geom_box_.data() + 6 * statics_.size();
    for (const GeomEntry& e : moving_) {
      fb[0] = e.lo.z;
      fb[1] = e.hi.z;
      fb[2] = e.lo.x;
      fb[3] = e.hi.x;
      fb[4] = e.lo.y;
      fb[5] = e.hi.y;
      fb += 6;
    }
  }
  moving_dirty_ = false;
}

bool RayCaster::test_geom(const GeomEntry& e, const Vec3& o, const Vec3& d, double t_max,
                          RayHit& best) {
  const Mat3 rt = e.world.rotation.transposed();
  const Vec3 lo = rt * (o - e.world.position);
  const Vec3 ld = rt * d;
  double t = 0;
  Vec3 n;
  bool hit = false;
  switch (e.type) {
    case scene::ShapeType::box:
      hit = ray_box(lo, ld, e.half, t_max, t, n);
      break;
    case scene::ShapeType::sphere:
      hit = ray_sphere(lo, ld, e.radius, t_max, t, n);
      break;
    case scene::ShapeType::cylinder:
      hit = ray_cylinder(lo, ld, e.radius, e.half_length, t_max, t, n);
      break;
  }
  if (!hit || (best.hit && t >= best.distance_m)) return false;
  best.hit = true;
  best.distance_m = t;
  best.point_m = o + d * t;
  best.normal = e.world.rotation * n;
  best.body = BodyHandle{e.body};
  best.material = e.material;
  return true;
}

void RayCaster::test_planes(const Vec3& o, const Vec3& d, double t_max, RayHit& best) const {
  // Axis-aligned planes seen from their front side only: the ground (normal +Z) and the walls
  // (normals toward the origin).
  auto consider = [&](double t, const Vec3& normal) {
    if (!(t >= 0) || t > (best.hit ? best.distance_m : t_max)) return;
    best.hit = true;
    best.distance_m = t;
    best.point_m = o + d * t;
    best.normal = normal;
    best.body = BodyHandle{0};
    best.material = 0;
  };
  if (d.z < 0 && o.z >= 0) consider(-o.z / d.z, {0, 0, 1});
  if (walls_) {
    const double w = wall_distance_;
    // A ray that cannot reach x, y = ±w skips the four tests.
    const double reach_x = std::abs(o.x) + std::abs(d.x) * t_max;
    const double reach_y = std::abs(o.y) + std::abs(d.y) * t_max;
    if (reach_x < w && reach_y < w) return;
    if (d.x > 0 && o.x <= w) consider((w - o.x) / d.x, {-1, 0, 0});
    if (d.x < 0 && o.x >= -w) consider((-w - o.x) / d.x, {1, 0, 0});
    if (d.y > 0 && o.y <= w) consider((w - o.y) / d.y, {0, -1, 0});
    if (d.y < 0 && o.y >= -w) consider((-w - o.y) / d.y, {0, 1, 0});
  }
}

bool RayCaster::prepare(const Vec3& direction, double& max_distance, Vec3& unit) const {
  const double len2 = dot(direction, direction);
  if (!(len2 > 0) || !(max_distance >= 0)) return false;
  max_distance = reach(max_distance);
  // Sensors pass unit directions: skip the square root when it is one already.
  unit = std::abs(len2 - 1) < 1e-15 ? direction : direction / std::sqrt(len2);
  return true;
}

RayHit RayCaster::cast(const Vec3& origin, const Vec3& direction, double max_distance,
                       std::int32_t ignore_body) const {
  RayHit best;
  Vec3 d;
  if (!prepare(direction, max_distance, d)) return best;
  const Vec3& o = origin;
  test_planes(o, d, max_distance, best);
  auto limit = [&] { return best.hit ? best.distance_m : max_distance; };

  if (fan_enabled_ && (d.x != 0 || d.y != 0)) {
    if (!(fan_active_ && o == active_origin_)) {
      if (has_last_origin_ && o == last_origin_)
        prepare_fan(o);  // the second ray from this origin in this tick
      else {
        last_origin_ = o;
        has_last_origin_ = true;
      }
    }
    if (fan_active_ && o == active_origin_) {
      cast_fan(o, d, max_distance, ignore_body, best);
      return best;
    }
  }
  const Vec3 inv = inverse_direction(d);
  double s0 = 0, s1 = 0;
  if (statics_.size() <= kSmallStatic) {
    // A few obstacles: their packed boxes one by one, against the segment's box first, beat
    // walking a grid.
    const Vec3 end = o + d * limit();
    const double xa = std::min(o.x, end.x), xb = std::max(o.x, end.x);
    const double ya = std::min(o.y, end.y), yb = std::max(o.y, end.y);
    const double za = std::min(o.z, end.z), zb = std::max(o.z, end.z);
    const double* boxes = static_box_.data();
    const std::size_t n = statics_.size();
    for (std::size_t i = 0; i < n; ++i) {
      const double* b = boxes + 6 * i;
      if (b[5] < za || b[4] > zb || b[1] < xa || b[0] > xb || b[3] < ya || b[2] > yb) continue;
      const GeomEntry& e = statics_[i];
      if (ray_aabb(o, inv, e.lo, e.hi, limit(), s0, s1)) test_geom(e, o, d, limit(), best);
    }
  } else {
    // Static obstacles: walk the grid cells the ray's XY projection crosses.
    double t0 = 0, t1 = limit();
    const double gx1 = grid_x0_ + nx_ * cell_, gy1 = grid_y0_ + ny_ * cell_;
    bool inside = true;
    auto clip = [&](double oi, double di, double lo, double hi) {
      if (di == 0) {
        if (oi < lo || oi > hi) inside = false;
        return;
      }
      double enter = (lo - oi) / di, leave = (hi - oi) / di;
      if (enter > leave) std::swap(enter, leave);
      t0 = std::max(t0, enter);
      t1 = std::min(t1, leave);
    };
    clip(o.x, d.x, grid_x0_, gx1);
    clip(o.y, d.y, grid_y0_, gy1);
    if (inside && t0 <= t1) {
      if (++cast_id_ == 0) {  // wrapped: clear the mailboxes
        std::fill(stamp_.begin(), stamp_.end(), 0u);
        cast_id_ = 1;
      }
      const double px = o.x + d.x * t0, py = o.y + d.y * t0;
      int ix = std::clamp(static_cast<int>(std::floor((px - grid_x0_) / cell_)), 0, nx_ - 1);
      int iy = std::clamp(static_cast<int>(std::floor((py - grid_y0_) / cell_)), 0, ny_ - 1);
      const int step_x = d.x > 0 ? 1 : -1, step_y = d.y > 0 ? 1 : -1;
      double next_x = d.x > 0   ? (grid_x0_ + (ix + 1) * cell_ - o.x) / d.x
                      : d.x < 0 ? (grid_x0_ + ix * cell_ - o.x) / d.x
                                : kInf;
      double next_y = d.y > 0   ? (grid_y0_ + (iy + 1) * cell_ - o.y) / d.y
                      : d.y < 0 ? (grid_y0_ + iy * cell_ - o.y) / d.y
                                : kInf;
      const double dx = d.x != 0 ? cell_ / std::abs(d.x) : kInf;
      const double dy = d.y != 0 ? cell_ / std::abs(d.y) : kInf;
      for (;;) {
        const auto c = static_cast<std::size_t>(iy * nx_ + ix);
        for (std::int32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
          const auto g = static_cast<std::size_t>(cell_items_[static_cast<std::size_t>(k)]);
          if (stamp_[g] == cast_id_) continue;
          stamp_[g] = cast_id_;
          const GeomEntry& e = statics_[g];
          if (ray_aabb(o, inv, e.lo, e.hi, limit(), s0, s1)) test_geom(e, o, d, limit(), best);
        }
        const double cell_exit = std::min({next_x, next_y, t1});
        if ((best.hit && best.distance_m <= cell_exit) || cell_exit >= t1) break;
        if (next_x < next_y) {
          ix += step_x;
          next_x += dx;
        } else {
          iy += step_y;
          next_y += dy;
        }
        if (ix < 0 || ix >= nx_ || iy < 0 || iy >= ny_) break;
      }
    }
  }

  // Moving geoms: sweep along x.
  if (!moving_.empty()) {
    if (moving_dirty_) update_moving();
    const double t_lim = limit();
    const double xa = std::min(o.x, o.x + d.x * t_lim), xb = std::max(o.x, o.x + d.x * t_lim);
    const double ya = std::min(o.y, o.y + d.y * t_lim), yb = std::max(o.y, o.y + d.y * t_lim);
    const double za = std::min(o.z, o.z + d.z * t_lim), zb = std::max(o.z, o.z + d.z * t_lim);
    // Locals, not members: test_geom() writes memory, which would make the compiler reload
    // every member pointer on every iteration.
    const double* lo_x = order_lo_x_.data();
    const double* boxes = order_box_.data();
    const std::int32_t* order = order_.data();
    const std::size_t n = order_.size();
    // A binary search pays off only past a few dozen geoms.
    std::size_t i =
        n <= 32
            ? 0
            : static_cast<std::size_t>(std::lower_bound(lo_x, lo_x + n, xa - max_width_x_) - lo_x);
    for (; i < n && lo_x[i] <= xb; ++i) {
      // The segment's bounding box against the packed boxes first, then the slab test.
      const double* box = boxes + 5 * i;
      // z first: most sensors look across the floor, where heights sort geoms out best.
      if (box[3] > zb || box[4] < za || box[0] < xa || box[1] > yb || box[2] < ya) continue;
      const GeomEntry& e = moving_[static_cast<std::size_t>(order[i])];
      if (ignore_body > 0 && e.body == ignore_body) continue;
      if (!ray_aabb(o, inv, e.lo, e.hi, limit(), s0, s1)) continue;
      test_geom(e, o, d, limit(), best);
    }
  }
  return best;
}

void RayCaster::prepare_fan(const Vec3& o) const {
  if (moving_dirty_) update_moving();
  bool keep = fan_valid_ && std::abs(o.x - fan_origin_.x) <= kFanOriginMargin &&
              std::abs(o.y - fan_origin_.y) <= kFanOriginMargin;
  const double* box = fan_box_.data();
  for (std::size_t i = 0, n = moving_.size(); keep && i < n; ++i) {
    const GeomEntry& e = moving_[i];
    const double* b = box + 4 * i;
    keep = e.lo.x >= b[0] - kFanGeomMargin && e.hi.x <= b[1] + kFanGeomMargin &&
           e.lo.y >= b[2] - kFanGeomMargin && e.hi.y <= b[3] + kFanGeomMargin;
  }
  if (!keep) build_fan(o);
  fan_active_ = true;
  active_origin_ = o;
}

void RayCaster::build_fan(const Vec3& o) const {
  const std::size_t n_static = statics_.size(), total = n_static + moving_.size();
  constexpr double kEps = 1e-9;
  std::fill(fan_start_.begin(), fan_start_.end(), 0);
  auto sector = [](double a) {
    a = a < 0 ? a + 4 : (a >= 4 ? a - 4 : a);
    return std::min(kFanSectors - 1, static_cast<int>(a * (kFanSectors / 4.0)));
  };
  for (std::size_t g = 0; g < total; ++g) {
    const GeomEntry& e = g < n_static ? statics_[g] : moving_[g - n_static];
    int first = 0, last = kFanSectors - 1;  // the whole circle unless narrowed below
    double m = kFanOriginMargin;
    if (g >= n_static) {
      double* b = &fan_box_[4 * (g - n_static)];
      b[0] = e.lo.x;
      b[1] = e.hi.x;
      b[2] = e.lo.y;
      b[3] = e.hi.y;
      m += kFanGeomMargin;
    }
    const double x0 = e.lo.x - m - o.x, x1 = e.hi.x + m - o.x;
    const double y0 = e.lo.y - m - o.y, y1 = e.hi.y + m - o.y;
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
  const std::size_t n_static = statics_.size();
  const std::int32_t* items = fan_items_.data();
  const std::int32_t a = fan_start_[static_cast<std::size_t>(k)];
  const std::int32_t b = fan_start_[static_cast<std::size_t>(k) + 1];
  double s0 = 0, s1 = 0;
  // The segment's bounding box (z first) before the slab test, as in the sweep.
  const Vec3 end = o + d * (best.hit ? best.distance_m : max_distance);
  const double xa = std::min(o.x, end.x), xb = std::max(o.x, end.x);
  const double ya = std::min(o.y, end.y), yb = std::max(o.y, end.y);
  const double za = std::min(o.z, end.z), zb = std::max(o.z, end.z);
  // The packed boxes first; the entry, and the inverse direction of the slab test, only for
  // the geoms the segment's box meets.
  const double* boxes = fan_geom_box_.data();
  const GeomEntry* statics = statics_.data();
  const GeomEntry* moving = moving_.data();
  Vec3 inv;
  bool have_inv = false;
  for (std::int32_t i = a; i < b; ++i) {
    const auto g = static_cast<std::size_t>(items[i]);
    const double* box = boxes + 6 * g;
    if (box[0] > zb || box[1] < za || box[2] > xb || box[3] < xa || box[4] > yb || box[5] < ya)
      continue;
    const GeomEntry& e = g < n_static ? statics[g] : moving[g - n_static];
    if (g >= n_static && ignore_body > 0 && e.body == ignore_body) continue;
    if (!have_inv) {
      inv = inverse_direction(d);
      have_inv = true;
    }
    const double t_lim = best.hit ? best.distance_m : max_distance;
    if (!ray_aabb(o, inv, e.lo, e.hi, t_lim, s0, s1)) continue;
    test_geom(e, o, d, t_lim, best);
  }
}

RayHit RayCaster::cast_brute_force(const Vec3& origin, const Vec3& direction, double max_distance,
                                   std::int32_t ignore_body) const {
  RayHit best;
  Vec3 d;
  if (!prepare(direction, max_distance, d)) return best;
  test_planes(origin, d, max_distance, best);
  if (moving_dirty_) update_moving();
  for (const auto& e : statics_)
    test_geom(e, origin, d, best.hit ? best.distance_m : max_distance, best);
  for (const auto& e : moving_)
    if (!(ignore_body > 0 && e.body == ignore_body))
      test_geom(e, origin, d, best.hit ? best.distance_m : max_distance, best);
  return best;
}

RayHit RayCaster::callback(const void* kernel, const Vec3& origin, const Vec3& direction,
                           double max_distance, std::int32_t ignore_body) {
  return static_cast<const RayCaster*>(kernel)->cast(origin, direction, max_distance, ignore_body);
}

}  // namespace s2sim::raycast
