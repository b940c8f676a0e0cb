// PairSorter (kernel/src/collision/pair_sorter.cpp): whatever order a broad phase finds its
// pairs in, they come out in increasing (i, j) order, by each of its three ways: directly for
// a few pairs among many boxes, by a counting sort on i with each i's few j sorted in place,
// and with std::sort for an i with many.
#include "collision/pair_sorter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

namespace s2sim::collision {
namespace {

/// `count` distinct pairs (i < j) of `boxes` boxes, shuffled; with `crowded` most of them on
/// box 0 (more than the insertion sort's sixteen).
PairSorter::Pairs random_pairs(int boxes, std::size_t count, bool crowded, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> box(0, boxes - 1);
  std::set<std::pair<std::int32_t, std::int32_t>> unique;
  while (unique.size() < count) {
    int i = crowded && unique.size() % 4 != 3 ? 0 : box(random);
    int j = box(random);
    if (i == j) continue;
    if (i > j) std::swap(i, j);
    unique.emplace(i, j);
  }
  PairSorter::Pairs pairs(unique.begin(), unique.end());
  std::shuffle(pairs.begin(), pairs.end(), random);
  return pairs;
}

TEST(PairSorter, GivesIncreasingOrderWhateverTheOrderFoundAndHowManyPairs) {
  struct Case {
    int boxes;
    std::size_t pairs;
    bool crowded;
  };
  // A few pairs among 400 boxes (sorted directly), as many as the boxes (counting sort, a few
  // j per i), and one box with most of them (its j by std::sort); none at all.
  for (const Case c : {Case{400, 10, false}, Case{400, 400, false}, Case{400, 300, true},
                       Case{50, 0, false}, Case{2, 1, false}}) {
    PairSorter sorter;
    sorter.reserve(c.boxes, c.pairs);
    for (unsigned seed = 1; seed <= 5; ++seed) {
      PairSorter::Pairs pairs = random_pairs(c.boxes, c.pairs, c.crowded, seed);
      PairSorter::Pairs expected = pairs;
      std::sort(expected.begin(), expected.end());
      sorter.sort(pairs);
      EXPECT_EQ(pairs, expected) << c.boxes << " boxes, " << c.pairs << " pairs, seed " << seed;
    }
  }
}

}  // namespace
}  // namespace s2sim::collision
