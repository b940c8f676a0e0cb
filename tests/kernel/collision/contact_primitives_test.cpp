// Analytic narrow phase against hand-computed answers.
#include "collision/contact_primitives.hpp"
#include "scene_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace s2sim::collision {
namespace {

const Plane kGround{{0, 0, 1}, 0};

TEST(Primitives, BoxCornersBelowThePlane) {
  Shape s;
  s.kind = ShapeKind::box;
  s.half_extents_m = {0.1, 0.2, 0.3};
  ContactPoint out[kMaxPointsPerPair];
  const int n = plane_contacts(s, {{0, 0, 0.299}, {}}, kGround, out);
  ASSERT_EQ(n, 4);
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(out[i].depth_m, 0.001, 1e-12);
    EXPECT_NEAR(out[i].point_m.z, -0.001, 1e-12);  // the corner itself, on the box
    EXPECT_EQ(out[i].normal, (Vec3{0, 0, 1}));
  }
  // Tilted 45 degrees about X: one edge down, two corners.
  const Mat3 r = test::rotation_about({1, 0, 0}, kPi / 4);
  const double reach = (0.2 + 0.3) / std::sqrt(2.0);
  EXPECT_EQ(plane_contacts(s, {{0, 0, reach - 1e-4}, r}, kGround, out), 2);
}

TEST(Primitives, WheelTouchesOnItsRimAtRadiusFromTheAxle) {
  // A wheel of radius 0.05 turning about world Y (cylinder Z along Y), 1 mm into the ground.
  Shape s;
  s.kind = ShapeKind::cylinder;
  s.radius_m = 0.05;
  s.half_length_m = 0.01;
  const Pose pose{{0, 0, 0.049}, test::rotation_about({1, 0, 0}, kPi / 2)};
  ContactPoint out[kMaxPointsPerPair];
  const int n = plane_contacts(s, pose, kGround, out);
  ASSERT_EQ(n, 2);  // one per edge of the tread
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(out[i].depth_m, 0.001, 1e-12);
    EXPECT_NEAR(norm(Vec3{out[i].point_m.x, 0, out[i].point_m.z - 0.049}), 0.05, 1e-12);
    EXPECT_NEAR(std::abs(out[i].point_m.y), 0.01, 1e-12);
  }
  // Standing on a cap: a tripod of rim points.
  EXPECT_EQ(plane_contacts(s, {{0, 0, 0.0099}, {}}, kGround, out), 3);
}

TEST(Primitives, AHullOnThePlaneGivesVertexPointsAndAPoseOfNaNsNoGarbageFeature) {
  // A flat sole of 12 vertices, more than a pair keeps: the deepest and the extreme ones.
  scene::ConvexHull hull;
  for (int k = 0; k < 12; ++k) {
    const double a = 2 * kPi * k / 12;
    hull.vertices.push_back({0.1 * std::cos(a), 0.1 * std::sin(a), 0});
  }
  hull.vertices.push_back({0, 0, 0.05});
  Shape s;
  s.kind = ShapeKind::convex;
  s.hull = &hull;
  // A body whose state diverged (a fuzzed placement 2e9 m under the floor did this): every
  // vertex compares false; the points must still name vertices of the hull, not whatever the
  // stack held (first, so that no earlier call left valid indices there).
  ContactPoint out[kMaxPointsPerPair];
  const double nan = std::nan("");
  const int m = plane_contacts(s, {{nan, nan, nan}, {}}, kGround, out);
  for (int i = 0; i < m; ++i) {
    EXPECT_GE(out[i].feature, 0);
    EXPECT_LT(out[i].feature, 13);
  }
  const int n = plane_contacts(s, {{0, 0, -0.001}, {}}, kGround, out);
  ASSERT_GE(n, 4);  // the deepest and the extremes along the plane's directions, no repeats
  ASSERT_LE(n, kMaxPointsPerPair);
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(out[i].depth_m, 0.001, 1e-12);
    EXPECT_GE(out[i].feature, 0);
    EXPECT_LT(out[i].feature, 12);
  }
}

TEST(Primitives, SphereContacts) {
  ContactPoint out[1];
  Shape s;
  s.kind = ShapeKind::sphere;
  s.radius_m = 0.1;
  ASSERT_EQ(plane_contacts(s, {{1, 2, 0.09}, {}}, kGround, out), 1);
  EXPECT_NEAR(out[0].depth_m, 0.01, 1e-12);
  EXPECT_NEAR(out[0].point_m.z, -0.01, 1e-12);
  ASSERT_EQ(sphere_sphere(0.1, {0, 0, 0.19}, 0.1, {0, 0, 0}, out), 1);
  EXPECT_NEAR(out[0].normal.z, 1, 1e-12);
  EXPECT_NEAR(out[0].point_m.z, 0.09, 1e-12);
  EXPECT_EQ(sphere_sphere(0.1, {0, 0, 0.21}, 0.1, {0, 0, 0}, out), 0);
  // A sphere on a box's top face and beside an edge.
  ASSERT_EQ(sphere_box(0.1, {0, 0, 0.195}, {0.1, 0.1, 0.1}, {}, out), 1);
  EXPECT_NEAR(out[0].normal.z, 1, 1e-12);
  EXPECT_NEAR(out[0].depth_m, 0.005, 1e-12);
  ASSERT_EQ(sphere_box(0.1, {0.15, 0, 0.15}, {0.1, 0.1, 0.1}, {}, out), 1);
  EXPECT_NEAR(out[0].normal.x, std::sqrt(0.5), 1e-12);
  // Swapping roles moves the point to the box's surface and flips the normal.
  swap_roles(out, 1);
  EXPECT_NEAR(out[0].normal.x, -std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(out[0].point_m.x, 0.1, 1e-12);
  EXPECT_NEAR(out[0].point_m.z, 0.1, 1e-12);
}

}  // namespace
}  // namespace s2sim::collision
