#pragma once
/// \file
/// Sweep and prune: the overlapping pairs among axis-aligned boxes. The proxies stay sorted
/// along the sweep axis between calls and are re-sorted by insertion, which is linear when
/// objects move a little per step; the first sort is N log N. The sweep axis is the one along
/// which the boxes spread most.

#include <s2sim/math.hpp>

#include <cstdint>
#include <utility>
#include <vector>

namespace s2sim::contact {

struct Aabb {
  Vec3 min, max;
};

class BroadPhase {
 public:
  /// `count` proxies; reserves every buffer once.
  void resize(int count);
  /// Pairs (i, j), i < j, whose boxes overlap, in increasing order; `out` is cleared first.
  /// Allocates only when more pairs overlap than ever before.
  void find_pairs(const Aabb* boxes, std::vector<std::pair<std::int32_t, std::int32_t>>& out);

 private:
  std::vector<std::int32_t> order_;
  int axis_ = 0;
};

}  // namespace s2sim::contact
