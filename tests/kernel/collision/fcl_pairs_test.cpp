// FCL pairs follow the narrow phase's conventions: normal from b toward a, points on a.
#include "collision/fcl_pairs.hpp"

#include <gtest/gtest.h>

namespace s2sim::collision {
namespace {

Shape box(double half) {
  Shape s;
  s.kind = ShapeKind::box;
  s.half_extents_m = {half, half, half};
  return s;
}
Shape cylinder(double radius, double half_length) {
  Shape s;
  s.kind = ShapeKind::cylinder;
  s.radius_m = radius;
  s.half_length_m = half_length;
  return s;
}

TEST(FclPairs, BoxOnBoxNormalPointsUpAndPointsLieOnTheUpperBox) {
  FclPairs fcl;
  ContactPoint out[4];
  // a (upper) overlaps b (lower) by 2 mm.
  const Pose pa{{0, 0, 0.198}, {}}, pb{{0, 0, 0}, {}};
  const int n = fcl.collide(box(0.1), pa, box(0.1), pb, out);
  ASSERT_EQ(n, 4);
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(out[i].normal.z, 1, 1e-9);
    EXPECT_NEAR(out[i].depth_m, 0.002, 1e-9);
    EXPECT_NEAR(out[i].point_m.z, 0.098, 1e-9);  // a's bottom face
  }
  // Same pair the other way round: the normal flips.
  const int m = fcl.collide(box(0.1), pb, box(0.1), pa, out);
  ASSERT_EQ(m, 4);
  EXPECT_NEAR(out[0].normal.z, -1, 1e-9);
  EXPECT_NEAR(out[0].point_m.z, 0.1, 1e-9);  // b's top face
}

TEST(FclPairs, CylinderAgainstBoxWall) {
  FclPairs fcl;
  ContactPoint out[4];
  // A cylinder (axis Z) 1 mm into a box wall on its +X side.
  const Pose pa{{0, 0, 0}, {}}, pb{{0.149, 0, 0}, {}};
  const int n = fcl.collide(cylinder(0.05, 0.1), pa, box(0.1), pb, out);
  ASSERT_GE(n, 1);
  EXPECT_NEAR(out[0].normal.x, -1, 1e-3);
  EXPECT_NEAR(out[0].depth_m, 0.001, 1e-4);
  EXPECT_NEAR(out[0].point_m.x, 0.05, 1e-3);
}

TEST(FclPairs, SeparatedShapesGiveNothing) {
  FclPairs fcl;
  ContactPoint out[4];
  EXPECT_EQ(fcl.collide(box(0.1), {{0, 0, 0.3}, {}}, box(0.1), {}, out), 0);
  EXPECT_EQ(fcl.collide(cylinder(0.1, 0.1), {{0, 0, 0.3}, {}}, box(0.1), {}, out), 0);
}

}  // namespace
}  // namespace s2sim::collision
