// The small-tree fast path (kernel/src/model/tree_dynamics.cpp) against Simbody's realize
// chain: the same accelerations to one part in 10^12, tick after tick, on trees of every
// joint the fast path takes, moving fast and loaded everywhere (issue 17).
#include "model/multibody.hpp"
#include "model_runner.hpp"
#include "scene_builder.hpp"
#include "sim/state_layout.hpp"

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

/// Loads that change every tick and reach every body and axis: sines of incommensurate rates.
void load(Multibody& mb, int tick) {
  Wrench* w = mb.applied_wrenches();
  for (int b = 1; b < mb.body_count(); ++b) {
    const double t = 0.37 * tick + 1.3 * b;
    w[b] = Wrench{{0.05 * std::sin(t), 0.04 * std::cos(1.1 * t), 0.03 * std::sin(0.7 * t)},
                  {2 * std::cos(t), 3 * std::sin(1.3 * t), 1.5 * std::cos(0.9 * t)}};
  }
  // Slowly turning axis loads build speed; fast ones shake it.
  for (std::size_t a = 0; a < mb.axes().size(); ++a)
    mb.applied_axis_forces()[a] = 0.3 * std::sin(0.004 * tick + static_cast<double>(a)) +
                                  0.1 * std::sin(0.5 * tick + static_cast<double>(a));
}

/// Per tick: Simbody takes the fast path's state, both step under the same loads, and the
/// change of every body's velocity over the tick (h·acceleration) is compared. Returns the
/// worst difference relative to that change, once the rounding of adding the change to the
/// velocity (a few ulps of the velocity itself) is taken off.
double worst_relative_difference(const scene::Scene& s, int ticks) {
  test::Runner fast(s), simbody(s);
  simbody.mb.set_tree_fast_path(false);
  EXPECT_TRUE(fast.mb.uses_tree_fast_path());
  EXPECT_FALSE(simbody.mb.uses_tree_fast_path());
  sim::StateLayout fast_layout, simbody_layout;
  fast.mb.declare_state(fast_layout);
  simbody.mb.declare_state(simbody_layout);
  std::vector<double> state;
  double worst = 0, fastest = 0;
  for (int tick = 0; tick < ticks; ++tick) {
    state.clear();
    fast_layout.save(state);
    simbody_layout.restore(simbody_layout.id(), simbody_layout.entries(), state);
    simbody.mb.restored();
    fast.read();
    const std::vector<Twist> before = fast.twists;
    load(fast.mb, tick);
    load(simbody.mb, tick);
    fast.step();
    simbody.step();
    for (int b = 1; b < fast.mb.body_count(); ++b) {
      const Twist& f = fast.twists[b];
      const Twist& g = simbody.twists[b];
      const double change = std::max(norm(f.angular_rad_s - before[b].angular_rad_s),
                                     norm(f.linear_m_s - before[b].linear_m_s));
      const double differs =
          std::max(norm(f.angular_rad_s - g.angular_rad_s), norm(f.linear_m_s - g.linear_m_s));
      const double pose_differs =
          norm(fast.poses[b].position - simbody.poses[b].position) +
          norm(fast.poses[b].rotation.column(0) - simbody.poses[b].rotation.column(0)) +
          norm(fast.poses[b].rotation.column(1) - simbody.poses[b].rotation.column(1));
      EXPECT_LE(pose_differs, 1e-14) << "body " << b << " tick " << tick;
      const double speed = std::max(norm(f.angular_rad_s), norm(f.linear_m_s));
      const double rounding = 8 * std::numeric_limits<double>::epsilon() * speed;
      if (change > 0) worst = std::max(worst, std::max(0.0, differs - rounding) / change);
      fastest = std::max(fastest, norm(f.angular_rad_s));
    }
    for (std::size_t a = 0; a < fast.vel.size(); ++a)
      EXPECT_NEAR(fast.vel[a], simbody.vel[a], 1e-12 * (1 + std::abs(fast.vel[a])))
          << fast.mb.axes()[a].name << " tick " << tick;
  }
  EXPECT_GT(fastest, 1.0) << "the bodies must spin for the velocity-product terms to count";
  return worst;
}

TEST(TreeDynamics, RoverAccelerationsMatchSimbodysToOnePartInATrillion) {
  const double worst = worst_relative_difference(rover(), 400);
  std::printf("rover: worst relative difference of the velocity change %.3g\n", worst);
  EXPECT_LT(worst, 1e-12);
}

TEST(TreeDynamics, WorldHingedArmAndFreeBoxMatchSimbodysToOnePartInATrillion) {
  const double worst = worst_relative_difference(arm_and_box(), 400);
  std::printf("arm and box: worst relative difference of the velocity change %.3g\n", worst);
  EXPECT_LT(worst, 1e-12);
}

TEST(TreeDynamics, UniversalBallLoopsAndJointReactionsKeepSimbody) {
  // A Universal joint: Simbody's.
  scene::Scene cardan;
  cardan.bodies.push_back(test::box("base", 2.0, {0.2, 0.2, 0.2}, {0, 0, 2}));
  cardan.bodies.push_back(test::box("cardan", 0.5, {0.1, 0.1, 0.4}, {0, 0, 1.7}));
  auto u = test::joint("u", JointType::universal, 1, 0, {0, 0, 1.9}, {1, 0, 0});
  u.axis2 = {0, 1, 0};
  cardan.joints.push_back(u);
  test::add_robot(cardan, "r");
  test::Runner with_universal(cardan);
  EXPECT_FALSE(with_universal.mb.uses_tree_fast_path());
  // A loop: constraints, Simbody's.
  test::Runner with_loop(test::four_bar());
  EXPECT_FALSE(with_loop.mb.uses_tree_fast_path());
  // Joint reactions come from Simbody's Acceleration stage.
  test::Runner with_reactions(rover());
  EXPECT_TRUE(with_reactions.mb.uses_tree_fast_path());
  with_reactions.mb.request_joint_reactions();
  EXPECT_FALSE(with_reactions.mb.uses_tree_fast_path());
  with_reactions.step(10);
  EXPECT_GT(norm(with_reactions.mb.joint_reactions()[0].force_N), 0.0);
}

}  // namespace
}  // namespace s2sim::model
