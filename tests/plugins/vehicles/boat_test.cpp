// scenes/boat: floats at its computed draft and turns with differential thrust.
#include "scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace s2sim {
namespace {

const std::string kHull = "robots/boat/solids/hull/";

TEST(Boat, FloatsAtItsComputedDraft) {
  // Drifting still (no speed asked): draft = m / (rho L B) = 30 / (1000 * 1.2 * 0.5) = 0.05 m.
  auto sim = vehicles_test::load("boat", {{"speed", 0}});
  sim->run_until(15.0);
  const double draft = 0.5 - (sim->signal(kHull + "z") - 0.15), computed = 0.05;
  std::printf("  draft %.5f m, computed %.5f m (%.2f %%)\n", draft, computed,
              100 * (draft - computed) / computed);
  EXPECT_NEAR(draft, computed, 0.01 * computed);
}

// The viewer drew the boat over a grey floor: no water was drawn. The buoyancy shows its
// surface (StepContext::show_liquid_surface), and a reset shows it again.
TEST(Boat, ShowsTheWaterSurfaceItFloatsOn) {
  auto sim = vehicles_test::load("boat", {{"speed", 0}});
  for (int run = 0; run < 2; ++run) {
    const auto& surfaces = sim->annotations().liquid_surfaces;
    ASSERT_EQ(surfaces.size(), 1u) << "run " << run;
    EXPECT_EQ(surfaces[0].z_m, 0.5);
    EXPECT_EQ(surfaces[0].source, "robots/boat/actuators/float");
    EXPECT_GT(surfaces[0].rgba[2], surfaces[0].rgba[0]) << "blue";
    EXPECT_GT(surfaces[0].rgba[3], 0.1);
    EXPECT_LT(surfaces[0].rgba[3], 0.9) << "see-through";
    sim->step(10);
    sim->reset();
  }
}

TEST(Boat, TurnsWithDifferentialThrust) {
  auto sim = vehicles_test::load("boat");
  sim->run_until(10.0);
  EXPECT_NEAR(sim->signal(kHull + "yaw"), 0, 0.02);
  EXPECT_GT(sim->signal(kHull + "vx"), 0.4) << "both thrusters push it ahead";
  sim->set_input("robots/boat/controllers/pilot/heading_ref", kPi / 2);
  sim->step(100);
  const double right = sim->signal("robots/boat/actuators/right/thrust");
  const double left = sim->signal("robots/boat/actuators/left/thrust");
  std::printf("  turning: right thruster %.2f N, left %.2f N\n", right, left);
  EXPECT_GT(right - left, 1.0) << "turning left, the starboard thruster pushes harder";
  sim->run_until(30.0);
  const double yaw = sim->signal(kHull + "yaw");
  std::printf("  heading after 20 s: %.2f deg (asked 90)\n", yaw * 180 / kPi);
  EXPECT_NEAR(yaw, kPi / 2, 3 * kPi / 180);
  EXPECT_GT(sim->signal(kHull + "y"), 1.0) << "it went left";
}

}  // namespace
}  // namespace s2sim
