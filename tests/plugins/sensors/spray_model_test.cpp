// The spray gun's model (plugins/sensors/spray_model.hpp) against closed forms: the solid
// angle of a triangle, the cone's weight, the angle off the beam.
#include "spray_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace s2sim::sensors::spray {
namespace {

TEST(SprayModel, AnOctantsTriangleSubtendsAnEighthOfTheSphere) {
  EXPECT_NEAR(solid_angle({1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 4 * kPi / 8, 1e-12);
  // Either winding, any distance.
  EXPECT_NEAR(solid_angle({0, 0, 3}, {0, 3, 0}, {3, 0, 0}), kPi / 2, 1e-12);
}

TEST(SprayModel, ASmallTriangleSubtendsItsAreaTimesTheCosineOverTheDistanceSquared) {
  // A 1 mm right triangle 0.5 m away, tilted 30° off facing the origin.
  const double a = 1e-3, r = 0.5, tilt = 30 * kPi / 180;
  const Vec3 c{0, 0, r};
  const Vec3 u{std::cos(tilt), 0, std::sin(tilt)}, v{0, 1, 0};
  const Vec3 p = c + u * a, q = c + v * a;
  const double omega = solid_angle(c, p, q);
  const Vec3 centre = (c + p + q) * (1.0 / 3);
  const Vec3 n = cross(u, v);
  const double d = norm(centre);
  EXPECT_NEAR(omega, (a * a / 2) * std::abs(dot(n, centre)) / (d * d * d), 1e-5 * omega);
}

TEST(SprayModel, TheConesWeightIsTheProfilesIntegralOverTheCap) {
  // Small angles: W = 2π σ² (1 − exp(−θ²/2σ²)) to the order of θ² (sin θ ≈ θ).
  const double theta = 0.01, sigma = 0.005;
  EXPECT_NEAR(cone_weight(theta, sigma), 2 * kPi * sigma * sigma * (1 - std::exp(-2.0)),
              1e-4 * cone_weight(theta, sigma));
  // A flat profile over a hemisphere: 2π.
  EXPECT_NEAR(cone_weight(kPi / 2, 1e6), 2 * kPi, 1e-9);
  // A flat profile over any cap: 2π (1 − cos θ).
  EXPECT_NEAR(cone_weight(0.2, 1e6), 2 * kPi * (1 - std::cos(0.2)), 1e-12);
}

TEST(SprayModel, AngleOffTheBeam) {
  EXPECT_NEAR(angle_off({1, 0, 0}, {1, 1, 0}, std::sqrt(2.0)), kPi / 4, 1e-15);
  EXPECT_EQ(angle_off({1, 0, 0}, {2, 0, 0}, 2), 0);
  EXPECT_NEAR(profile(0.1, 0.1), std::exp(-0.5), 1e-16);
}

}  // namespace
}  // namespace s2sim::sensors::spray
