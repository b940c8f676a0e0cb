// The drag plugin against closed forms: quadratic drag's terminal velocity, linear drag's
// exponential approach, the wind input; determinism and reset.
#include "common/edited_copy.hpp"
#include "fixture.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace s2sim {
namespace {

using fluids_test::load;
const char* kVz = "robots/ball/solids/ball/vz";

TEST(Drag, SphereFallingInAirReachesTheTerminalVelocity) {
  // v_t = sqrt(2 m g / (rho Cd A)), and on the way v(t) = v_t tanh(g t / v_t).
  const double m = 0.05, r = 0.1, cd = 0.47, rho = 1.225, area = kPi * r * r;
  const double vt = std::sqrt(2 * m * kGravity_m_s2 / (rho * cd * area));
  auto sim = load("sphere_air", {{"ball_mass", m}, {"ball_radius", r}, {"cd", cd}});
  double worst = 0;
  while (sim->time_s() < 6.0 - 1e-9) {
    sim->step(100);
    // The velocity read is the leapfrog's, half a tick behind the time.
    const double t = sim->time_s() - 0.5 * sim->tick_s();
    const double expected = vt * std::tanh(kGravity_m_s2 * t / vt);
    worst = std::max(worst, std::abs(-sim->signal(kVz) - expected) / expected);
  }
  const double v = -sim->signal(kVz);
  std::printf(
      "  terminal: %.5f m/s after 6 s, analytic %.5f m/s (%.4f %%), worst on the way %.4f %%\n", v,
      vt, 100 * (v - vt) / vt, 100 * worst);
  EXPECT_NEAR(v, vt, 0.005 * vt);
  EXPECT_LT(worst, 0.005);
  EXPECT_NEAR(sim->signal("robots/ball/actuators/air/force"), m * kGravity_m_s2,
              0.005 * m * kGravity_m_s2);
}

TEST(Drag, LinearDragApproachesItsTerminalVelocityExponentially) {
  // m dv/dt = -m g - b v: v(t) = -(m g / b)(1 - e^(-t b / m)).
  const double m = 0.05, b = 0.04;
  auto sim = load("sphere_air", {{"ball_mass", m}, {"cd", 0}, {"linear", b}});
  for (double t : {0.5, 1.0, 2.0, 4.0}) {
    sim->run_until(t);
    const double expected = -(m * kGravity_m_s2 / b) * (1 - std::exp(-t * b / m));
    std::printf("  linear: t = %.1f s  v = %.5f m/s, analytic %.5f (%.4f %%)\n", t,
                sim->signal(kVz), expected, 100 * (sim->signal(kVz) - expected) / expected);
    EXPECT_NEAR(sim->signal(kVz), expected, 0.005 * std::abs(expected));
  }
}

TEST(Drag, WindInputCarriesTheBodyAlong) {
  // Horizontally only the drag acts: v_x(t) = w (1 - e^(-t b / m)).
  const double m = 0.05, b = 0.04, wind = 3.0;
  auto sim = load("sphere_air", {{"ball_mass", m}, {"cd", 0}, {"linear", b}});
  sim->set_input("robots/ball/actuators/air/wind_x", wind);
  sim->run_until(2.0);
  const double expected = wind * (1 - std::exp(-2.0 * b / m));
  EXPECT_NEAR(sim->signal("robots/ball/solids/ball/vx"), expected, 0.005 * expected);
}

TEST(Drag, RunsAreDeterministicAndResetAndRestoreAreExact) {
  auto a = load("sphere_air", {{"linear", 0.01}});
  auto b = load("sphere_air", {{"linear", 0.01}});
  a->run_until(1.0);
  b->run_until(1.0);
  EXPECT_EQ(a->signal(kVz), b->signal(kVz));
  const auto snapshot = a->save();
  a->run_until(2.0);
  const double at_two = a->signal(kVz);
  a->restore(snapshot);
  a->run_until(2.0);
  EXPECT_EQ(a->signal(kVz), at_two);
  a->reset();
  a->run_until(1.0);
  EXPECT_EQ(a->signal(kVz), b->signal(kVz));
}

// A misspelt parameter of a fluids kind is a refusal, not a warning: the default it leaves in
// place would change the physics silently. `cD` for `cd`.
TEST(Drag, AMisspeltParameterIsRefusedNamingTheClosestOne) {
  const auto dir = s2sim::test::edited_copy(
      std::filesystem::path(S2SIM_SOURCE_DIR) / "tests/plugins/fluids/fixtures/sphere_air",
      "ball.xml", "density='1.225' cd='cd'", "density='1.225' cD='cd'");
  SimulationOptions o;
  o.plugin_path = {std::filesystem::path(S2SIM_PLUGIN_DIR)};
  try {
    Simulation::load(dir, o);
    FAIL() << "a misspelt cd was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::scene);
    const std::string what = e.what();
    EXPECT_NE(what.find("ball.xml: robot/plugin[1]@cD: unknown attribute: kind 'drag' does not "
                        "read it; did you mean 'cd'?"),
              std::string::npos)
        << what;
  }
}

TEST(Drag, NegativeOrUnknownParametersAreRefusedWithTheirPlace) {
  try {
    load("sphere_air", {{"cd", -1}});
    FAIL() << "a negative cd was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("ball.xml"), std::string::npos) << what;
    EXPECT_NE(what.find("cd"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace s2sim
