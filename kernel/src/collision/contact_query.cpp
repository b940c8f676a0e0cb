#include "collision/contact_query.hpp"

#include "collision/box_box.hpp"

namespace s2sim::collision {

ContactQuery::ContactQuery(const ShapeTable& table)
    : count_(table.size()),
      max_pairs_(kMaxPairsBase + kMaxPairsPerShape * static_cast<std::size_t>(table.size())) {
  broad_phase_.resize(count_);
  pairs_.reserve(64 + 16 * static_cast<std::size_t>(count_));
  fcl_.prepare(table.shapes());
}

void ContactQuery::reset() {
  broad_phase_.resize(count_);
  islands_.reset();
}

void ContactQuery::group_by_islands(
    const std::vector<std::int32_t>& island_of_shape,
    const std::function<bool(std::int32_t, std::int32_t)>& may_touch) {
  by_islands_ = islands_.build(island_of_shape, may_touch);
  searched_.clear();
  is_static_.assign(island_of_shape.size(), 0);
  for (std::size_t s = 0; s < island_of_shape.size(); ++s) {
    if (island_of_shape[s] == IslandBroadPhase::kAbsent) continue;
    searched_.push_back(static_cast<std::int32_t>(s));
    is_static_[s] = island_of_shape[s] < 0;
  }
}

const std::vector<std::pair<std::int32_t, std::int32_t>>& ContactQuery::overlapping_pairs_searched(
    const Placement& placement) {
  using Found = IslandBroadPhase::Found;
  const Aabb* boxes = placement.boxes();
  const Found found = islands_.find_pairs(boxes, pairs_, max_pairs_);
  if (found == Found::too_many_pairs)
    throw TooManyPairs{max_pairs_, pairs_.front().first, pairs_.front().second};
  if (found == Found::pairs) return pairs_;
  // Too many islands' boxes overlap for the search by islands: every two searched shapes, in
  // increasing order (the pairs within an island that the islands search leaves out the
  // contact layer drops as the grid's).
  pairs_.clear();
  for (std::size_t a = 0; a < searched_.size(); ++a)
    for (std::size_t b = a + 1; b < searched_.size(); ++b) {
      const std::int32_t i = searched_[a], j = searched_[b];
      if (is_static_[static_cast<std::size_t>(i)] && is_static_[static_cast<std::size_t>(j)])
        continue;
      if (!overlap(boxes[i], boxes[j])) continue;
      pairs_.emplace_back(i, j);
      if (pairs_.size() > max_pairs_) throw TooManyPairs{max_pairs_, i, j};
    }
  return pairs_;
}

const std::vector<std::pair<std::int32_t, std::int32_t>>& ContactQuery::overlapping_pairs(
    const Placement& placement) {
  using Found = IslandBroadPhase::Found;
  const Found found = by_islands_ ? islands_.find_pairs(placement.boxes(), pairs_, max_pairs_)
                                  : Found::too_many_groups;
  if (found == Found::too_many_pairs ||
      (found == Found::too_many_groups &&
       !broad_phase_.find_pairs(placement.boxes(), pairs_, max_pairs_)))
    throw TooManyPairs{max_pairs_, pairs_.front().first, pairs_.front().second};
  return pairs_;
}

int ContactQuery::pair_points(const ShapeTable& table, const Placement& placement, std::int32_t a,
                              std::int32_t b, ContactPoint* out, bool& renumbered) {
  const Shape& sa = table.shapes()[static_cast<std::size_t>(a)];
  const Shape& sb = table.shapes()[static_cast<std::size_t>(b)];
  const Pose& pa = placement.world()[a];
  const Pose& pb = placement.world()[b];
  const double margin = placement.margins()[a] + placement.margins()[b];
  renumbered = false;
  if (sa.kind == ShapeKind::sphere && sb.kind == ShapeKind::sphere)
    return sphere_sphere(sa.radius_m, pa.position, sb.radius_m, pb.position, out, margin);
  if (sa.kind == ShapeKind::sphere && sb.kind == ShapeKind::box)
    return sphere_box(sa.radius_m, pa.position, sb.half_extents_m, pb, out, margin);
  if (sa.kind == ShapeKind::box && sb.kind == ShapeKind::sphere) {
    const int n = sphere_box(sb.radius_m, pb.position, sa.half_extents_m, pa, out, margin);
    swap_roles(out, n);
    return n;
  }
  // The rest number their points by clipping order: ContactWorld matches them to its memory.
  renumbered = true;
  if (sa.kind == ShapeKind::box && sb.kind == ShapeKind::box)
    return box_box(sa.half_extents_m, pa, sb.half_extents_m, pb, out, margin);
  return fcl_.collide(sa, pa, sb, pb, out, margin);
}

}  // namespace s2sim::collision
