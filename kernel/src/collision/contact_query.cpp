#include "collision/contact_query.hpp"

#include "collision/contact_primitives.hpp"

#include <cmath>

namespace s2sim::collision {

ContactQuery::ContactQuery(const ShapeTable& table) : count_(table.size()) {
  broad_phase_.resize(count_);
  pairs_.reserve(64 + 16 * static_cast<std::size_t>(count_));
}

void ContactQuery::reset() {
  broad_phase_.resize(count_);
}

int ContactQuery::plane_points(const ShapeTable& table, const Placement& placement, std::int32_t s,
                               std::int32_t p, ContactPoint* out) {
  const Aabb& box = placement.boxes()[s];
  const Plane& plane = table.planes()[static_cast<std::size_t>(p)];
  const Vec3 center = (box.min + box.max) * 0.5, half = (box.max - box.min) * 0.5;
  const double reach = std::abs(plane.normal.x) * half.x + std::abs(plane.normal.y) * half.y +
                       std::abs(plane.normal.z) * half.z;
  if (dot(plane.normal, center) - reach >= plane.offset_m) return 0;
  return plane_contacts(table.shapes()[static_cast<std::size_t>(s)], placement.world()[s], plane,
                        out);
}

const std::vector<std::pair<std::int32_t, std::int32_t>>& ContactQuery::overlapping_pairs(
    const Placement& placement) {
  broad_phase_.find_pairs(placement.boxes(), pairs_);
  return pairs_;
}

int ContactQuery::pair_points(const ShapeTable& table, const Placement& placement, std::int32_t a,
                              std::int32_t b, ContactPoint* out, bool& renumbered) {
  const Shape& sa = table.shapes()[static_cast<std::size_t>(a)];
  const Shape& sb = table.shapes()[static_cast<std::size_t>(b)];
  const Pose& pa = placement.world()[a];
  const Pose& pb = placement.world()[b];
  renumbered = false;
  if (sa.kind == ShapeKind::sphere && sb.kind == ShapeKind::sphere)
    return sphere_sphere(sa.radius_m, pa.position, sb.radius_m, pb.position, out);
  if (sa.kind == ShapeKind::sphere && sb.kind == ShapeKind::box)
    return sphere_box(sa.radius_m, pa.position, sb.half_extents_m, pb, out);
  if (sa.kind == ShapeKind::box && sb.kind == ShapeKind::sphere) {
    const int n = sphere_box(sb.radius_m, pb.position, sa.half_extents_m, pa, out);
    swap_roles(out, n);
    return n;
  }
  renumbered = true;
  return fcl_.collide(sa, pa, sb, pb, out);
}

}  // namespace s2sim::collision
