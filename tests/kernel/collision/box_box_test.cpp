// The kernel's box-box against FCL's boxBox2 (through FclPairs): the same points, normals,
// depths and point order on thousands of random pairs of every kind of contact (face-face,
// edge-edge, vertex-face, tilted, deep, grazing, within the speculative margin). The point
// order matters: ContactWorld::match_features matches points to its memory greedily in order.
#include "collision/box_box.hpp"
#include "collision/fcl_pairs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

namespace s2sim::collision {
namespace {

constexpr double kTolerance_m = 1e-9;

Shape box(const Vec3& half) {
  Shape s;
  s.kind = ShapeKind::box;
  s.half_extents_m = half;
  return s;
}

Mat3 rotation_about(Vec3 axis, double angle_rad) {
  axis = axis / norm(axis);
  const double h = 0.5 * angle_rad, s = std::sin(h);
  return to_matrix(Quat{std::cos(h), axis.x * s, axis.y * s, axis.z * s});
}

/// One family of configurations: how b is placed against a.
enum class Family { face_face, tilted, edge_edge, vertex_face, deep, grazing, margin, random };

const char* name(Family f) {
  switch (f) {
    case Family::face_face:
      return "face-face";
    case Family::tilted:
      return "tilted";
    case Family::edge_edge:
      return "edge-edge";
    case Family::vertex_face:
      return "vertex-face";
    case Family::deep:
      return "deep";
    case Family::grazing:
      return "grazing";
    case Family::margin:
      return "margin";
    case Family::random:
      return "random";
  }
  return "?";
}

struct Case {
  Vec3 half_a, half_b;
  Pose pose_a, pose_b;
  double margin_m = 0;
};

/// A random pair of the family: b is put on top of a (along a's +Z turned by a random
/// rotation of the whole pair), at a gap or overlap that the family chooses.
Case make_case(Family family, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1, 1), size(0.02, 0.3), angle(-kPi, kPi);
  auto random_axis = [&] { return Vec3{unit(rng), unit(rng), unit(rng) + 1e-3}; };
  Case c;
  c.half_a = {size(rng), size(rng), size(rng)};
  c.half_b = {size(rng), size(rng), size(rng)};
  Mat3 turn_a, turn_b;  // a and b in the pair's frame
  Vec3 offset;          // b's centre relative to a's, in a's frame, before the overlap is set
  double overlap_m = std::uniform_real_distribution<double>(0, 3e-3)(rng);
  switch (family) {
    case Family::face_face:  // aligned but for a yaw about the shared normal
      turn_b = rotation_about({0, 0, 1}, angle(rng));
      offset = {0.5 * unit(rng) * c.half_a.x, 0.5 * unit(rng) * c.half_a.y, 0};
      break;
    case Family::tilted:  // a few degrees off face-face: one edge or corner lower
      turn_b =
          rotation_about({0, 0, 1}, angle(rng)) * rotation_about(random_axis(), 0.1 * unit(rng));
      offset = {0.5 * unit(rng) * c.half_a.x, 0.5 * unit(rng) * c.half_a.y, 0};
      break;
    case Family::edge_edge:  // a's edge up (45° about Y), b's edge down (45° about X), crossed
      turn_a = rotation_about({0, 1, 0}, kPi / 4 + 0.05 * unit(rng));
      turn_b = rotation_about({0, 0, 1}, 0.5 * unit(rng)) *
               rotation_about({1, 0, 0}, kPi / 4 + 0.05 * unit(rng));
      offset = {0.01 * unit(rng), 0.01 * unit(rng), 0};
      break;
    case Family::vertex_face:  // a corner of b down onto a's face
      turn_b = rotation_about({1, 1, 0}, 0.9553166181245093 + 0.05 * unit(rng)) *
               rotation_about({0, 0, 1}, 0.1 * unit(rng));
      offset = {0.3 * unit(rng) * c.half_a.x, 0.3 * unit(rng) * c.half_a.y, 0};
      break;
    case Family::deep:  // overlaps of a quarter of the smaller box
      turn_b = rotation_about(random_axis(), angle(rng));
      offset = {0.5 * unit(rng) * c.half_a.x, 0.5 * unit(rng) * c.half_a.y, 0};
      overlap_m = 0.25 * std::min(c.half_a.z, c.half_b.z) * (1 + unit(rng));
      break;
    case Family::grazing:  // overlaps of nanometres
      turn_b =
          rotation_about({0, 0, 1}, angle(rng)) * rotation_about(random_axis(), 0.02 * unit(rng));
      offset = {0.5 * unit(rng) * c.half_a.x, 0.5 * unit(rng) * c.half_a.y, 0};
      overlap_m = 1e-8 * (1 + unit(rng));
      break;
    case Family::margin:  // apart by up to 4 mm, with a 3 mm margin
      turn_b =
          rotation_about({0, 0, 1}, angle(rng)) * rotation_about(random_axis(), 0.05 * unit(rng));
      offset = {0.5 * unit(rng) * c.half_a.x, 0.5 * unit(rng) * c.half_a.y, 0};
      overlap_m = -4e-3 * 0.5 * (1 + unit(rng));
      c.margin_m = 3e-3;
      break;
    case Family::random:  // anywhere around a, any orientation
      turn_b = rotation_about(random_axis(), angle(rng));
      offset = Vec3{unit(rng), unit(rng), 0} * 0.3;
      overlap_m = 0.05 * unit(rng);
      c.margin_m = unit(rng) > 0 ? 2e-3 : 0;
      break;
  }
  // Lower b along the pair's Z until its lowest point is overlap_m below a's highest.
  auto height = [](const Mat3& turn, const Vec3& half) {
    return std::abs(turn.m[2][0]) * half.x + std::abs(turn.m[2][1]) * half.y +
           std::abs(turn.m[2][2]) * half.z;
  };
  offset.z = height(turn_a, c.half_a) + height(turn_b, c.half_b) - overlap_m;
  // Turn and place the whole pair anywhere.
  const Mat3 world = rotation_about(random_axis(), angle(rng));
  c.pose_a = {Vec3{unit(rng), unit(rng), unit(rng)}, world * turn_a};
  c.pose_b = {c.pose_a.position + world * offset, world * turn_b};
  return c;
}

std::string describe(const Case& c) {
  char text[400];
  std::snprintf(text, sizeof text,
                "a (%.17g, %.17g, %.17g) at (%.17g, %.17g, %.17g), b (%.17g, %.17g, %.17g) at "
                "(%.17g, %.17g, %.17g), margin %g",
                c.half_a.x, c.half_a.y, c.half_a.z, c.pose_a.position.x, c.pose_a.position.y,
                c.pose_a.position.z, c.half_b.x, c.half_b.y, c.half_b.z, c.pose_b.position.x,
                c.pose_b.position.y, c.pose_b.position.z, c.margin_m);
  return text;
}

double distance(const Vec3& x, const Vec3& y) {
  return norm(x - y);
}

/// Compares the two narrow phases on one case: returns whether they agree (same count and
/// features, numbers within the tolerance) and sets `points` and `identical` (to the bit).
bool agree(FclPairs& fcl, const Case& c, int& points, bool& identical) {
  ContactPoint ours[kMaxBoxBoxPoints], theirs[kMaxBoxBoxPoints];
  const int n = box_box(c.half_a, c.pose_a, c.half_b, c.pose_b, ours, c.margin_m);
  const int m = fcl.collide(box(c.half_a), c.pose_a, box(c.half_b), c.pose_b, theirs, c.margin_m);
  points = n;
  identical = n == m;
  EXPECT_EQ(n, m) << describe(c);
  bool close = n == m;
  for (int i = 0; close && i < n; ++i) {
    const ContactPoint &x = ours[i], &y = theirs[i];
    const bool same = distance(x.point_m, y.point_m) < kTolerance_m &&
                      distance(x.normal, y.normal) < kTolerance_m &&
                      std::abs(x.depth_m - y.depth_m) < kTolerance_m && x.feature == y.feature;
    EXPECT_TRUE(same) << "point " << i << " of " << n << ": ours at (" << x.point_m.x << ", "
                      << x.point_m.y << ", " << x.point_m.z << ") depth " << x.depth_m
                      << ", FCL's at (" << y.point_m.x << ", " << y.point_m.y << ", " << y.point_m.z
                      << ") depth " << y.depth_m << "; " << describe(c);
    close = close && same;
    identical =
        identical && x.point_m == y.point_m && x.normal == y.normal && x.depth_m == y.depth_m;
  }
  return close;
}

TEST(BoxBox, SameContactsAsFclsBoxBox2OnRandomPairs) {
  FclPairs fcl;
  std::mt19937 rng(17);
  constexpr int kPerFamily = 2000;
  for (Family family : {Family::face_face, Family::tilted, Family::edge_edge, Family::vertex_face,
                        Family::deep, Family::grazing, Family::margin, Family::random}) {
    int touching = 0, identical = 0, points = 0;
    int by_count[kMaxBoxBoxPoints + 1] = {};
    for (int k = 0; k < kPerFamily; ++k) {
      int n = 0;
      bool same = false;
      ASSERT_TRUE(agree(fcl, make_case(family, rng), n, same)) << name(family) << ", case " << k;
      touching += n > 0;
      identical += same;
      points += n;
      ++by_count[n];
    }
    // Each family must exercise contact (a generator that misses would compare nothing); some
    // of its pairs miss on purpose (b's lowest corner beyond a's face, a grazing gap).
    EXPECT_GT(touching, kPerFamily / 5) << name(family);
    std::printf(
        "%-12s %d pairs, %d touching, %d points (0:%d 1:%d 2:%d 3:%d 4:%d), %d identical "
        "to the bit\n",
        name(family), kPerFamily, touching, points, by_count[0], by_count[1], by_count[2],
        by_count[3], by_count[4], identical);
  }
}

TEST(BoxBox, FaceOnFaceGivesFourCornersAtTheirDepth) {
  // a (upper) 2 mm into b (lower), a smaller than b: a's four bottom corners.
  ContactPoint out[kMaxBoxBoxPoints];
  const Pose pa{{0, 0, 0.148}, {}}, pb{{0, 0, 0}, {}};
  const int n = box_box({0.05, 0.05, 0.05}, pa, {0.1, 0.1, 0.1}, pb, out);
  ASSERT_EQ(n, 4);
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(out[i].normal.z, 1, 1e-12);
    EXPECT_NEAR(out[i].depth_m, 0.002, 1e-12);
    EXPECT_NEAR(out[i].point_m.z, 0.098, 1e-12);  // a's bottom face
    EXPECT_NEAR(std::abs(out[i].point_m.x), 0.05, 1e-12);
    EXPECT_NEAR(std::abs(out[i].point_m.y), 0.05, 1e-12);
    EXPECT_EQ(out[i].feature, i);
  }
}

TEST(BoxBox, EdgeOnEdgeGivesOnePointBetweenTheEdges) {
  // b turned 45° about X (an edge along X at its bottom), a turned 45° about Y (an edge along
  // Y at its top), b 1 mm down into a: one point at the crossing, normal along Z.
  const double h = 0.1, r = h * std::sqrt(2.0);
  const Pose pa{{0, 0, 0}, rotation_about({0, 1, 0}, kPi / 4)};
  const Pose pb{{0, 0, 2 * r - 0.001}, rotation_about({1, 0, 0}, kPi / 4)};
  ContactPoint out[kMaxBoxBoxPoints];
  const int n = box_box({h, h, h}, pa, {h, h, h}, pb, out);
  ASSERT_EQ(n, 1);
  EXPECT_NEAR(out[0].normal.z, -1, 1e-9);  // from b (above) toward a
  EXPECT_NEAR(out[0].depth_m, 0.001, 1e-9);
  EXPECT_NEAR(out[0].point_m.z, r, 1e-9);  // a's top edge
  EXPECT_NEAR(out[0].point_m.x, 0, 1e-9);
  EXPECT_NEAR(out[0].point_m.y, 0, 1e-9);
}

TEST(BoxBox, WithinTheMarginGivesNegativeDepthsAndBeyondItNothing) {
  ContactPoint out[kMaxBoxBoxPoints];
  const Vec3 half{0.1, 0.1, 0.1};
  const Pose below{{0, 0, 0}, {}};
  const Pose gap_2mm{{0, 0, 0.202}, {}};
  const int n = box_box(half, gap_2mm, half, below, out, 0.003);
  ASSERT_EQ(n, 4);
  for (int i = 0; i < n; ++i)
    EXPECT_NEAR(out[i].depth_m, -0.002, 1e-12);
  EXPECT_EQ(box_box(half, gap_2mm, half, below, out, 0.0015), 0);
  EXPECT_EQ(box_box(half, gap_2mm, half, below, out), 0);
}

}  // namespace
}  // namespace s2sim::collision
