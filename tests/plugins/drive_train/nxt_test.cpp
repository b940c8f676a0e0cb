// scenes/nxt, the paper's Lego NXT differential robot, on the floor (contact layer).
#include "bench_util.hpp"

#include <cmath>
#include <cstdio>

namespace s2sim::test {
namespace {

const fs::path kNxt = fs::path(S2SIM_SOURCE_DIR) / "scenes/nxt";

TEST(Nxt, WheelsInTheAirTurnAtTheFreeRunningSpeedOfEq311) {
  auto sim = Simulation::load(kNxt, bench_options({{"lift", 5}}));  // falls 1.2 m in 0.5 s
  sim->set_input("robots/nxt/axes/right/ref_voltage", 6);
  sim->set_input("robots/nxt/axes/left/ref_voltage", -6);
  sim->run_until(0.5);
  const double w = (6 - kRa * kTc / kKs) / (kKs + kRa * kB / kKs);  // 11.516 rad/s
  EXPECT_NEAR(sim->signal("robots/nxt/axes/right/speed"), w, 1e-3 * w);
  EXPECT_NEAR(sim->signal("robots/nxt/axes/left/speed"), -w, 1e-3 * w);
}

TEST(Nxt, At6VoltsDrivesStraight1MetreAtTheSpeedRTimesWPredicts) {
  auto sim = Simulation::load(kNxt, bench_options());
  const double r = 0.028;
  const double w = (6 - kRa * kTc / kKs) / (kKs + kRa * kB / kKs);  // (3.11): 11.516 rad/s
  // Right wheel positive, left negative: both drive toward +X (docs/format.md, wheels).
  sim->set_input("robots/nxt/axes/right/ref_voltage", 6);
  sim->set_input("robots/nxt/axes/left/ref_voltage", -6);
  sim->run_until(0.5);  // start-up transient
  const double x0 = sim->signal("robots/nxt/x"), t0 = sim->time_s();
  double wheel_sum = 0;
  int n = 0;
  while (sim->signal("robots/nxt/x") - x0 < 1.0 && sim->time_s() < t0 + 10) {
    sim->step();
    wheel_sum += 0.5 * (sim->signal("robots/nxt/axes/right/speed") -
                        sim->signal("robots/nxt/axes/left/speed"));
    ++n;
  }
  const double distance = sim->signal("robots/nxt/x") - x0;
  const double v = distance / (sim->time_s() - t0);
  std::printf(
      "  1 m in %.3f s: v = %.4f m/s; r*w(3.11) = %.4f m/s, r*w(measured) = %.4f m/s, "
      "y = %.4f m\n",
      sim->time_s() - t0, v, r * w, r * wheel_sum / n, sim->signal("robots/nxt/y"));
  ASSERT_GE(distance, 1.0);
  EXPECT_NEAR(v, r * w, 0.02 * r * w);
  EXPECT_NEAR(v, r * wheel_sum / n, 0.02 * r * wheel_sum / n);
  EXPECT_NEAR(sim->signal("robots/nxt/y"), 0.0, 0.02) << "not straight";
  EXPECT_NEAR(sim->signal("robots/nxt/yaw"), 0.0, 0.02) << "not straight";
}

}  // namespace
}  // namespace s2sim::test
