// The broad phase finds exactly the overlapping pairs that a brute-force test finds.
#include "collision/broad_phase.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace s2sim::collision {
namespace {

std::vector<std::pair<std::int32_t, std::int32_t>> brute_force(const std::vector<Aabb>& boxes) {
  std::vector<std::pair<std::int32_t, std::int32_t>> out;
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      const Aabb &a = boxes[i], &b = boxes[j];
      if (a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y &&
          a.min.z <= b.max.z && b.min.z <= a.max.z)
        out.emplace_back(static_cast<std::int32_t>(i), static_cast<std::int32_t>(j));
    }
  return out;
}

TEST(BroadPhase, MatchesBruteForceWhileObjectsMove) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> where(-1, 1), size(0.01, 0.2), step(-0.02, 0.02);
  std::vector<Aabb> boxes(300);
  for (auto& b : boxes) {
    const Vec3 c{where(rng), where(rng), 0.3 * where(rng)};
    const Vec3 h{size(rng), size(rng), size(rng)};
    b = {c - h, c + h};
  }
  BroadPhase bp;
  bp.resize(static_cast<int>(boxes.size()));
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  for (int frame = 0; frame < 50; ++frame) {
    bp.find_pairs(boxes.data(), pairs);
    ASSERT_EQ(pairs, brute_force(boxes)) << "frame " << frame;
    for (auto& b : boxes) {
      const Vec3 d{step(rng), step(rng), step(rng)};
      b.min += d;
      b.max += d;
    }
  }
}

// The grid keeps its cell and its sorted entries from call to call and re-sorts only
// the boxes that changed cells. Boxes that grow and shrink (the cell is chosen anew, some turn
// large and back), a few that jump across the scene, and a reset half way: every call still
// gives exactly the brute-force pairs.
TEST(BroadPhase, KeptCellsGiveTheSamePairsAsAFreshSearch) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> where(-1, 1), size(0.02, 0.1), step(-0.005, 0.005),
      unit(0, 1);
  const int n = 200;
  std::vector<Vec3> center(n), half(n);
  for (int i = 0; i < n; ++i) {
    center[i] = {where(rng), where(rng), 0.2 * where(rng)};
    half[i] = {size(rng), size(rng), size(rng)};
  }
  std::vector<Aabb> boxes(n);
  BroadPhase kept;
  kept.resize(n);
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs, fresh_pairs;
  for (int frame = 0; frame < 120; ++frame) {
    const double scale = 1 + 0.8 * std::sin(0.1 * frame);  // the cell must follow
    for (int i = 0; i < n; ++i) {
      center[i] += Vec3{step(rng), step(rng), step(rng)};
      if (unit(rng) < 0.01) center[i] = {where(rng), where(rng), 0.2 * where(rng)};
      const double grow = i % 23 == 0 ? 6 * scale : scale;  // a few become large
      boxes[i] = {center[i] - half[i] * grow, center[i] + half[i] * grow};
    }
    if (frame == 60) kept.resize(n);
    ASSERT_TRUE(kept.find_pairs(boxes.data(), pairs));
    ASSERT_EQ(pairs, brute_force(boxes)) << "frame " << frame;
    BroadPhase fresh;
    fresh.resize(n);
    ASSERT_TRUE(fresh.find_pairs(boxes.data(), fresh_pairs));
    ASSERT_EQ(pairs, fresh_pairs) << "frame " << frame;
  }
}

// Boxes placed into one another ask for pairs quadratic in their number; past the
// caller's limit the search stops (false) instead of growing without bound. Both paths: a few
// boxes (tested pairwise) and many (the grid).
// Fuzzer finding (CI, case pile-533): a box flung to 1e20 m made the cell index's conversion
// overflow. Far boxes share a clamped cell and are still paired only when they overlap.
TEST(BroadPhase, BoxesFarBeyondTheGridArePairedOnlyWhenTheyOverlap) {
  std::vector<Aabb> boxes;
  for (int i = 0; i < 60; ++i) {  // enough for the grid (not the brute-force path)
    const Vec3 c{0.3 * i, 0, 0}, h{0.1, 0.1, 0.1};
    boxes.push_back({c - h, c + h});
  }
  const Vec3 h{0.1, 0.1, 0.1};
  for (double far : {1e20, -1e20, 1e300}) {
    boxes.push_back({Vec3{far, 0, 0} - h, Vec3{far, 0, 0} + h});
    boxes.push_back({Vec3{far, 0.05, 0} - h, Vec3{far, 0.05, 0} + h});  // overlaps the last
    boxes.push_back({Vec3{0, far, far} - h, Vec3{0, far, far} + h});
  }
  BroadPhase bp;
  bp.resize(static_cast<int>(boxes.size()));
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  for (int frame = 0; frame < 3; ++frame) {
    bp.find_pairs(boxes.data(), pairs);
    EXPECT_EQ(pairs, brute_force(boxes)) << "frame " << frame;
  }
}

TEST(BroadPhase, StopsPastTheLimitOfPairs) {
  for (const int n : {40, 300}) {
    std::vector<Aabb> boxes(static_cast<std::size_t>(n), Aabb{{0, 0, 0}, {0.1, 0.1, 0.1}});
    BroadPhase bp;
    bp.resize(n);
    std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
    const std::size_t all = static_cast<std::size_t>(n) * (n - 1) / 2;
    EXPECT_TRUE(bp.find_pairs(boxes.data(), pairs, all)) << n;
    EXPECT_EQ(pairs.size(), all);
    EXPECT_FALSE(bp.find_pairs(boxes.data(), pairs, all - 1)) << n;
    EXPECT_EQ(pairs.size(), all);  // max_pairs + 1: the search stopped at the first one over
    EXPECT_FALSE(bp.find_pairs(boxes.data(), pairs, 10)) << n;
    EXPECT_EQ(pairs.size(), 11u);
  }
}

}  // namespace
}  // namespace s2sim::collision
