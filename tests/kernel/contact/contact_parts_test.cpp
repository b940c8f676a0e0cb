// The contact layer part by part (kernel/src/contact/contact_parts.cpp): on every substep the
// parts' results equal compute()'s to the bit, whether the substep splits or two parts' bodies
// meet and it runs whole.
#include "contact/contact_world.hpp"
#include "contact_runner.hpp"
#include "scene_builder.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

namespace s2sim::contact {
namespace {

/// Computes the whole contact for the runner and, on the same poses, a second contact world
/// part by part; counts the substeps that split and every number that differs.
struct SideBySide final : model::SubstepForces {
  SideBySide(ContactWorld& whole_world, ContactWorld& by_parts, int body_count)
      : whole(whole_world), parts(by_parts), split_wrenches(static_cast<std::size_t>(body_count)) {}

  void compute(const Pose* poses, const Twist* twists, double step_s, Wrench* wrenches,
               model::FrictionPoints* friction = nullptr) override {
    (void)friction;  // both worlds compare the force law's friction
    whole.compute(poses, twists, step_s, wrenches);
    // Placed by the parts after the first substep, as the island-parallel step does.
    if (parts.begin_parts(substeps > 0, poses, twists, step_s)) {
      for (int p = 0; p < 2; ++p)
        parts.compute_part(p, poses, twists, step_s, split_wrenches.data());
      parts.end_parts();
      ++split;
    } else {
      parts.compute(poses, twists, step_s, split_wrenches.data());
    }
    ++substeps;
    for (std::size_t b = 1; b < split_wrenches.size(); ++b)
      differing += std::memcmp(&split_wrenches[b], &wrenches[b], sizeof(Wrench)) != 0;
    const std::int32_t count = *whole.contact_count();
    if (*parts.contact_count() != count) {
      ++differing;
      return;
    }
    deepest_count = std::max(deepest_count, count);
    for (std::int32_t i = 0; i < count; ++i) {
      const ContactInfo &a = whole.contacts()[i], &b = parts.contacts()[i];
      const double va[] = {a.point_m.x, a.point_m.y, a.point_m.z, a.normal.x,  a.normal.y,
                           a.normal.z,  a.force_N.x, a.force_N.y, a.force_N.z, a.depth_m};
      const double vb[] = {b.point_m.x, b.point_m.y, b.point_m.z, b.normal.x,  b.normal.y,
                           b.normal.z,  b.force_N.x, b.force_N.y, b.force_N.z, b.depth_m};
      differing += a.body_a.index != b.body_a.index || a.body_b.index != b.body_b.index ||
                   std::memcmp(va, vb, sizeof va) != 0;
    }
    // The parts place their shapes for the next substep from the new poses, after it.
  }
  ContactWorld& whole;
  ContactWorld& parts;
  std::vector<Wrench> split_wrenches;
  int substeps = 0, split = 0, differing = 0;
  std::int32_t deepest_count = 0;
};

/// One step of `run`, then the two parts place their shapes from its poses, as the
/// island-parallel step does after its multibody stages.
void step_and_place(test::ContactRunner& run, ContactWorld& parts) {
  run.step();
  const Pose* poses = nullptr;
  const Twist* twists = nullptr;
  run.mb.current_bodies(poses, twists);
  for (int p = 0; p < 2; ++p)
    parts.place_part(p, poses, twists, 1e-3);
}

// Two stacks a metre apart, one per part, each hit by a falling box at the same instant (stops
// and held points in both parts at once), and later a box of part 0 landing on part 1's stack
// and staying there (the substeps then run whole).
TEST(ContactParts, ThePartsGiveTheWholeContactBitForBit) {
  scene::Scene s;
  const double size = 0.1;
  s.bodies.push_back(test::box("a_below", 0.5, {size, size, size}, {0, 0, size / 2}));
  s.bodies.push_back(test::box("a_above", 0.5, {size, size, size}, {0.01, 0, 1.5 * size + 0.3}));
  s.bodies.push_back(test::box("b_below", 2.0, {size, size, size}, {1, 0, size / 2}));
  s.bodies.push_back(test::box("b_above", 0.3, {size, size, size}, {1.02, 0, 1.5 * size + 0.3}));
  s.bodies.push_back(test::box("late", 0.4, {size, size, size}, {1.01, 0.01, 2.5 * size + 0.8}));
  test::ContactRunner run(s);
  ContactWorld parts(run.table, s, run.mb.apparent_mass_kg());
  parts.set_mobility(run.mb.contact_mobility());
  ASSERT_TRUE(parts.split({0, 0, 0, 1, 1, 0}, 2));
  SideBySide side(run.contacts, parts, run.mb.body_count());
  run.contact = &side;
  for (int n = 0; n < 1200; ++n)
    step_and_place(run, parts);
  EXPECT_EQ(side.differing, 0);
  EXPECT_GT(side.split, 200) << "of " << side.substeps << " substeps";
  EXPECT_GT(side.substeps - side.split, 200) << "the late box never met part 1's stack";
  EXPECT_GT(side.deepest_count, 12);
  EXPECT_NEAR(run.poses[5].position.z, 2.5 * size, 2e-3) << "the late box is not on the stack";
}

/// Two pairs of 0.1 m boxes hinged together lying on the ground, 1.5 m apart along x (bodies
/// left, right[, loose] per pair); `loose`: a loose box dropped across each hinge.
scene::Scene hinged_pairs(bool loose) {
  scene::Scene s;
  const double size = 0.1;
  for (int part = 0; part < 2; ++part) {
    const double x = 1.5 * part;
    const int first = static_cast<int>(s.bodies.size());
    s.bodies.push_back(test::box("left", 0.5, {size, size, size}, {x, 0, size / 2}));
    s.bodies.push_back(test::box("right", 0.7, {size, size, size}, {x + size, 0, size / 2}));
    if (loose)
      s.bodies.push_back(test::box("loose", 0.3, {size, size, size},
                                   {x + size / 2 + 0.01 * part, 0, 1.5 * size + 0.2}));
    s.joints.push_back(test::joint("hinge", scene::JointType::hinge, first, first + 1,
                                   {x + size / 2, 0, 0}, {0, 1, 0}));
  }
  return s;
}

// Two parts a metre and a half apart, each a pair of boxes hinged together lying on the ground
// (one island of two shapes) with a loose box dropped across the hinge: the parts' boxes never
// overlap, so each part finds its own pairs (the loose box on the hinged ones) on its own
// thread, with the whole contact's numbers.
TEST(ContactParts, EachPartFindsItsOwnPairsWhileThePartsAreApart) {
  const scene::Scene s = hinged_pairs(true);
  test::ContactRunner run(s);
  ContactWorld parts(run.table, s, run.mb.apparent_mass_kg());
  parts.set_mobility(run.mb.contact_mobility());
  ASSERT_TRUE(parts.split({0, 0, 0, 0, 1, 1, 1}, 2));
  SideBySide side(run.contacts, parts, run.mb.body_count());
  run.contact = &side;
  int pairs_between_bodies = 0;
  for (int n = 0; n < 1000; ++n) {
    step_and_place(run, parts);
    for (std::int32_t i = 0; i < *parts.contact_count(); ++i)
      pairs_between_bodies += parts.contacts()[i].body_b.index != 0;
  }
  EXPECT_EQ(side.differing, 0);
  EXPECT_EQ(side.split, side.substeps);
  EXPECT_EQ(parts.substeps_with_own_pairs(), side.substeps);
  EXPECT_GT(pairs_between_bodies, 1000) << "the loose boxes never lay on the hinged ones";
}

// Running ahead (kernel/src/sim/run_ahead.cpp): two hinged pairs of boxes 1.5 m apart along
// x, one per part (each part searching its own pairs by islands), get fences that let each
// come 45 % of the gap between their bounds closer to the other, and go anywhere sideways or
// away; a part that comes closer is told, and parts whose bounds touch get no fences.
TEST(ContactParts, EachPartIsFencedAwayFromTheOthersAndToldWhenItLeavesItsFence) {
  const scene::Scene s = hinged_pairs(false);
  const double size = 0.1;
  test::ContactRunner run(s);
  ContactWorld parts(run.table, s, run.mb.apparent_mass_kg());
  parts.set_mobility(run.mb.contact_mobility());
  ASSERT_TRUE(parts.split({0, 0, 0, 1, 1}, 2));
  SideBySide side(run.contacts, parts, run.mb.body_count());
  run.contact = &side;
  EXPECT_FALSE(parts.fence_parts()) << "before a substep ran part by part: no fences";
  step_and_place(run, parts);
  ASSERT_EQ(side.split, 1);
  const Pose* poses = nullptr;
  const Twist* twists = nullptr;
  run.mb.current_bodies(poses, twists);
  const std::vector<Pose> start(poses, poses + 5);
  std::vector<Pose> moved = start;
  auto shift_part_0 = [&](double dx, double dy = 0) {  // both its boxes
    for (int b : {1, 2}) {
      moved[static_cast<std::size_t>(b)].position.x =
          start[static_cast<std::size_t>(b)].position.x + dx;
      moved[static_cast<std::size_t>(b)].position.y =
          start[static_cast<std::size_t>(b)].position.y + dy;
    }
    parts.place_part(0, moved.data(), twists, 1e-3);
  };
  // The gap between the bounds: 1.5 m less the pair's length (0.2 m) and the shapes' margins.
  ASSERT_TRUE(parts.fence_parts());
  EXPECT_TRUE(parts.part_inside_fence(0));
  EXPECT_TRUE(parts.part_inside_fence(1));
  shift_part_0(0.5);  // towards part 1, within its reach (45 % of about 1.3 m)
  EXPECT_TRUE(parts.part_inside_fence(0));
  shift_part_0(-5.0, 3.0);  // away from it and sideways: no limit
  EXPECT_TRUE(parts.part_inside_fence(0));
  shift_part_0(0.5, -20.0);  // sideways, as close as before: still inside
  EXPECT_TRUE(parts.part_inside_fence(0));
  shift_part_0(0.7);  // past its reach: a pair with part 1 might form unseen
  EXPECT_FALSE(parts.part_inside_fence(0));
  EXPECT_TRUE(parts.part_inside_fence(1));
  shift_part_0(1.5 - 2 * size);  // the two parts' bounds overlap: no fences
  EXPECT_FALSE(parts.fence_parts());
}

}  // namespace
}  // namespace s2sim::contact
