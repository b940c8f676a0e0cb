#pragma once
/// \file
/// Puts a broad phase's pairs (i, j), i < j, in increasing order whatever the order they were
/// found in, so that forces are summed in the same order whatever the history (a restored
/// snapshot repeats the run bit for bit).

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace s2sim::collision {

class PairSorter {
 public:
  using Pairs = std::vector<std::pair<std::int32_t, std::int32_t>>;
  /// Pairs of `count` boxes; reserves for `pairs` of them.
  void reserve(int count, std::size_t pairs);
  /// Sorts by (i, j): a counting sort on i, then each i's few j in place; fewer pairs than
  /// an eighth of the boxes directly. Allocates only when more pairs come than ever before.
  void sort(Pairs& pairs);

 private:
  int count_ = 0;
  std::vector<std::uint32_t> first_of_;  // where each i's pairs start
  Pairs sorted_;
};

}  // namespace s2sim::collision
