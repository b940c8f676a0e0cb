#pragma once
/// \file
/// The contact query on placed shapes: which shapes reach a static plane and their points
/// there, which pairs of shapes have overlapping boxes (broad phase), and a pair's points
/// (narrow phase: analytic for spheres, box_box.hpp for two boxes, FCL for pairs with a
/// cylinder). The query's buffers (the broad phase's, FCL's solver) belong to the caller's
/// instance; the table is only read.

#include "collision/broad_phase.hpp"
#include "collision/contact_point.hpp"
#include "collision/contact_primitives.hpp"
#include "collision/fcl_pairs.hpp"
#include "collision/island_broad_phase.hpp"
#include "collision/placement.hpp"
#include "collision/shape_table.hpp"

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace s2sim::collision {

/// How many shape pairs may overlap at once: kMaxPairsBase + kMaxPairsPerShape per shape, far
/// above any pile that is not bodies placed into one another (docs/reliability.md, "Limits").
inline constexpr std::size_t kMaxPairsBase = 1024;
inline constexpr std::size_t kMaxPairsPerShape = 64;

/// Thrown by ContactQuery::overlapping_pairs when more shape pairs overlap than its limit:
/// `shape_a`, `shape_b` is one of them. The simulation turns it into a located runtime error.
struct TooManyPairs {
  std::size_t limit;
  std::int32_t shape_a, shape_b;
  /// The rule of the limit in words: "1024 + 64 per shape".
  static std::string rule() {
    return std::to_string(kMaxPairsBase) + " + " + std::to_string(kMaxPairsPerShape) + " per shape";
  }
};

class ContactQuery {
 public:
  /// Reserves every buffer for the table's shapes.
  explicit ContactQuery(const ShapeTable& table);

  /// Forgets what the buffers learnt (sizes back to those at load).
  void reset();

  /// Finds the pairs by islands from now on (island_broad_phase.hpp) where that pays:
  /// `island_of_shape` per shape (−1: static), `may_touch` for two shapes of one island.
  /// overlapping_pairs() then leaves out the pairs within an island that may not touch.
  void group_by_islands(const std::vector<std::int32_t>& island_of_shape,
                        const std::function<bool(std::int32_t, std::int32_t)>& may_touch);

  /// Points of shape `s` against each static plane p of the table its box reaches: calls
  /// `sink(p, points, count)` with the points written to `buffer` (kMaxPointsPerPair). With the
  /// placement's speculative margins, also the points within the shape's margin of the plane
  /// (negative depth).
  template <class Sink>
  static void plane_points(const ShapeTable& table, const Placement& placement, std::int32_t s,
                           ContactPoint* buffer, Sink&& sink);

  /// The pairs (i, j), i < j, of shapes whose boxes overlap, in increasing order (by islands:
  /// but for those group_by_islands() leaves out). Allocates
  /// only when more pairs overlap than ever before. Throws TooManyPairs past max_pairs().
  const std::vector<std::pair<std::int32_t, std::int32_t>>& overlapping_pairs(
      const Placement& placement);
  /// Whether group_by_islands() found the search by islands worth it (else the grid).
  bool by_islands() const { return by_islands_; }
  /// overlapping_pairs() among the shapes group_by_islands() was given (a part's own and the
  /// static ones, the others labelled IslandBroadPhase::kAbsent), which must have found the
  /// search by islands worth it: the same pairs, in the same order, for those shapes; when more
  /// island boxes overlap than max_pairs(), by testing every two of them instead of the grid
  /// (which holds every shape). Throws TooManyPairs as overlapping_pairs() does.
  const std::vector<std::pair<std::int32_t, std::int32_t>>& overlapping_pairs_searched(
      const Placement& placement);
  /// How many pairs may overlap at once: kMaxPairsBase + kMaxPairsPerShape per shape.
  std::size_t max_pairs() const { return max_pairs_; }

  /// Points of shape `a` against shape `b` (at most 4, written to `out`). `renumbered` is set
  /// when the narrow phase numbers its points in its own, unstable order (box-box clipping,
  /// FCL): the caller gives them stable feature ids. Points within the sum of the two shapes'
  /// speculative margins are reported with a negative depth, except for pairs with a cylinder
  /// (GJK/EPA reports touching points only).
  int pair_points(const ShapeTable& table, const Placement& placement, std::int32_t a,
                  std::int32_t b, ContactPoint* out, bool& renumbered);

 private:
  int count_ = 0;
  std::size_t max_pairs_ = 0;
  BroadPhase broad_phase_;
  IslandBroadPhase islands_;
  bool by_islands_ = false;
  std::vector<std::int32_t> searched_;  // group_by_islands(): the shapes not kAbsent, ascending
  std::vector<char> is_static_;         // per shape: labelled static (-1)
  FclPairs fcl_;
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs_;
};

template <class Sink>
void ContactQuery::plane_points(const ShapeTable& table, const Placement& placement, std::int32_t s,
                                ContactPoint* buffer, Sink&& sink) {
  const Aabb& box = placement.boxes()[s];
  const Vec3 center = (box.min + box.max) * 0.5, half = (box.max - box.min) * 0.5;
  const auto& planes = table.planes();
  for (std::size_t p = 0; p < planes.size(); ++p) {
    const Plane& plane = planes[p];
    const double reach = std::abs(plane.normal.x) * half.x + std::abs(plane.normal.y) * half.y +
                         std::abs(plane.normal.z) * half.z;
    if (dot(plane.normal, center) - reach >= plane.offset_m) continue;
    const int n = plane_contacts(table.shapes()[static_cast<std::size_t>(s)], placement.world()[s],
                                 plane, buffer, placement.margins()[s]);
    sink(static_cast<std::int32_t>(p), buffer, n);
  }
}

}  // namespace s2sim::collision
