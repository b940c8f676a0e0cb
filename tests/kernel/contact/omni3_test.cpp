// scenes/omni3: three omni wheels at 120 degrees translate the robot sideways and turn it in
// place on command (anisotropic friction of docs/models/contact.md, motors of dc-motor.md).
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace s2sim {
namespace {

constexpr double kWheelRadius = 0.03, kCentreDistance = 0.11;

/// Sets each wheel's speed reference for a body velocity (vx, vy) in the robot frame and a
/// yaw rate w.
void command(Simulation& sim, double vx, double vy, double w) {
  for (int angle : {0, 120, 240}) {
    const double a = angle * kPi / 180;
    const double speed =
        (-std::sin(a) * vx + std::cos(a) * vy + kCentreDistance * w) / kWheelRadius;
    sim.set_input("robots/omni3/axes/w" + std::to_string(angle) + "/ref_speed", speed);
  }
}

std::unique_ptr<Simulation> load() {
  return Simulation::load(std::filesystem::path(S2SIM_SOURCE_DIR) / "scenes/omni3");
}

TEST(Omni3, TranslatesSidewaysOnCommand) {
  auto sim = load();
  sim->run_until(0.5);  // settle on the floor
  command(*sim, 0, 0.2, 0);
  sim->run_until(1.5);
  const double x0 = sim->signal("robots/omni3/x"), y0 = sim->signal("robots/omni3/y");
  sim->run_until(3.5);
  const double vx = (sim->signal("robots/omni3/x") - x0) / 2,
               vy = (sim->signal("robots/omni3/y") - y0) / 2;
  EXPECT_NEAR(vy, 0.2, 0.01) << "sideways speed";
  EXPECT_NEAR(vx, 0.0, 0.01) << "forward drift";
  EXPECT_NEAR(sim->signal("robots/omni3/yaw"), 0.0, 0.05) << "it turned";
}

TEST(Omni3, RotatesInPlaceOnCommand) {
  auto sim = load();
  sim->run_until(0.5);
  command(*sim, 0, 0, 1.0);
  sim->run_until(1.5);
  const double x = sim->signal("robots/omni3/x"), y = sim->signal("robots/omni3/y");
  // The mean yaw rate over 2 s (the 10 ms speed loops make it ripple by a few per cent).
  double sum = 0;
  int samples = 0;
  while (sim->time_s() < 3.5) {
    sim->step();
    sum += sim->signal("robots/omni3/wz");
    ++samples;
  }
  EXPECT_NEAR(sum / samples, 1.0, 0.03) << "mean yaw rate";
  EXPECT_LT(std::hypot(sim->signal("robots/omni3/x") - x, sim->signal("robots/omni3/y") - y), 0.02)
      << "the centre wandered while turning";
}

}  // namespace
}  // namespace s2sim
