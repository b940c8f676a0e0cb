// The small-tree fast path (kernel/src/model/tree_dynamics.cpp) against Simbody's realize
// chain: the same accelerations to one part in 10^12, tick after tick, on trees of every
// joint the fast path takes, moving fast and loaded everywhere.
#include "fast_path_comparison.hpp"
#include "model/multibody.hpp"
#include "model_runner.hpp"
#include "scene_builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace s2sim::model {
namespace {

using scene::JointType;

/// A rover: a free, tilted chassis with an offset centre of mass; two wheels on tilted axes
/// off its centre; a slider mast carrying a two-hinge arm; a camera fixed to the mast.
scene::Scene rover() {
  scene::Scene s;
  s.bodies.push_back(test::box("chassis", 3.0, {0.4, 0.3, 0.1}, {0.1, -0.2, 0.5},
                               test::rotation_about({1, 2, 3}, 0.3)));
  s.bodies[0].com_m = {0.03, -0.01, 0.02};
  s.bodies.push_back(test::box("left", 0.05, {0.06, 0.02, 0.06}, {0.1, 0.0, 0.45}));
  s.bodies.push_back(test::box("right", 0.05, {0.06, 0.02, 0.06}, {0.1, -0.4, 0.45}));
  s.bodies[2].com_m = {0.004, 0.001, -0.002};
  s.bodies.push_back(test::box("mast", 0.4, {0.03, 0.03, 0.3}, {0.0, -0.2, 0.7}));
  s.bodies.push_back(test::box("upper", 0.3, {0.2, 0.02, 0.02}, {0.1, -0.2, 0.85}));
  s.bodies.push_back(test::box("lower", 0.2, {0.2, 0.02, 0.02}, {0.3, -0.2, 0.85},
                               test::rotation_about({0, 1, 1}, 0.5)));
  s.bodies.push_back(test::box("camera", 0.1, {0.05, 0.05, 0.05}, {0.0, -0.15, 0.86}));
  s.joints.push_back(test::joint("wl", JointType::hinge, 1, 0, {0.1, 0.0, 0.45}, {0.1, 1, 0}));
  s.joints.push_back(test::joint("wr", JointType::hinge, 0, 2, {0.1, -0.4, 0.45}, {0, 1, 0.2}));
  s.joints.push_back(test::joint("lift", JointType::slider, 3, 0, {0.0, -0.2, 0.6}, {0, 0.1, 1}));
  s.joints.push_back(test::joint("shoulder", JointType::hinge, 4, 3, {0, -0.2, 0.85}, {0, 1, 0}));
  s.joints.push_back(test::joint("elbow", JointType::hinge, 5, 4, {0.2, -0.2, 0.85}, {1, 0, 1}));
  s.joints.push_back(test::joint("mount", JointType::fixed, 6, 3, {0.0, -0.15, 0.86}));
  test::add_robot(s, "rover");
  return s;
}

/// An arm hinged to the world on a tilted axis, a slider and a wrist; and a second tree, a
/// free crate with a hinged lid.
scene::Scene arm_and_box() {
  scene::Scene s;
  s.bodies.push_back(test::box("base", 1.0, {0.1, 0.1, 0.5}, {0, 0, 1.25}));
  s.bodies.push_back(test::box("slide", 0.5, {0.3, 0.05, 0.05}, {0.2, 0, 1.5}));
  s.bodies.push_back(test::box("wrist", 0.2, {0.05, 0.05, 0.15}, {0.35, 0, 1.45},
                               test::rotation_about({1, 0, 0}, 0.2)));
  s.bodies[2].com_m = {0.01, 0.0, -0.03};
  s.joints.push_back(test::joint("turn", JointType::hinge, 0, -1, {0, 0, 1}, {0.2, 0, 1}));
  s.joints.push_back(test::joint("reach", JointType::slider, 1, 0, {0.05, 0, 1.5}, {1, 0, 0.1}));
  s.joints.push_back(test::joint("twist", JointType::hinge, 2, 1, {0.35, 0, 1.5}, {0, 1, 0}));
  test::add_robot(s, "arm");
  scene::Robot arm = s.robots.back();
  s.bodies.push_back(
      test::box("crate", 2.0, {0.2, 0.3, 0.4}, {1, 1, 2}, test::rotation_about({3, -1, 2}, 1.1)));
  s.bodies.push_back(test::box("lid", 0.3, {0.2, 0.3, 0.02}, {1, 1, 2.21}));
  s.joints.push_back(test::joint("hinge", JointType::hinge, 4, 3, {1.1, 1, 2.2}, {0, 1, 0}));
  // A second robot of the crate and its lid (add_robot takes every body given so far).
  scene::Robot crate;
  crate.id = "crate";
  crate.bodies = {3, 4};
  crate.joints = {3};
  crate.main_body = 3;
  for (int b : crate.bodies)
    s.bodies[static_cast<std::size_t>(b)].robot = 1;
  s.joints[3].robot = 1;
  s.robots = {arm, crate};
  return s;
}

/// A free body carrying a bracket welded to it, and below the bracket two hinges in a chain:
/// speeds whose body hangs from a weld (their rows of the factor skip the weld's body, which
/// has no speeds, to the free body's).
scene::Scene welded_chain() {
  scene::Scene s;
  s.bodies.push_back(
      test::box("hub", 1.5, {0.2, 0.2, 0.2}, {0, 0, 1}, test::rotation_about({1, -1, 2}, 0.4)));
  s.bodies.push_back(test::box("bracket", 0.2, {0.05, 0.05, 0.2}, {0.1, 0, 0.85}));
  s.bodies.push_back(test::box("link", 0.3, {0.25, 0.03, 0.03}, {0.25, 0, 0.75}));
  s.bodies[2].com_m = {0.02, 0.0, 0.005};
  s.bodies.push_back(test::box("tip", 0.1, {0.04, 0.04, 0.1}, {0.38, 0, 0.7}));
  s.joints.push_back(test::joint("bolt", JointType::fixed, 1, 0, {0.1, 0, 0.9}));
  s.joints.push_back(test::joint("knee", JointType::hinge, 2, 1, {0.12, 0, 0.75}, {0, 1, 0.3}));
  s.joints.push_back(test::joint("ankle", JointType::hinge, 3, 2, {0.37, 0, 0.75}, {1, 0, 0}));
  test::add_robot(s, "welded");
  return s;
}

/// Steps `scene` on the fast path and on Simbody from the same state every tick (400 ticks,
/// fast_path_comparison.hpp): each body's velocity change agrees within 1e-12 of its size.
void expect_simbodys_velocity_changes(const char* name, const scene::Scene& scene,
                                      test::FastPathTolerance tolerance = {}) {
  const double worst = test::worst_relative_difference(scene, 400, tolerance);
  std::printf("%s: worst relative difference of the velocity change %.3g\n", name, worst);
  EXPECT_LT(worst, 1e-12) << name;
}

TEST(TreeDynamics, SpeedsBelowAWeldMatchSimbodysToOnePartInATrillion) {
  expect_simbodys_velocity_changes("welded chain", welded_chain());
}

TEST(TreeDynamics, RoverAccelerationsMatchSimbodysToOnePartInATrillion) {
  expect_simbodys_velocity_changes("rover", rover());
}

TEST(TreeDynamics, WorldHingedArmAndFreeBoxMatchSimbodysToOnePartInATrillion) {
  expect_simbodys_velocity_changes("arm and box", arm_and_box());
}

/// A free, tilted hub; a shaft on a Universal joint with tilted axes (its second turning with
/// its first), a second shaft on another Universal below it, and a flap hinged to that one.
scene::Scene cardan_chain() {
  scene::Scene s;
  s.bodies.push_back(
      test::box("hub", 2.0, {0.2, 0.2, 0.2}, {0, 0, 2}, test::rotation_about({2, 1, -1}, 0.35)));
  s.bodies.push_back(test::box("shaft", 0.5, {0.05, 0.05, 0.4}, {0, 0, 1.7}));
  s.bodies[1].com_m = {0.01, -0.005, 0.02};
  s.bodies.push_back(test::box("second", 0.3, {0.04, 0.04, 0.3}, {0.02, 0, 1.35},
                               test::rotation_about({1, 0, 0}, 0.2)));
  s.bodies.push_back(test::box("flap", 0.1, {0.1, 0.01, 0.08}, {0.08, 0, 1.2}));
  auto u1 = test::joint("u1", JointType::universal, 1, 0, {0, 0, 1.9}, {1, 0.2, 0});
  u1.axis2 = {0, 1, 0.3};
  auto u2 = test::joint("u2", JointType::universal, 2, 1, {0.01, 0, 1.5}, {0.3, 1, 0});
  u2.axis2 = {1, 0, 0.4};
  s.joints.push_back(u1);
  s.joints.push_back(u2);
  s.joints.push_back(test::joint("flap", JointType::hinge, 3, 2, {0.04, 0, 1.22}, {0, 0.2, 1}));
  test::add_robot(s, "cardan");
  return s;
}

TEST(TreeDynamics, UniversalJointsMatchSimbodysToOnePartInATrillion) {
  // Under the loads the flap spins to -120 rad, where one unit in the last place of its angle
  // is 1.4e-14: the poses of its body agree to a few of those.
  test::FastPathTolerance tolerance;
  tolerance.pose = 1e-13;
  expect_simbodys_velocity_changes("cardan chain", cardan_chain(), tolerance);
}

/// A free, tilted hub; an arm on a Ball joint off its centre of mass, a forearm on a second
/// Ball, and a hinge below: quaternion coordinates whose rates are Simbody's.
scene::Scene ball_chain() {
  scene::Scene s;
  s.bodies.push_back(
      test::box("hub", 2.0, {0.2, 0.2, 0.2}, {0, 0, 2}, test::rotation_about({-1, 2, 1}, 0.5)));
  s.bodies.push_back(test::box("arm", 0.5, {0.05, 0.05, 0.4}, {0.05, 0, 1.7},
                               test::rotation_about({0, 1, 0}, 0.3)));
  s.bodies[1].com_m = {0.01, 0.02, -0.01};
  s.bodies.push_back(test::box("forearm", 0.3, {0.04, 0.04, 0.3}, {0.1, 0, 1.35}));
  s.bodies.push_back(test::box("hand", 0.1, {0.08, 0.02, 0.06}, {0.1, 0.03, 1.18}));
  s.joints.push_back(test::joint("shoulder", JointType::ball, 1, 0, {0.02, 0, 1.9}));
  s.joints.push_back(test::joint("elbow", JointType::ball, 2, 1, {0.08, 0, 1.5}));
  s.joints.push_back(test::joint("wrist", JointType::hinge, 3, 2, {0.1, 0.01, 1.2}, {0, 1, 0.5}));
  test::add_robot(s, "balls");
  return s;
}

TEST(TreeDynamics, BallJointsMatchSimbodysToOnePartInATrillion) {
  expect_simbodys_velocity_changes("ball chain", ball_chain());
}

/// Per tick from the same state under the same loads, the joint reactions of the fast path
/// (TreeDynamics::reactions) against Simbody's (calcMobilizerReactionForces): the worst
/// difference relative to 1 N (N·m) plus the reaction's size.
double worst_reaction_difference(const scene::Scene& s, int ticks) {
  test::FastAndSimbody runs(s);
  test::Runner &fast = runs.fast, &simbody = runs.simbody;
  for (test::Runner* r : {&fast, &simbody})
    r->mb.request_joint_reactions();
  EXPECT_TRUE(fast.mb.uses_tree_fast_path()) << "joint reactions keep the fast path";
  double worst = 0, largest = 0;
  for (int tick = 0; tick < ticks; ++tick) {
    runs.sync();
    for (test::Runner* r : {&fast, &simbody})
      test::load_everywhere(r->mb, tick);
    fast.step();
    simbody.step();
    for (std::size_t j = 0; j < s.joints.size(); ++j) {
      const Wrench &f = fast.mb.joint_reactions()[j], &g = simbody.mb.joint_reactions()[j];
      const double size = std::max(norm(g.force_N), norm(g.torque_Nm));
      const double differs = std::max(norm(f.force_N - g.force_N), norm(f.torque_Nm - g.torque_Nm));
      worst = std::max(worst, differs / (1 + size));
      largest = std::max(largest, size);
    }
  }
  EXPECT_GT(largest, 1.0) << "the joints must carry loads";
  return worst;
}

/// A free base with a carriage on a slider whose child is the joint's body 2 (its reaction is
/// reported on body 1, the base, moved from M's origin to F's as the carriage travels), and a
/// flap hinged to the carriage the same way round.
scene::Scene reversed_slider() {
  scene::Scene s;
  s.bodies.push_back(
      test::box("base", 1.0, {0.4, 0.1, 0.1}, {0, 0, 1}, test::rotation_about({0, 1, 2}, 0.3)));
  s.bodies.push_back(test::box("carriage", 0.3, {0.1, 0.08, 0.05}, {0.05, 0, 1.08}));
  s.bodies[1].com_m = {0.01, 0.005, 0.0};
  s.bodies.push_back(test::box("flap", 0.1, {0.02, 0.1, 0.06}, {0.12, 0, 1.1}));
  s.joints.push_back(test::joint("rail", JointType::slider, 0, 1, {0.05, 0, 1.05}, {1, 0.1, 0}));
  s.joints.push_back(test::joint("flap", JointType::hinge, 1, 2, {0.1, 0, 1.1}, {0, 1, 0.2}));
  test::add_robot(s, "slide");
  return s;
}

TEST(TreeDynamics, JointReactionsOnTheFastPathMatchSimbodys) {
  // Every joint kind: free roots, hinges on tilted axes, a slider (whose reaction moves from
  // M's origin to F's when the child is body 2), welds, Universal and Ball joints.
  for (const auto& [name, scene] :
       {std::pair{"rover", rover()}, std::pair{"arm and box", arm_and_box()},
        std::pair{"welded chain", welded_chain()}, std::pair{"cardan chain", cardan_chain()},
        std::pair{"ball chain", ball_chain()}, std::pair{"reversed slider", reversed_slider()}}) {
    const double worst = worst_reaction_difference(scene, 300);
    std::printf("%s: worst joint reaction difference %.3g\n", name, worst);
    EXPECT_LT(worst, 1e-9) << name;
  }
}

TEST(TreeDynamics, JointReactionsWithLoopsKeepSimbody) {
  // With a loop, a reaction counts the constraint forces: Simbody's.
  scene::Scene four_bar;
  four_bar.bodies.push_back(test::box("crank", 0.5, {0.03, 0.03, 0.4}, {0, 0, 1.3}));
  four_bar.bodies.push_back(test::box("rocker", 0.5, {0.03, 0.03, 0.4}, {0.5, 0, 1.3}));
  four_bar.bodies.push_back(test::box("coupler", 1.0, {0.5, 0.03, 0.03}, {0.25, 0, 1.1}));
  four_bar.joints.push_back(test::joint("a", JointType::hinge, 0, -1, {0, 0, 1.5}, {0, 1, 0}));
  four_bar.joints.push_back(test::joint("b", JointType::hinge, 1, -1, {0.5, 0, 1.5}, {0, 1, 0}));
  four_bar.joints.push_back(test::joint("c", JointType::hinge, 2, 0, {0, 0, 1.1}, {0, 1, 0}));
  four_bar.joints.push_back(test::joint("d", JointType::hinge, 2, 1, {0.5, 0, 1.1}, {0, 1, 0}));
  test::add_robot(four_bar, "four_bar");
  test::Runner loop(four_bar);
  EXPECT_TRUE(loop.mb.uses_tree_fast_path());
  loop.mb.request_joint_reactions();
  EXPECT_FALSE(loop.mb.uses_tree_fast_path());
  loop.step(10);
  EXPECT_GT(norm(loop.mb.joint_reactions()[0].force_N), 0.0);
}

}  // namespace
}  // namespace s2sim::model
