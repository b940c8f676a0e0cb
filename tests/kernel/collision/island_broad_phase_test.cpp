// The broad phase by islands finds exactly the overlapping pairs of a full search, less the
// pairs within an island that may not touch and the static–static ones.
#include "collision/island_broad_phase.hpp"

#include <gtest/gtest.h>

#include <random>

namespace s2sim::collision {
namespace {

using Pairs = std::vector<std::pair<std::int32_t, std::int32_t>>;

bool boxes_overlap(const Aabb& a, const Aabb& b) {
  return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y &&
         a.min.z <= b.max.z && b.min.z <= a.max.z;
}

// Robots of 2–7 shapes each (their own random "may touch" pattern), loose one-shape things and
// static obstacles, shuffled through the table as a scene's shapes are; every frame they
// drift, a few jump, and some islands crowd together.
TEST(IslandBroadPhase, GivesTheFullSearchsPairsButTheExcludedOnes) {
  for (const int islands : {12, 80}) {  // the island level brute force, then on a grid
    std::mt19937 rng(static_cast<unsigned>(islands));
    std::uniform_real_distribution<double> where(-1, 1), size(0.02, 0.15), unit(0, 1);
    std::uniform_int_distribution<int> members(2, 7);
    std::vector<std::int32_t> island_of_shape;
    for (int i = 0; i < islands; ++i)
      for (int k = members(rng); k > 0; --k)
        island_of_shape.push_back(i);
    for (int k = 0; k < islands / 4; ++k)
      island_of_shape.push_back(-1);
    std::shuffle(island_of_shape.begin(), island_of_shape.end(), rng);
    const auto n = static_cast<std::int32_t>(island_of_shape.size());
    std::vector<char> touch(static_cast<std::size_t>(n * n));
    for (auto& t : touch)
      t = unit(rng) < 0.3 ? 1 : 0;
    auto may_touch = [&](std::int32_t i, std::int32_t j) {
      return touch[static_cast<std::size_t>(i * n + j)] != 0;
    };
    IslandBroadPhase search;
    ASSERT_TRUE(search.build(island_of_shape, may_touch));

    std::vector<Vec3> center(static_cast<std::size_t>(n)), half(center.size());
    std::vector<Vec3> island_center(static_cast<std::size_t>(islands));
    for (auto& c : island_center)
      c = {where(rng), where(rng), 0.2 * where(rng)};
    for (std::size_t s = 0; s < center.size(); ++s) {
      const std::int32_t i = island_of_shape[s];
      center[s] = (i < 0 ? Vec3{where(rng), where(rng), 0} : island_center[i]) +
                  Vec3{0.2 * where(rng), 0.2 * where(rng), 0.05 * where(rng)};
      half[s] = {size(rng), size(rng), size(rng)};
    }
    std::vector<Aabb> boxes(center.size());
    Pairs found;
    std::size_t total = 0;
    for (int frame = 0; frame < 60; ++frame) {
      for (std::size_t s = 0; s < center.size(); ++s) {
        if (island_of_shape[s] >= 0)
          center[s] += Vec3{0.02 * where(rng), 0.02 * where(rng), 0.01 * where(rng)};
        if (unit(rng) < 0.005) center[s] = {0.1 * where(rng), 0.1 * where(rng), 0};  // a crowd
        boxes[s] = {center[s] - half[s], center[s] + half[s]};
      }
      Pairs expected;
      for (std::int32_t i = 0; i < n; ++i)
        for (std::int32_t j = i + 1; j < n; ++j) {
          const std::int32_t a = island_of_shape[static_cast<std::size_t>(i)],
                             b = island_of_shape[static_cast<std::size_t>(j)];
          if ((a < 0 && b < 0) || (a == b && !may_touch(i, j))) continue;
          if (boxes_overlap(boxes[static_cast<std::size_t>(i)], boxes[static_cast<std::size_t>(j)]))
            expected.emplace_back(i, j);
        }
      ASSERT_EQ(search.find_pairs(boxes.data(), found), IslandBroadPhase::Found::pairs);
      ASSERT_EQ(found, expected) << islands << " islands, frame " << frame;
      total += found.size();
      if (frame == 30) search.reset();
    }
    EXPECT_GT(total, 60u) << "the scenes must overlap somewhere to test anything";
  }
}

TEST(IslandBroadPhase, IsDeclinedWhenIslandsDoNotGroupShapesOrMayAllTouch) {
  auto always = [](std::int32_t, std::int32_t) { return true; };
  IslandBroadPhase search;
  std::vector<std::int32_t> loose(100);  // a pile: one shape per island
  for (std::size_t s = 0; s < loose.size(); ++s)
    loose[s] = static_cast<std::int32_t>(s);
  EXPECT_FALSE(search.build(loose, always));
  EXPECT_FALSE(search.build(std::vector<std::int32_t>(100, 0), always))
      << "one island of 100 shapes that may all touch: 4950 pairs to test each step";
  EXPECT_TRUE(search.build(std::vector<std::int32_t>(100, 0),
                           [](std::int32_t i, std::int32_t j) { return j == i + 1; }));
}

TEST(IslandBroadPhase, SaysWhenTooManyPairsOrIslandsOverlap) {
  // 40 islands of two shapes each, all over one another: 780 pairs of islands, 40·79 = 3160
  // pairs of shapes that may touch.
  std::vector<std::int32_t> island_of_shape;
  for (int i = 0; i < 40; ++i)
    island_of_shape.insert(island_of_shape.end(), {i, i});
  IslandBroadPhase search;
  ASSERT_TRUE(search.build(island_of_shape, [](std::int32_t, std::int32_t) { return true; }));
  std::vector<Aabb> boxes(island_of_shape.size(), Aabb{{0, 0, 0}, {1, 1, 1}});
  Pairs found;
  EXPECT_EQ(search.find_pairs(boxes.data(), found, 1000), IslandBroadPhase::Found::too_many_pairs);
  EXPECT_GT(found.size(), 1000u);
  // Islands that overlap as wholes but whose shapes do not: the caller asks a grid instead.
  // Island i: one shape at x = −1, y = 0.01·i, the other at x = 1, y = 0.5 − 0.01·i, so every
  // island's box holds y = 0.25 while no two shapes meet.
  for (std::size_t s = 0; s < boxes.size(); ++s) {
    const double i = static_cast<double>(s / 2);
    const double x = s % 2 == 0 ? -1.0 : 1.0, y = s % 2 == 0 ? 0.01 * i : 0.5 - 0.01 * i;
    boxes[s] = {{x, y, 0}, {x + 0.1, y + 0.001, 0.1}};
  }
  EXPECT_EQ(search.find_pairs(boxes.data(), found, 100), IslandBroadPhase::Found::too_many_groups);
  EXPECT_EQ(search.find_pairs(boxes.data(), found), IslandBroadPhase::Found::pairs);
  EXPECT_TRUE(found.empty());
}

}  // namespace
}  // namespace s2sim::collision
