#pragma once
/// \file
/// The broad phase: the overlapping pairs among axis-aligned boxes, by a uniform grid kept in
/// a sorted array (no hash table, no allocation once warm). The cell is as large as the
/// boxes up to the 90th percentile of size, so each such box touches at most 8 cells; larger
/// boxes (long obstacles, belts) are tested against every box. Sorting the cell entries makes
/// it N log N as objects are added, whatever their layout (a sweep-and-prune degrades to
/// N^1.5 on a floor covered with objects). A few dozen boxes are simply tested pairwise.

#include "collision/shape.hpp"

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace s2sim::collision {

class BroadPhase {
 public:
  /// `count` proxies; reserves every buffer once.
  void resize(int count);
  /// Pairs (i, j), i < j, whose boxes overlap, in increasing order; `out` is cleared first.
  /// Allocates only when more pairs overlap than ever before. Stops, returning false, once
  /// more than `max_pairs` are found (`out` then holds max_pairs + 1 of them): boxes piled
  /// into one another would otherwise ask for memory quadratic in their number.
  bool find_pairs(const Aabb* boxes, std::vector<std::pair<std::int32_t, std::int32_t>>& out,
                  std::size_t max_pairs = SIZE_MAX);

 private:
  struct Entry {
    std::uint64_t cell;
    std::int32_t box;
  };
  int count_ = 0;
  std::vector<double> sizes_;
  std::vector<Entry> entries_;
  std::vector<std::int32_t> large_;
  std::vector<char> is_large_;
};

}  // namespace s2sim::collision
