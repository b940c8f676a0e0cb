// scenes/quadrotor: hovers within 2 cm of its set height and holds its heading against its
// propellers' drag torques, then flies its 2 m square.
#include "scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace s2sim {
namespace {

const std::string kFrame = "robots/quad/solids/frame/";

TEST(Quadrotor, HoversWithinTwoCentimetresAndHoldsItsHeading) {
  auto sim = vehicles_test::load("quadrotor", {{"hover_s", 100}});  // no square
  // Hover, then turn to 30 degrees and hold there: the propellers' drag torques (the motors'
  // reactions on the frame) are the only yaw actuator, and they must balance again after.
  const double yaw_ref = 30 * kPi / 180;
  sim->run_until(3.0);
  const double yaw_before = sim->signal(kFrame + "yaw");
  sim->set_input("robots/quad/controllers/pilot/yaw_ref", yaw_ref);
  sim->run_until(7.0);
  double worst_z = 0, worst_yaw = 0, worst_xy = 0, torque = 0;
  while (sim->time_s() < 10.0 - 1e-9) {
    sim->step(10);
    worst_z = std::max(worst_z, std::abs(sim->signal(kFrame + "z") - 1.0));
    worst_yaw = std::max(worst_yaw, std::abs(sim->signal(kFrame + "yaw") - yaw_ref));
    worst_xy = std::max(worst_xy, std::hypot(sim->signal(kFrame + "x"), sim->signal(kFrame + "y")));
    torque = std::max(torque, std::abs(sim->signal("robots/quad/actuators/m1/torque")));
  }
  std::printf(
      "  hover 7-10 s: |z - 1| <= %.4f m, |yaw - 30 deg| <= %.3f deg, |xy| <= %.4f m; "
      "one prop's drag torque %.4f N*m\n",
      worst_z, worst_yaw * 180 / kPi, worst_xy, torque);
  EXPECT_LT(worst_z, 0.02);
  EXPECT_LT(std::abs(yaw_before) * 180 / kPi, 1.0) << "heading held through the take-off";
  EXPECT_LT(worst_yaw * 180 / kPi, 1.0);
  EXPECT_GT(torque, 0.01) << "the reaction torques the pilot holds against";
}

TEST(Quadrotor, FliesItsTwoMetreSquare) {
  auto sim = vehicles_test::load("quadrotor");
  const double corners[4][2] = {{2, 0}, {2, 2}, {0, 2}, {0, 0}};
  double nearest[4] = {1e9, 1e9, 1e9, 1e9}, worst_z = 0;
  while (sim->time_s() < 8.0 + 4 * 6.0 - 1e-9) {
    sim->step(10);
    const double x = sim->signal(kFrame + "x"), y = sim->signal(kFrame + "y");
    const int leg = std::clamp(static_cast<int>((sim->time_s() - 8.0) / 6.0), -1, 3);
    if (leg >= 0) {
      nearest[leg] = std::min(nearest[leg], std::hypot(x - corners[leg][0], y - corners[leg][1]));
      worst_z = std::max(worst_z, std::abs(sim->signal(kFrame + "z") - 1.0));
    }
  }
  for (int i = 0; i < 4; ++i) {
    std::printf("  corner (%g, %g): nearest %.3f m\n", corners[i][0], corners[i][1], nearest[i]);
    EXPECT_LT(nearest[i], 0.1);
  }
  std::printf("  height held within %.3f m along the square\n", worst_z);
  EXPECT_LT(worst_z, 0.1);
}

}  // namespace
}  // namespace s2sim
