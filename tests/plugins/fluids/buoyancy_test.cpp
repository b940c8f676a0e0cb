// The buoyancy plugin: a neutrally buoyant body stays put, a box floats at its draft, rights
// itself when its metacentre is above its centre of mass and capsizes when it is below.
#include "fixture.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

namespace s2sim {
namespace {

using fluids_test::load;

TEST(Buoyancy, NeutrallyBuoyantBodyDriftsLessThanOneCentimetreInAMinute) {
  const double m = 0.05, r = 0.1;
  const double density = m / (4.0 / 3.0 * kPi * r * r * r);  // rho V = m
  auto sim = load("sphere_air", {{"ball_mass", m},
                                 {"ball_radius", r},
                                 {"cd", 0.47},
                                 {"fluid_density", density},
                                 {"start_z", 10}});
  sim->run_until(60.0);
  const double drift = std::abs(sim->signal("robots/ball/solids/ball/z") - 10);
  std::printf("  neutral: drift %.3g m in 60 s\n", drift);
  EXPECT_LT(drift, 0.01);
  EXPECT_NEAR(sim->signal("robots/ball/actuators/lift/immersed_fraction"), 1, 1e-12);
}

TEST(Buoyancy, FloatingBoxSettlesAtTheDraftWhereTheDisplacedWaterWeighsItsMass) {
  // 60 kg, 1 m x 0.6 m waterplane: draft = m / (rho L B) = 0.1 m; surface at z = 1 m.
  const double m = 60, draft = m / (1000 * 1 * 0.6);
  auto sim = load("floating_box", {{"hull_mass", m}, {"start_z", 1.15}});
  sim->run_until(20.0);
  const double bottom = sim->signal("robots/boat/solids/hull/z") - 0.2;
  const double measured = 1 - bottom;
  std::printf("  draft: %.5f m, computed %.5f m (%.3f %%)\n", measured, draft,
              100 * (measured - draft) / draft);
  EXPECT_NEAR(measured, draft, 0.01 * draft);
  EXPECT_NEAR(sim->signal("robots/boat/actuators/float/force"), m * kGravity_m_s2, 0.01 * m * 9.81);
}

TEST(Buoyancy, UprightCylinderSettlesAtTheDraftWhereTheDisplacedWaterWeighsItsMass) {
  // r = 0.3 m, L = 0.4 m: draft = m / (rho pi r^2); 0.09 m for this mass (GM = 0.095 m > 0).
  const double r = 0.3, draft = 0.09, m = 1000 * kPi * r * r * draft;
  auto sim = load("floating_cylinder", {{"buoy_mass", m}, {"start_z", 1.15}});
  sim->run_until(20.0);
  const double measured = 1 - (sim->signal("robots/buoy/solids/buoy/z") - 0.2);
  std::printf("  spar buoy draft: %.6f m, computed %.6f m (%.4f %%)\n", measured, draft,
              100 * (measured - draft) / draft);
  EXPECT_NEAR(measured, draft, 1e-3 * draft);
  EXPECT_NEAR(sim->signal("robots/buoy/actuators/float/force"), m * kGravity_m_s2,
              1e-3 * m * kGravity_m_s2);
}

double roll_deg_after(double t, std::map<std::string, double> constants) {
  auto sim = load("floating_box", std::move(constants));
  sim->run_until(t);
  return sim->signal("robots/boat/solids/hull/roll") * 180 / kPi;
}

TEST(Buoyancy, TiltedBoxWithItsMetacentreAboveItsCentreOfMassRightsItself) {
  // B = 0.6, T = 0.1, H = 0.4: GM = T/2 + B^2/(12 T) - H/2 = 0.05 + 0.3 - 0.2 = 0.15 m > 0.
  const double roll = roll_deg_after(20, {{"tilt_deg", 20}});
  std::printf("  stable hull: 20 deg -> %.4f deg after 20 s\n", roll);
  EXPECT_LT(std::abs(roll), 0.5);
}

TEST(Buoyancy, TiltedBoxWithItsMetacentreBelowItsCentreOfMassCapsizes) {
  // B = 0.2, T = 0.5, H = 0.6: GM = 0.25 + 0.04/6 - 0.3 = -0.043 m < 0.
  const double roll = roll_deg_after(
      20,
      {{"hull_mass", 100}, {"hull_y", 0.2}, {"hull_z", 0.6}, {"start_z", 0.8}, {"tilt_deg", 5}});
  std::printf("  unstable hull: 5 deg -> %.2f deg after 20 s\n", roll);
  EXPECT_GT(std::abs(roll), 30);
}

}  // namespace
}  // namespace s2sim
