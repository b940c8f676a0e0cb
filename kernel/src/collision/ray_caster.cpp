#include "collision/ray_caster.hpp"

#include "collision/ray_primitives.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace s2sim::collision {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPad = 1e-9;              // box padding against round-off on cell and box edges
constexpr std::size_t kSmallStatic = 16;   // up to this many obstacles: no grid walk
constexpr std::size_t kFanMaxGeoms = 256;  // fan culling up to this many geoms

Vec3 inverse_direction(const Vec3& d) {
  return {d.x != 0 ? 1 / d.x : kInf, d.y != 0 ? 1 / d.y : kInf, d.z != 0 ? 1 / d.z : kInf};
}

/// A surface exactly at the ray's end counts: round-off must not decide whether a wall at
/// the beam length is seen.
double reach(double max_distance) {
  return max_distance * (1 + 1e-12) + 1e-12;
}

/// Normalises a ray's direction into `unit` and clips `max_distance` to the world's reach;
/// false for a zero direction or a negative distance (no hit).
bool prepare(const Vec3& direction, double& max_distance, Vec3& unit) {
  const double len2 = dot(direction, direction);
  if (!(len2 > 0) || !(max_distance >= 0)) return false;
  max_distance = reach(max_distance);
  // Sensors pass unit directions: skip the square root when it is one already.
  unit = std::abs(len2 - 1) < 1e-15 ? direction : direction / std::sqrt(len2);
  return true;
}

void pack(double* out, double a, double b, double c, double d, double e, double f) {
  out[0] = a;
  out[1] = b;
  out[2] = c;
  out[3] = d;
  out[4] = e;
  out[5] = f;
}

}  // namespace

RayCaster::RayCaster(const ShapeTable& table, const Pose* poses)
    : table_(table),
      poses_(poses),
      statics_(table.statics().data()),
      moving_(table.moving().data()),
      n_static_(table.statics().size()),
      n_moving_(table.moving().size()),
      placement_(table, kPad),
      parked_shape_(static_cast<std::size_t>(table.size()), 0) {
  const Aabb* boxes = placement_.boxes();
  std::vector<Aabb> static_boxes;
  for (std::size_t k = 0; k < n_static_; ++k) {
    const Aabb& b = boxes[statics_[k]];
    static_boxes.push_back(b);
    static_box_.insert(static_box_.end(), {b.min.x, b.max.x, b.min.y, b.max.y, b.min.z, b.max.z});
  }
  grid_ = StaticGrid(static_boxes);
  stamp_.assign(n_static_, 0);

  const std::size_t total = n_static_ + n_moving_;
  fan_enabled_ = n_static_ <= kSmallStatic && total > 0 && total <= kFanMaxGeoms;
  if (fan_enabled_) {
    fan_start_.assign(kFanSectors + 1, 0);
    fan_items_.assign(kFanSectors * total, 0);
    fan_first_.assign(total, 0);
    fan_last_.assign(total, 0);
    fan_box_.assign(4 * n_moving_, 0.0);
    fan_geom_box_.assign(6 * total, 0.0);
    fan_shape_.assign(statics_, statics_ + n_static_);
    fan_shape_.insert(fan_shape_.end(), moving_, moving_ + n_moving_);
    for (std::size_t g = 0; g < n_static_; ++g) {
      const Aabb& b = boxes[statics_[g]];
      pack(&fan_geom_box_[6 * g], b.min.z, b.max.z, b.min.x, b.max.x, b.min.y, b.max.y);
    }
  }
  order_.resize(n_moving_);
  for (std::size_t i = 0; i < order_.size(); ++i)
    order_[i] = static_cast<std::int32_t>(i);
  order_lo_x_.assign(n_moving_, 0.0);
  order_box_.assign(5 * n_moving_, 0.0);
}

void RayCaster::update_moving() {
  placement_.update(table_, poses_);
  const Aabb* boxes = placement_.boxes();
  // Insertion sort by lo.x: nearly sorted from the previous tick, so about linear.
  for (std::size_t i = 1; i < order_.size(); ++i) {
    const std::int32_t k = order_[i];
    const double x = boxes[moving_[k]].min.x;
    std::size_t j = i;
    for (; j > 0 && boxes[moving_[order_[j - 1]]].min.x > x; --j)
      order_[j] = order_[j - 1];
    order_[j] = k;
  }
  max_width_x_ = 0;
  for (std::size_t i = 0; i < order_.size(); ++i) {
    const Aabb& b = boxes[moving_[order_[i]]];
    order_lo_x_[i] = b.min.x;
    double* box = &order_box_[5 * i];
    box[0] = b.max.x;
    box[1] = b.min.y;
    box[2] = b.max.y;
    box[3] = b.min.z;
    box[4] = b.max.z;
    max_width_x_ = std::max(max_width_x_, b.max.x - b.min.x);
  }
  if (fan_enabled_) {
    double* fb = fan_geom_box_.data() + 6 * n_static_;
    for (std::size_t k = 0; k < n_moving_; ++k, fb += 6) {
      const Aabb& b = boxes[moving_[k]];
      pack(fb, b.min.z, b.max.z, b.min.x, b.max.x, b.min.y, b.max.y);
    }
  }
  moving_dirty_ = false;
}

bool RayCaster::test_shape(std::int32_t s, const Vec3& o, const Vec3& d, double t_max,
                           RayHit& best) const {
  if (parked_shape_[static_cast<std::size_t>(s)]) return false;
  const Pose& world = placement_.world()[s];
  const Shape& shape = table_.shapes()[static_cast<std::size_t>(s)];
  const Mat3 rt = world.rotation.transposed();
  const Vec3 lo = rt * (o - world.position);
  const Vec3 ld = rt * d;
  double t = 0;
  Vec3 n;
  bool hit = false;
  switch (shape.kind) {
    case ShapeKind::box:
      hit = ray_box(lo, ld, shape.half_extents_m, t_max, t, n);
      break;
    case ShapeKind::sphere:
      hit = ray_sphere(lo, ld, shape.radius_m, t_max, t, n);
      break;
    case ShapeKind::cylinder:
      hit = ray_cylinder(lo, ld, shape.radius_m, shape.half_length_m, t_max, t, n);
      break;
    case ShapeKind::convex:
      hit = ray_convex(lo, ld, *shape.hull, t_max, t, n);
      break;
  }
  if (!hit || (best.hit && t >= best.distance_m)) return false;
  best.hit = true;
  best.distance_m = t;
  best.point_m = o + d * t;
  best.normal = world.rotation * n;
  best.body = BodyHandle{table_.bodies()[static_cast<std::size_t>(s)]};
  best.material = table_.materials()[static_cast<std::size_t>(s)];
  return true;
}

void RayCaster::test_planes(const Vec3& o, const Vec3& d, double t_max, RayHit& best) const {
  // The table's planes are the ground (normal +Z) and the walls (normals toward the origin),
  // axis-aligned and seen from their front side only: tested here axis by axis.
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
  if (table_.walls()) {
    const double w = table_.wall_distance_m();
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

RayHit RayCaster::cast(const Vec3& origin, const Vec3& direction, double max_distance,
                       std::int32_t ignore_body) {
  RayHit best;
  Vec3 d;
  if (!prepare(direction, max_distance, d)) return best;
  const Vec3& o = origin;
  test_planes(o, d, max_distance, best);
  if (use_fan(o, d)) {
    cast_fan(o, d, max_distance, ignore_body, best);
    return best;
  }
  const Vec3 inv = inverse_direction(d);
  cast_statics(o, d, inv, max_distance, best);
  if (n_moving_ > 0) cast_moving(o, d, inv, max_distance, ignore_body, best);
  return best;
}

void RayCaster::cast_statics(const Vec3& o, const Vec3& d, const Vec3& inv, double max_distance,
                             RayHit& best) {
  auto limit = [&] { return best.hit ? best.distance_m : max_distance; };
  const Aabb* boxes = placement_.boxes();
  double s0 = 0, s1 = 0;
  if (n_static_ <= kSmallStatic) {
    // A few obstacles: their packed boxes one by one, against the segment's box first, beat
    // walking a grid.
    const Vec3 end = o + d * limit();
    const double xa = std::min(o.x, end.x), xb = std::max(o.x, end.x);
    const double ya = std::min(o.y, end.y), yb = std::max(o.y, end.y);
    const double za = std::min(o.z, end.z), zb = std::max(o.z, end.z);
    const double* packed = static_box_.data();
    for (std::size_t i = 0; i < n_static_; ++i) {
      const double* b = packed + 6 * i;
      if (b[5] < za || b[4] > zb || b[1] < xa || b[0] > xb || b[3] < ya || b[2] > yb) continue;
      const std::int32_t s = statics_[i];
      if (ray_aabb(o, inv, boxes[s].min, boxes[s].max, limit(), s0, s1))
        test_shape(s, o, d, limit(), best);
    }
    return;
  }
  // Walk the grid cells the ray's XY projection crosses.
  if (++cast_id_ == 0) {  // wrapped: clear the mailboxes
    std::fill(stamp_.begin(), stamp_.end(), 0u);
    cast_id_ = 1;
  }
  grid_.walk(
      o, d, limit(),
      [&](std::int32_t k) {
        if (stamp_[static_cast<std::size_t>(k)] == cast_id_) return;
        stamp_[static_cast<std::size_t>(k)] = cast_id_;
        const std::int32_t s = statics_[k];
        if (ray_aabb(o, inv, boxes[s].min, boxes[s].max, limit(), s0, s1))
          test_shape(s, o, d, limit(), best);
      },
      [&] { return best.hit ? best.distance_m : kInf; });
}

void RayCaster::cast_moving(const Vec3& o, const Vec3& d, const Vec3& inv, double max_distance,
                            std::int32_t ignore_body, RayHit& best) {
  if (moving_dirty_) update_moving();
  auto limit = [&] { return best.hit ? best.distance_m : max_distance; };
  const double t_lim = limit();
  const double xa = std::min(o.x, o.x + d.x * t_lim), xb = std::max(o.x, o.x + d.x * t_lim);
  const double ya = std::min(o.y, o.y + d.y * t_lim), yb = std::max(o.y, o.y + d.y * t_lim);
  const double za = std::min(o.z, o.z + d.z * t_lim), zb = std::max(o.z, o.z + d.z * t_lim);
  // Locals, not members: test_shape() writes memory, which would make the compiler reload
  // every member pointer on every iteration.
  const double* lo_x = order_lo_x_.data();
  const double* packed = order_box_.data();
  const std::int32_t* order = order_.data();
  const std::int32_t* moving = moving_;
  const std::int32_t* body = table_.bodies().data();
  const Aabb* boxes = placement_.boxes();
  const std::size_t n = order_.size();
  double s0 = 0, s1 = 0;
  // A binary search pays off only past a few dozen geoms.
  std::size_t i =
      n <= 32
          ? 0
          : static_cast<std::size_t>(std::lower_bound(lo_x, lo_x + n, xa - max_width_x_) - lo_x);
  for (; i < n && lo_x[i] <= xb; ++i) {
    // The segment's bounding box against the packed boxes first, then the slab test.
    const double* box = packed + 5 * i;
    // z first: most sensors look across the floor, where heights sort geoms out best.
    if (box[3] > zb || box[4] < za || box[0] < xa || box[1] > yb || box[2] < ya) continue;
    const std::int32_t s = moving[order[i]];
    if (ignore_body > 0 && body[s] == ignore_body) continue;
    if (!ray_aabb(o, inv, boxes[s].min, boxes[s].max, limit(), s0, s1)) continue;
    test_shape(s, o, d, limit(), best);
  }
}

RayHit RayCaster::cast_brute_force(const Vec3& origin, const Vec3& direction, double max_distance,
                                   std::int32_t ignore_body) {
  RayHit best;
  Vec3 d;
  if (!prepare(direction, max_distance, d)) return best;
  test_planes(origin, d, max_distance, best);
  if (moving_dirty_) update_moving();
  const std::int32_t* body = table_.bodies().data();
  for (std::size_t k = 0; k < n_static_; ++k)
    test_shape(statics_[k], origin, d, best.hit ? best.distance_m : max_distance, best);
  for (std::size_t k = 0; k < n_moving_; ++k)
    if (!(ignore_body > 0 && body[moving_[k]] == ignore_body))
      test_shape(moving_[k], origin, d, best.hit ? best.distance_m : max_distance, best);
  return best;
}

RayHit RayCaster::callback(const void* kernel, const Vec3& origin, const Vec3& direction,
                           double max_distance, std::int32_t ignore_body) {
  // The kernel hands its own caster, a non-const object, through the SDK's `const void*`.
  return static_cast<RayCaster*>(const_cast<void*>(kernel))
      ->cast(origin, direction, max_distance, ignore_body);
}

}  // namespace s2sim::collision
