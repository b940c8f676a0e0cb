// The drive-train capabilities SimTwo scripts reach (docs/scripting.md, coverage), on this
// folder's script_api_drive scene, each checked against numbers: a spring set by SetAxisSpring
// swings at sqrt(k / I), the energy meter is the sum of V I over the steps where it is positive,
// controller gains and mode set at run time take over; for each, a snapshot and a reset bring
// the run back exactly and two runs are identical.
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using s2sim::ScriptMode;
using s2sim::Simulation;
using s2sim::SimulationOptions;

namespace {

const fs::path kScene = fs::path(S2SIM_PASCAL_FIXTURES) / ".." / "script_api_drive";
constexpr double kPi = 3.14159265358979323846;
constexpr double kInertia = 1.0 * (0.4 * 0.4 + 0.1 * 0.1) / 12;  // the rotor about its axis
const char* const kAxis = "robots/spinner/axes/spin/";

#define SKIP_WITHOUT_FPC \
  if (std::system("fpc -iV > /dev/null 2>&1") != 0) GTEST_SKIP() << "no fpc"

class ScriptAxes : public ::testing::Test {
 protected:
  void SetUp() override {
    ::setenv("S2SIM_PASCAL_CACHE", S2SIM_PASCAL_TEST_CACHE, 1);
    ::unsetenv("S2SIM_FPC");
    ::unsetenv("S2SIM_COM_PORT");
    ::setenv("S2SIM_UDP_PORT", "0", 1);  // no port of its own needed
  }
  static std::unique_ptr<Simulation> load(const char* fixture) {
    SimulationOptions o;
    o.script_mode = ScriptMode::always;
    o.script_file = fs::path(S2SIM_PASCAL_FIXTURES) / fixture;
    o.sheet_cells = {{1, 1, "0"}, {1, 2, "0"}, {1, 3, "0"}, {1, 4, "0"}, {1, 5, "0"}};
    return Simulation::load(kScene, o);
  }
};

std::string at(const char* name) {
  return std::string(kAxis) + name;
}

/// `names` after every step until `until` seconds.
std::vector<double> trace(Simulation& sim, double until, const std::vector<std::string>& names) {
  std::vector<double> values;
  while (sim.time_s() < until - 1e-9) {
    sim.step(1);
    for (const auto& n : names)
      values.push_back(sim.signal(n));
  }
  return values;
}

/// The run from `mid` to `end` repeats bit for bit after a snapshot at `mid`, a reset repeats
/// the run from the start, and so does a second load.
void expect_repeatable(const char* fixture, double mid, double end,
                       const std::vector<std::string>& names,
                       std::unique_ptr<Simulation> (*load)(const char*)) {
  auto sim = load(fixture);
  const auto whole = trace(*sim, mid, names);
  const Simulation::Snapshot snap = sim->save();
  const auto after = trace(*sim, end, names);
  sim->restore(snap);
  const auto again = trace(*sim, end, names);
  ASSERT_EQ(after.size(), again.size());
  EXPECT_EQ(std::memcmp(after.data(), again.data(), after.size() * sizeof(double)), 0)
      << "a restored snapshot did not repeat the run";
  sim->reset();
  const auto reset = trace(*sim, mid, names);
  ASSERT_EQ(whole.size(), reset.size());
  EXPECT_EQ(std::memcmp(whole.data(), reset.data(), whole.size() * sizeof(double)), 0)
      << "a reset did not repeat the run";
  auto other = load(fixture);
  const auto second = trace(*other, mid, names);
  EXPECT_EQ(std::memcmp(whole.data(), second.data(), whole.size() * sizeof(double)), 0)
      << "a second load did not repeat the run";
}

TEST_F(ScriptAxes, SpringSetByTheScriptSwingsAtSqrtKOverI) {
  SKIP_WITHOUT_FPC;
  auto sim = load("axis_spring.pas");
  EXPECT_EQ(sim->signal(at("spring_k")), 0);  // the scene has no spring
  const auto q = trace(*sim, 3.0, {at("pos")});
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  EXPECT_EQ(sim->signal(at("spring_k")), 1);
  // Upward crossings of the zero position, 0.5 rad, interpolated within the step.
  std::vector<double> crossings;
  for (std::size_t i = 1; i < q.size(); ++i) {
    const double a = q[i - 1] - 0.5, b = q[i] - 0.5;
    if (a < 0 && b >= 0) crossings.push_back(1e-3 * (static_cast<double>(i) + (-a) / (b - a)));
  }
  ASSERT_GE(crossings.size(), 3u);
  const double period =
      (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  // 2 pi sqrt(I / k) = 0.7478486 s; 0.7478464 s measured (3e-6 relative).
  EXPECT_NEAR(period, 2 * kPi * std::sqrt(kInertia / 1.0), 1e-5);
  double high = -1, low = 2;
  for (std::size_t i = 100; i < q.size(); ++i) {
    high = std::max(high, q[i]);
    low = std::min(low, q[i]);
  }
  EXPECT_NEAR(high, 1, 1e-4);  // released at 0 about 0.5: no friction, no loss
  EXPECT_NEAR(low, 0, 1e-4);
  expect_repeatable("axis_spring.pas", 1.0, 2.0, {at("pos"), at("speed")}, &ScriptAxes::load);
}

TEST_F(ScriptAxes, ViscousFrictionSetByTheScriptSlowsTheRotorAsExpOfMinusBvTOverI) {
  SKIP_WITHOUT_FPC;
  auto sim = load("axis_friction.pas");
  sim->run_until(0.1);
  const double w1 = sim->signal(at("speed"));
  sim->run_until(1.1);
  const double w2 = sim->signal(at("speed"));
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  EXPECT_GT(w1, 9);  // set spinning at 10 rad/s at the 39 ms call
  // w(t) = w0 exp(-Bv t / I): over 1 s, exp(-0.01 / 0.0141667) = 0.4937.
  EXPECT_NEAR(w2 / w1, std::exp(-0.01 * 1.0 / kInertia), 1e-3);
  EXPECT_EQ(sim->signal("sheet/A1"), 0.01);
  EXPECT_EQ(sim->signal("sheet/B1"), 0);
  EXPECT_EQ(sim->signal("sheet/C1"), 0);  // CoulombLimit ignored, as by SimTwo
  expect_repeatable("axis_friction.pas", 0.5, 1.0, {at("speed")}, &ScriptAxes::load);
}

TEST_F(ScriptAxes, EnergyMeterIsTheSumOfPositiveVTimesIAndRestartsAtItsReset) {
  SKIP_WITHOUT_FPC;
  auto sim = load("energy_meter.pas");
  const double dt = sim->tick_s();
  double drawn = 0, returned = 0, drawn_at_reset = 0;
  double previous_cell = 0;
  int readings = 0;
  bool reset_seen = false;
  while (sim->time_s() < 2.0 - 1e-9) {
    const double before = drawn;  // the meter a call reads: the steps before its own
    sim->step(1);
    const double p = sim->signal(at("power"));
    (p > 0 ? drawn : returned) += p * dt;
    EXPECT_NEAR(sim->signal(at("energy_drawn")), drawn, 1e-12);
    const double cell = sim->signal("sheet/A1");
    if (cell != previous_cell || sim->signal("controllers/script/calls") > readings) {
      readings = static_cast<int>(sim->signal("controllers/script/calls"));
      const double t = sim->time_s() - dt;  // the call's Time
      if (t >= 1.0 - 1e-9 && !reset_seen) {
        reset_seen = true;
        drawn_at_reset = before;
      }
      const double expected = before - (reset_seen ? drawn_at_reset : 0);
      EXPECT_NEAR(cell, expected, 1e-12) << "at " << t << " s";
      previous_cell = cell;
    }
  }
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  EXPECT_EQ(readings, 50);
  // The 0.3 V phase gives energy back (the meter does not count it): enough to matter.
  EXPECT_LT(returned, -0.02);
  EXPECT_GT(drawn, 1.0);
  EXPECT_TRUE(reset_seen);
  expect_repeatable("energy_meter.pas", 0.7, 1.5, {at("energy_drawn"), "sheet/A1"},
                    &ScriptAxes::load);
}

TEST_F(ScriptAxes, ControllerGainsAndModeSetByTheScriptTakeOver) {
  SKIP_WITHOUT_FPC;
  auto sim = load("controller_gains.pas");
  // Under SimTwo's law (a SimTwo scene) u = Kp e + Ki S, S the error summed over the physics
  // step at each controller call (10 ms): S = (V - Kp e) / Ki from the voltage and the error.
  auto integral = [&](double ki) {
    return (sim->signal(at("voltage")) - 1.0 * sim->signal(at("control_error"))) / ki;
  };
  sim->run_until(1.035);
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  EXPECT_NEAR(sim->signal(at("speed")), 10, 1.5);  // the speed loop the script set (Ki 100, Kp 1)
  EXPECT_LT(integral(100), -0.01);                 // -0.0175 seen
  sim->run_until(1.041);  // Ki changed at the 1.039 s call; the controller's next call at 1.04 s
  EXPECT_NEAR(integral(100.001), sim->signal(at("control_error")) * sim->tick_s(), 1e-12)
      << "the integral did not restart";
  sim->run_until(4.0);  // the position loop from 1.5 s (Kp 20, Kd 0.2): to 1 rad, the shortest way
  EXPECT_NEAR(std::remainder(sim->signal(at("pos")) - 1, 2 * kPi), 0, 0.01);  // 0.0018 seen
  EXPECT_NEAR(sim->signal(at("speed")), 0, 0.05);
  EXPECT_EQ(sim->signal(at("controller_mode")), 1);
  EXPECT_EQ(sim->signal(at("controller_kp")), 20);
  EXPECT_EQ(sim->signal(at("controller_kd")), 0.2);
  EXPECT_EQ(sim->signal("sheet/B1"), 0);    // Ki read back
  EXPECT_EQ(sim->signal("sheet/C1"), 0.2);  // Kd
  EXPECT_EQ(sim->signal("sheet/D1"), 20);   // Kp
  EXPECT_EQ(sim->signal("sheet/E1"), 0);    // Kf
  expect_repeatable("controller_gains.pas", 1.2, 2.5, {at("pos"), at("voltage")},
                    &ScriptAxes::load);
}

}  // namespace
