// The AX-12-style servo: a step of the goal, the speed and torque limits, holding a load.
#include <s2sim/kernel/simulation.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace s2sim {
namespace {

namespace fs = std::filesystem;
const fs::path kArm = fs::path(S2SIM_SOURCE_DIR) / "tests/plugins/servo/fixtures/arm";

std::unique_ptr<Simulation> load_arm(double arm_mass = 0.05, double kd = 0.08) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  o.constants = {{"arm_mass", arm_mass}, {"servo_kd", kd}};
  return Simulation::load(kArm, o);
}

TEST(Servo, StepToSixtyDegreesWithinTheSpeedAndTorqueLimits) {
  auto sim = load_arm();
  const std::string a = "robots/arm/axes/shoulder/";
  const double goal = 60 * kPi / 180, speed_max = 114 * 2 * kPi / 60;
  sim->set_input(a + "ref_pos", goal);
  double max_w = 0, max_t = 0, reached = -1;
  while (sim->time_s() < 1.0) {
    sim->step();
    max_w = std::max(max_w, std::abs(sim->signal(a + "speed")));
    max_t = std::max(max_t, std::abs(sim->signal(a + "servo_torque")));
    const bool in = std::abs(sim->signal(a + "pos") - goal) < kPi / 180;
    if (!in)
      reached = -1;
    else if (reached < 0)
      reached = sim->time_s();
  }
  std::printf(
      "  60 deg: within 1 deg from %.3f s (speed-limited move %.3f s), max speed %.3f "
      "rad/s (limit %.3f), max torque %.3f N*m, final %.3f deg\n",
      reached, goal / speed_max, max_w, speed_max, max_t, sim->signal(a + "pos") * 180 / kPi);
  ASSERT_GT(reached, 0);
  EXPECT_LT(reached, goal / speed_max + 0.15);
  EXPECT_LT(max_w, speed_max);
  EXPECT_LE(max_t, 1.5);
}

TEST(Servo, MovingSpeedInputSlowsTheMoveAndGoalIsClampedToTheRange) {
  auto sim = load_arm();
  const std::string a = "robots/arm/axes/shoulder/";
  sim->set_input(a + "ref_speed", 1.0);
  sim->set_input(a + "ref_pos", 3.0);  // beyond 150°: clamped
  sim->run_until(1.0);
  EXPECT_NEAR(sim->signal(a + "servo_setpoint"), 1.0, 1e-9);  // 1 rad/s for 1 s
  sim->run_until(4.0);
  EXPECT_NEAR(sim->signal(a + "servo_setpoint"), 150 * kPi / 180, 1e-12);
}

TEST(Servo, AWeightBeyondTheStallTorqueIsNotHeld) {
  // 4 kg at 5 cm needs 1.96 N·m at the horizontal, more than the AX-12's 1.5.
  auto sim = load_arm(4.0);
  const std::string a = "robots/arm/axes/shoulder/";
  sim->run_until(1.0);
  // Saturated: the torque-speed line, never more than the stall torque (back-driven too).
  const double speed_max = 114 * 2 * kPi / 60;
  double max_t = 0;
  while (sim->time_s() < 2.0) {
    sim->step();
    max_t = std::max(max_t, std::abs(sim->signal(a + "servo_torque")));
  }
  const double w = sim->signal(a + "speed"), line = std::min(1.5, 1.5 * (1 - w / speed_max));
  std::printf("  4 kg: torque %.4f N*m (line %.4f), max %.4f, pos %.3f rad, speed %.3f rad/s\n",
              sim->signal(a + "servo_torque"), line, max_t, sim->signal(a + "pos"), w);
  EXPECT_NEAR(sim->signal(a + "servo_torque"), line, 0.05);
  EXPECT_LE(max_t, 1.5);
  EXPECT_LT(sim->signal(a + "pos"), -0.5) << "the arm should sag";
}

TEST(Servo, StrongSpeedFeedbackOnALightArmSettlesAtOneMillisecond) {
  // The 50 g, 10 cm arm turns at 1.7e-4 kg·m²: kd = 0.5 N·m·s/rad applied as an explicit force
  // would give kd·dt/I = 3.0 and diverge; the servo hands it to the kernel as an implicit drive.
  auto sim = load_arm(0.05, 0.5);
  const std::string a = "robots/arm/axes/shoulder/";
  const double goal = 30 * kPi / 180, speed_max = 114 * 2 * kPi / 60;
  sim->set_input(a + "ref_pos", goal);
  double max_w = 0;
  while (sim->time_s() < 1.0) {
    sim->step();
    max_w = std::max(max_w, std::abs(sim->signal(a + "speed")));
  }
  std::printf("  kd 0.5: final %.4f deg, max speed %.3f rad/s, final speed %.2e rad/s\n",
              sim->signal(a + "pos") * 180 / kPi, max_w, sim->signal(a + "speed"));
  EXPECT_NEAR(sim->signal(a + "pos"), goal, 0.5 * kPi / 180);
  EXPECT_LT(max_w, speed_max);
  EXPECT_LT(std::abs(sim->signal(a + "speed")), 1e-6);
}

}  // namespace
}  // namespace s2sim
