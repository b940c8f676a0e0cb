// SimTwo's <drag>, <buoyant> and <propeller> (simtwo-format.md §4.4) on a SimTwo-format scene:
// the per-step factors reproduced step by step, the quadratic coefficient's terminal velocity,
// the reversed weight, thrust = coefficient x spin; bad values refused, things warned.
#include "fixture.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

namespace s2sim {
namespace {

using fluids_test::load;
const char* kVz = "robots/r/solids/ball/vz";
const char* kZ = "robots/r/solids/ball/z";

TEST(SimTwoFluids, StokesFactorScalesTheVelocityEveryStepAsOdeDoes) {
  // ODE after each step: v <- v + h g, then v <- (1 - stokes) v when |v|^2 > 1e-4.
  const double stokes = 0.01, h = 1e-3;
  auto sim = load("simtwo_drag", {{"stokes", stokes}});
  // The kernel's leapfrog starts with a half step (its speeds live mid-step,
  // docs/models/multibody.md): the recurrence starts there too.
  double v = 0, worst = 0;
  for (int n = 0; n < 3000; ++n) {
    sim->step();
    v -= (n == 0 ? 0.5 : 1.0) * h * kGravity_m_s2;
    if (v * v > 1e-4) v *= 1 - stokes;
    worst = std::max(worst, std::abs(sim->signal(kVz) - v) / std::abs(v));
  }
  std::printf("  stokes 0.01: v = %.9f m/s after 3 s, SimTwo's recurrence %.9f, worst %.3g\n",
              sim->signal(kVz), v, worst);
  EXPECT_LT(worst, 1e-9);
  // The terminal speed of this recurrence, g h (1 - s) / s, not g h / s.
  EXPECT_NEAR(-v, kGravity_m_s2 * h * (1 - stokes) / stokes, 1e-6);
}

TEST(SimTwoFluids, RollFactorScalesTheSpinEveryStepAsOdeDoes) {
  // ODE's angular damping after each step: w <- (1 - roll) w while |w|^2 > 1e-4; a sphere
  // spun at 10 rad/s about Z at t = 0 by the test plugin (its inertia is isotropic: no
  // gyroscopic term, so the spin changes by the damping alone).
  const double roll = 0.01;
  SimulationOptions o;
  o.plugin_path = {std::filesystem::path(S2SIM_TEST_PLUGIN_DIR) / "scene",
                   std::filesystem::path(S2SIM_PLUGIN_DIR)};
  o.constants.push_back({"roll", roll});
  auto sim = Simulation::load(
      std::filesystem::path(S2SIM_SOURCE_DIR) / "tests/plugins/fluids/fixtures/simtwo_roll", o);
  const char* wz = "robots/r/solids/ball/wz";
  sim->step(2);  // the spin is set, then damped from the next step on
  double w = sim->signal(wz), worst = 0;
  ASSERT_GT(w, 9.0);
  int steps = 0;
  while (w * w > 1e-4 && steps < 5000) {
    sim->step();
    w *= 1 - roll;
    worst = std::max(worst, std::abs(sim->signal(wz) - w) / std::abs(w));
    ++steps;
  }
  std::printf("  roll 0.01: %d steps to |w| = %.6f rad/s, worst relative difference %.3g\n", steps,
              w, worst);
  EXPECT_LT(worst, 1e-9);
  // Below ODE's threshold (|w| = 0.01 rad/s) the spin is left alone.
  const double below = sim->signal(wz);
  sim->step(100);
  EXPECT_DOUBLE_EQ(sim->signal(wz), below);
}

TEST(SimTwoFluids, QuadraticCoefficientGivesSimTwosTerminalVelocity) {
  const double cd = 0.5, m = 0.5, area = kPi * 0.01, rho = 1.293;
  const double vt = std::sqrt(2 * m * kGravity_m_s2 / (rho * cd * area));
  auto sim = load("simtwo_drag", {{"stokes", 0}, {"coefficient", cd}});
  sim->run_until(15.0);
  std::printf("  coefficient 0.5: %.5f m/s, analytic %.5f m/s\n", -sim->signal(kVz), vt);
  EXPECT_NEAR(-sim->signal(kVz), vt, 0.005 * vt);
}

TEST(SimTwoFluids, NegativeBuoyantMassReversesTheWeight) {
  {  // -0.5 kg on a 0.5 kg ball: it hovers
    auto sim = load("simtwo_drag", {{"stokes", 0}, {"buoyant_mass", -0.5}});
    sim->run_until(5.0);
    EXPECT_NEAR(sim->signal(kZ), 500, 1e-9);
  }
  {  // -1 kg: it rises at g (the velocity read is the leapfrog's, half a tick behind)
    auto sim = load("simtwo_drag", {{"stokes", 0}, {"buoyant_mass", -1.0}});
    sim->run_until(2.0);
    EXPECT_NEAR(sim->signal(kVz), kGravity_m_s2 * (2.0 - 0.5 * sim->tick_s()), 1e-9);
  }
}

TEST(SimTwoFluids, PropellerThrustIsTheCoefficientTimesItsSpin) {
  auto sim = load("simtwo_drag", {{"stokes", 0}});
  sim->set_input("robots/r/axes/spin/ref_torque", 1e-4);
  sim->run_until(0.5);
  const double spin = sim->signal("robots/r/solids/prop/propeller/spin_rate");
  EXPECT_GT(spin, 1.0);
  EXPECT_NEAR(sim->signal("robots/r/solids/prop/propeller/thrust"), 0.05 * spin, 1e-12);
}

void expect_refused(const char* fixture, const char* attribute) {
  try {
    load(fixture);
    ADD_FAILURE() << fixture << " was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    std::printf("  %s: %s\n", fixture, what.c_str());
    EXPECT_NE(what.find("t.xml"), std::string::npos) << what;
    EXPECT_NE(what.find(attribute), std::string::npos) << what;
  }
}

TEST(SimTwoFluids, OutOfRangeValuesAreRefusedWhereTheyAreWritten) {
  expect_refused("bad_drag", "coefficient");
  expect_refused("bad_buoyant", "mass");
  expect_refused("bad_thrust", "coefficient");
}

TEST(SimTwoFluids, BuoyancyOnAThingIsLeftOutWithAWarningAsSimTwoDoes) {
  auto sim = load("thing_buoyant");
  bool warned = false;
  for (const auto& w : sim->warnings())
    warned = warned || w.find("robot solids only") != std::string::npos;
  EXPECT_TRUE(warned);
}

}  // namespace
}  // namespace s2sim
