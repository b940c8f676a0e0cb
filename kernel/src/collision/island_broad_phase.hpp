#pragma once
/// \file
/// The broad phase by islands: shapes grouped by island (the bodies a chain of
/// joints connects, so a robot is one), found in two levels. First the islands' boxes (each
/// the union of its shapes' boxes) and the static shapes against each other, by a BroadPhase;
/// then, for each pair of overlapping islands, their shapes against each other, and within
/// each island only the shape pairs that may touch (fixed at load: different bodies not joined
/// to each other). A scene of robots costs a few box tests per robot instead of a grid of all
/// their shapes, and the pairs of one robot's joined parts, which the contact layer would drop
/// anyway, are never found.
///
/// The pairs are exactly BroadPhase's on the same boxes without the pairs within an island that
/// may not touch and without the static–static pairs, in the same increasing order
/// (`IslandBroadPhase.GivesTheFullSearchsPairsButTheExcludedOnes`).

#include "collision/broad_phase.hpp"
#include "collision/pair_sorter.hpp"
#include "collision/shape.hpp"

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace s2sim::collision {

class IslandBroadPhase {
 public:
  using Pairs = std::vector<std::pair<std::int32_t, std::int32_t>>;

  /// `island_of_shape`: per shape, its island (any non-negative label) or −1 for a static
  /// shape. `may_touch(i, j)`, i < j of one island: whether the pair is ever wanted.
  /// Returns false, and the search is not to be used, when the islands group too few shapes
  /// to pay (mostly one shape each, as in a pile of loose things) or an island has so many
  /// shapes that may touch each other that a grid of all shapes does better.
  /// A shape labelled kAbsent is not searched at all (another part's, when each part of the
  /// parallel step searches its own shapes: contact_parts.cpp).
  static constexpr std::int32_t kAbsent = -2;
  bool build(const std::vector<std::int32_t>& island_of_shape,
             const std::function<bool(std::int32_t, std::int32_t)>& may_touch);

  /// Forgets what the island level's grid learnt (as BroadPhase::resize).
  void reset();

  enum class Found {
    pairs,            ///< `out` holds the pairs
    too_many_pairs,   ///< more than `max_pairs` shape pairs overlap; `out` holds some of them
    too_many_groups,  ///< more than `max_pairs` islands' boxes overlap: ask a grid of shapes
  };
  /// The pairs (i, j), i < j, whose boxes overlap, but for those said above, in increasing
  /// order; `out` is cleared first. Stops once more than `max_pairs` are found (as
  /// BroadPhase::find_pairs), at either level (islands whose boxes overlap each other without
  /// their shapes doing so may be too many for this search, not for a grid of the shapes).
  Found find_pairs(const Aabb* boxes, Pairs& out, std::size_t max_pairs = SIZE_MAX);

 private:
  int shape_count_ = 0;
  int island_count_ = 0;                   // groups [0, island_count_) are islands
  std::vector<std::int32_t> first_shape_;  // per group: where its shapes start in shapes_
  std::vector<std::int32_t> shapes_;       // grouped: each island's shapes, then the statics
  Pairs within_;                           // the pairs within islands that may touch
  std::vector<Aabb> group_boxes_;
  BroadPhase groups_;
  Pairs group_pairs_;
  PairSorter sorter_;
};

}  // namespace s2sim::collision
