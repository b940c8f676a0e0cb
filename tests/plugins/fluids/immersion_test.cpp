// The immersed volume and centroid of box, cylinder and sphere hulls against closed forms and
// a fine grid count.
#include "immersion.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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

TEST(Immersion, UprightCylinderIsItsDraftTimesItsWaterplaneAtAnyDraft) {
  // A spar buoy: the volume grows linearly with the draft, with no steps at any depth.
  const double r = 0.1, length = 1.0;
  for (const Mat3& turn : {Mat3::identity(), rotation_xyz(kPi, 0, 0)})
    for (double draft : {0.0, 1e-9, 0.0123456, 0.3051, 0.5, 0.77777, 1.0, 1.5}) {
      const Pose hull{{0.2, -0.1, 0.5}, turn};  // bottom at z = 0
      const Immersion im = immersed_cylinder(hull, r, length, draft);
      const double under = std::min(draft, length);
      EXPECT_NEAR(im.volume_m3, kPi * r * r * under, 1e-15) << draft;
      if (under > 0) {
        EXPECT_NEAR(im.centroid_m.z, 0.5 * under, 1e-12) << draft;
      }
    }
}

TEST(Immersion, TiltedCylinderCutThroughItsCentreIsHalfUnder) {
  const double r = 0.15, length = 0.8;
  for (double tilt : {1e-9, 1e-4, 0.3, 0.9, 1.4, kPi / 2 - 1e-6}) {
    const Pose hull{{0.3, -0.2, 0.5}, rotation_xyz(tilt, 0, 0.7)};
    const Immersion im = immersed_cylinder(hull, r, length, 0.5);
    EXPECT_NEAR(im.volume_m3, 0.5 * kPi * r * r * length, 1e-14) << tilt;
    EXPECT_LT(im.centroid_m.z, 0.5) << tilt;
  }
}

// An independent reference: plain slabs across the axis, each a disk cut by the waterline
// where the slab's centre meets it (converges as the slab count squared).
Immersion cylinder_by_slabs(const Pose& hull, double r, double length, double surface, int n) {
  const Vec3 axis = hull.rotation.column(2), tilt = Vec3{0, 0, 1} - axis * axis.z;
  const double sin_t = norm(tilt), ds = length / n;
  double volume = 0;
  Vec3 moment;
  for (int k = 0; k < n; ++k) {
    const Vec3 c = hull.position + axis * ((k + 0.5) * ds - 0.5 * length);
    const double h = std::clamp((surface - c.z) / sin_t, -r, r), w = std::sqrt(r * r - h * h);
    const double area = r * r * std::acos(-h / r) + h * w;
    volume += area * ds;
    moment += (c + tilt / sin_t * (-2.0 / 3.0 * w * w * w / std::max(area, 1e-300))) * area * ds;
  }
  return {volume, moment / volume};
}

TEST(Immersion, TiltedCylinderMatchesFineSlabsWhetherTheWaterlineCrossesItsSidesOrItsCaps) {
  const double r = 0.12, length = 0.9;
  struct Case {
    double tilt, surface;
  } cases[] = {{0.2, 0.05}, {0.2, 0.4}, {0.8, -0.1}, {1.2, 0.02}, {0.05, 0.3}, {1.5, -0.08}};
  for (const auto& c : cases) {
    const Pose hull{{0.1, 0.2, 0.0}, rotation_xyz(c.tilt, 0.1, 0.4)};
    const Immersion im = immersed_cylinder(hull, r, length, c.surface);
    const Immersion ref = cylinder_by_slabs(hull, r, length, c.surface, 400000);
    ASSERT_GT(ref.volume_m3, 0);
    EXPECT_NEAR(im.volume_m3, ref.volume_m3, 1e-8 * ref.volume_m3) << c.tilt << " " << c.surface;
    EXPECT_NEAR(norm(im.centroid_m - ref.centroid_m), 0, 1e-8) << c.tilt << " " << c.surface;
  }
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
