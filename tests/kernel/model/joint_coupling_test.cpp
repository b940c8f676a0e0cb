// Joint couplings in the multibody (docs/models/multibody.md, "Coupled joints"): a coupling
// through a mobilizer that runs against its joint's direction (axis value = −q), and a coupled
// slider on a free-floating body, each held exactly, with the fast path's accelerations checked
// against Simbody's CoordinateCoupler at every substep.
#include "model/multibody.hpp"
#include "model_runner.hpp"
#include "scene_builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace s2sim::model {
namespace {

using scene::JointType;
using test::Runner;

TEST(JointCoupling, AReversedMobilizerCouplesInAxisValuesWithTheEffectiveInertia) {
  // The wheel's joint names the world as body1: its mobilizer runs from body2, so its axis
  // value is −q. Coupled at −3 times the hub's axis value, under 0.01 N·m on the hub:
  // θ = ½·τ/(I1 + 9·I2)·t².
  scene::Scene s;
  s.bodies.push_back(test::box("hub", 1.0, {0.2, 0.2, 0.02}, {0, 0, 1}));
  s.bodies.push_back(test::box("wheel", 2.0, {0.1, 0.1, 0.02}, {0.5, 0, 1}));
  s.joints.push_back(test::joint("drive", JointType::hinge, 0, -1, {0, 0, 1}));
  s.joints.push_back(test::joint("geared", JointType::hinge, -1, 1, {0.5, 0, 1}));
  test::add_robot(s, "gear");
  s.couplings.push_back({1, 0, -3.0, 0.0, Location{"test", "geared", ""}});
  Runner r(s);
  r.mb.choose_dynamics(DynamicsChoice::checked);
  ASSERT_STREQ(r.mb.dynamics_name(), "checked");
  const double I1 = 0.08 / 12, I2 = 2 * 0.02 / 12, torque = 0.01;
  double worst = 0;
  for (int n = 0; n < 1000; ++n) {
    r.mb.applied_axis_forces()[0] = torque;
    r.step();
    worst = std::max(worst, std::abs(r.pos[1] + 3 * r.pos[0]));
  }
  const double expected = 0.5 * torque / (I1 + 9 * I2);
  const DynamicsCheck check = r.mb.dynamics_check();
  std::printf(
      "hub at 1 s %.12f rad (I1 + 9 I2: %.12f); wheel off -3x the hub by %.3g rad; "
      "%ld accelerations within %.3g of Simbody's\n",
      r.pos[0], expected, worst, static_cast<long>(check.compared), check.worst_relative);
  EXPECT_NEAR(r.pos[0], expected, 1e-6 * expected);
  EXPECT_LT(worst, 1e-9);
  EXPECT_LE(check.worst_relative, 1e-12);
}

TEST(JointCoupling, ACoupledSliderOnAFreeFloatingBodyIsHeldAndMatchesSimbody) {
  // A free base spinning and falling, an arm hinged to it, a slider on the arm held at
  // 0.1·hinge + 0.05: every speed moving (the velocity-product terms count).
  scene::Scene s;
  s.bodies.push_back(test::box("base", 2.0, {0.3, 0.2, 0.1}, {0, 0, 2}));
  s.bodies.push_back(test::box("arm", 0.5, {0.4, 0.04, 0.04}, {0.35, 0, 2}));
  s.bodies.push_back(test::box("block", 0.3, {0.05, 0.05, 0.05}, {0.45, 0, 2}));
  s.joints.push_back(test::joint("shoulder", JointType::hinge, 1, 0, {0.15, 0, 2}, {0, 1, 0}));
  s.joints.push_back(test::joint("rail", JointType::slider, 2, 1, {0.45, 0, 2}, {1, 0, 0}));
  test::add_robot(s, "floater");
  s.couplings.push_back({1, 0, 0.1, 0.05, Location{"test", "rail", ""}});
  Runner r(s);
  r.mb.choose_dynamics(DynamicsChoice::checked);
  ASSERT_STREQ(r.mb.dynamics_name(), "checked");
  EXPECT_NEAR(r.pos[1], 0.05, 1e-15) << "the offset sets the follower at load";
  double worst = 0;
  for (int n = 0; n < 1000; ++n) {
    r.mb.applied_axis_forces()[0] = n < 500 ? 0.3 : -0.2;
    r.step();
    worst = std::max(worst, std::abs(r.pos[1] - (0.1 * r.pos[0] + 0.05)));
  }
  const DynamicsCheck check = r.mb.dynamics_check();
  std::printf(
      "shoulder at 1 s %.6f rad; rail off 0.1 shoulder + 0.05 by %.3g m; %ld "
      "accelerations within %.3g of Simbody's\n",
      r.pos[0], worst, static_cast<long>(check.compared), check.worst_relative);
  EXPECT_GT(std::abs(r.pos[0]), 0.1) << "the shoulder did not turn";
  EXPECT_LT(worst, 1e-9);
  EXPECT_LE(check.worst_relative, 1e-9);
}

}  // namespace
}  // namespace s2sim::model
