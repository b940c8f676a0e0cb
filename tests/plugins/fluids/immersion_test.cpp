// The immersed volume and centroid of box, cylinder and sphere hulls against closed forms and
// a fine grid count.
#include "immersion.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace s2sim::fluids {
namespace {

Mat3 rotation_xyz(double ax, double ay, double az) {
  const double cx = std::cos(ax), sx = std::sin(ax), cy = std::cos(ay), sy = std::sin(ay),
               cz = std::cos(az), sz = std::sin(az);
  Mat3 rx{{{1, 0, 0}, {0, cx, -sx}, {0, sx, cx}}};
  Mat3 ry{{{cy, 0, sy}, {0, 1, 0}, {-sy, 0, cy}}};
  Mat3 rz{{{cz, -sz, 0}, {sz, cz, 0}, {0, 0, 1}}};
  return rz * ry * rx;
}

TEST(Immersion, LevelBoxIsItsDraftTimesItsWaterplane) {
  const Pose hull{{0, 0, 0.1}, Mat3::identity()};
  const Immersion im = immersed_box(hull, {1, 0.6, 0.4}, 0.0);
  EXPECT_NEAR(im.volume_m3, 1 * 0.6 * 0.1, 1e-12);
  EXPECT_NEAR(im.centroid_m.z, -0.05, 1e-12);
  EXPECT_NEAR(im.centroid_m.x, 0, 1e-12);
  EXPECT_NEAR(immersed_box(hull, {1, 0.6, 0.4}, 1.0).volume_m3, 0.24, 1e-12);  // all under
  EXPECT_EQ(immersed_box(hull, {1, 0.6, 0.4}, -1.0).volume_m3, 0);             // all above
}

TEST(Immersion, TiltedBoxCutThroughItsCentreIsHalfUnder) {
  // A plane through the centre of a centrally symmetric body halves it.
  const Pose hull{{0.3, -0.2, 0.5}, rotation_xyz(0.4, -0.7, 1.1)};
  const Immersion im = immersed_box(hull, {1, 0.6, 0.4}, 0.5);
  EXPECT_NEAR(im.volume_m3, 0.12, 1e-12);
  EXPECT_LT(im.centroid_m.z, 0.5);
}

TEST(Immersion, TiltedBoxMatchesAGridCount) {
  const Pose hull{{0, 0, 0.05}, rotation_xyz(0.35, 0.2, 0.3)};
  const Vec3 size{1, 0.6, 0.4};
  const Immersion im = immersed_box(hull, size, 0.0);
  const int n = 200;
  double count = 0;
  Vec3 sum;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Vec3 local{((i + 0.5) / n - 0.5) * size.x, ((j + 0.5) / n - 0.5) * size.y,
                         ((k + 0.5) / n - 0.5) * size.z};
        const Vec3 p = hull * local;
        if (p.z < 0) {
          count += 1;
          sum += p;
        }
      }
  const double cell = size.x * size.y * size.z / (double(n) * n * n);
  EXPECT_NEAR(im.volume_m3, count * cell, 2e-3 * im.volume_m3);
  const Vec3 c = sum / count;
  EXPECT_NEAR(im.centroid_m.x, c.x, 2e-3);
  EXPECT_NEAR(im.centroid_m.y, c.y, 2e-3);
  EXPECT_NEAR(im.centroid_m.z, c.z, 2e-3);
}

TEST(Immersion, LevelCylinderHalfUnderHasItsCentroidAtFourRThirdPi) {
  // Axis along world X (local Z turned by 90° about Y), surface through the axis.
  const double r = 0.2, length = 1.5;
  const Pose hull{{0, 0, 0}, rotation_xyz(0, kPi / 2, 0)};
  const Immersion im = immersed_cylinder(hull, r, length, 0.0);
  EXPECT_NEAR(im.volume_m3, 0.5 * kPi * r * r * length, 1e-12);
  EXPECT_NEAR(im.centroid_m.z, -4 * r / (3 * kPi), 1e-12);
  // A quarter of the radius under: the circular segment's area.
  const double h = -0.5 * r;  // waterline 0.1 m below the axis
  const double segment = r * r * std::acos(-h / r) + h * std::sqrt(r * r - h * h);
  EXPECT_NEAR(immersed_cylinder(hull, r, length, h).volume_m3, segment * length, 1e-12);
}

TEST(Immersion, SphereCapVolumeAndCentroid) {
  const double r = 0.3;
  const Immersion half = immersed_sphere({0, 0, 1}, r, 1.0);
  EXPECT_NEAR(half.volume_m3, 2.0 / 3.0 * kPi * r * r * r, 1e-12);
  EXPECT_NEAR(half.centroid_m.z, 1 - 3 * r / 8, 1e-12);
  EXPECT_NEAR(immersed_sphere({0, 0, 1}, r, 2.0).volume_m3, 4.0 / 3.0 * kPi * r * r * r, 1e-12);
  EXPECT_NEAR(immersed_sphere({0, 0, 1}, r, 2.0).centroid_m.z, 1, 1e-12);
  EXPECT_EQ(immersed_sphere({0, 0, 1}, r, 0.0).volume_m3, 0);
}

}  // namespace
}  // namespace s2sim::fluids
