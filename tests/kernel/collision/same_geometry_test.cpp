// Acceptance test of the one collision world: contact and ray casting see the same geometry.
// For every shape kind (box, sphere, cylinder, an omni wheel's cylinder) against the ground
// plane, against every other kind and against a static obstacle, a contact is made; then a
// ray cast along the contact normal from just inside b (which a ray does not see from
// inside) must enter a at the contact point, and one cast back from inside a, beyond the
// overlap, must enter b (or the ground) within the contact's depth of that point.
#include "collision/contact_query.hpp"
#include "collision/placement.hpp"
#include "collision/ray_caster.hpp"
#include "collision/shape_table.hpp"
#include "scene_builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace s2sim::collision {
namespace {

enum class Kind { box, sphere, cylinder, omni };

const char* name(Kind k) {
  switch (k) {
    case Kind::box:
      return "box";
    case Kind::sphere:
      return "sphere";
    case Kind::cylinder:
      return "cylinder";
    case Kind::omni:
      return "omni wheel";
  }
  return "?";
}

scene::Geom geom(Kind k) {
  scene::Geom g;
  switch (k) {
    case Kind::box:
      g.shape.type = scene::ShapeType::box;
      g.shape.size_m = {0.3, 0.2, 0.25};
      break;
    case Kind::sphere:
      g.shape.type = scene::ShapeType::sphere;
      g.shape.radius_m = 0.12;
      break;
    case Kind::cylinder:
    case Kind::omni:
      g.shape.type = scene::ShapeType::cylinder;
      g.shape.radius_m = 0.1;
      g.shape.length_m = 0.08;
      if (k == Kind::omni) g.friction = scene::FrictionKind::omni;
      break;
  }
  return g;
}

scene::Body body(Kind k) {
  scene::Body b;
  b.id = name(k);
  b.mass_kg = 1;
  b.geoms.push_back(geom(k));
  return b;
}

constexpr double kDepth = 2e-3;  // how far the shapes are pushed into each other
constexpr double kSlack = 1e-9;  // round-off allowance on top of a contact's depth
/// FCL's GJK/EPA (libccd), which solves the pairs with a cylinder, finds the depth to about
/// 1e-4 m (its EPA tolerance): the ray, exact, may find b's surface that much further.
constexpr double kEpaSlack = 3e-4;

/// Casts the two rays through every point and checks what they meet.
void check_points(const std::string& what, RayCaster& rays, const ContactPoint* points, int n,
                  std::int32_t body_a, std::int32_t body_b, double slack_b = kSlack) {
  ASSERT_GT(n, 0) << what << ": no contact";
  for (int i = 0; i < n; ++i) {
    const ContactPoint& c = points[i];
    SCOPED_TRACE(what + ", point " + std::to_string(i));
    ASSERT_GT(c.depth_m, 0);
    // Into a, from inside b (or from under the ground): a's surface at the point.
    const RayHit into_a = rays.cast(c.point_m - c.normal * (0.5 * c.depth_m), c.normal, 1, -1);
    ASSERT_TRUE(into_a.hit);
    EXPECT_EQ(into_a.body.index, body_a);
    EXPECT_LE(norm(into_a.point_m - c.point_m), c.depth_m + kSlack);
    // Back into b, from inside a beyond the overlap: b's surface, the depth from the point.
    const RayHit into_b = rays.cast(c.point_m + c.normal * (1.5 * c.depth_m), -c.normal, 1, -1);
    ASSERT_TRUE(into_b.hit);
    EXPECT_EQ(into_b.body.index, body_b);
    EXPECT_LE(norm(into_b.point_m - c.point_m), c.depth_m + slack_b);
  }
}

const Mat3 kTilt = test::rotation_about({0.3, -0.5, 0.8}, 0.7);

TEST(SameGeometry, EveryKindOnTheGround) {
  for (Kind k : {Kind::box, Kind::sphere, Kind::cylinder, Kind::omni}) {
    scene::Scene sc;
    sc.bodies.push_back(body(k));
    const ShapeTable table(sc);
    const Shape& shape = table.shapes()[0];
    // Tilted, lowered until its lowest point (an omni wheel's: in its mid-plane) is kDepth
    // under the ground.
    const double az = kTilt.column(2).z;
    const double drop =
        shape.mid_plane ? shape.radius_m * std::sqrt(1 - az * az) : extent(shape, kTilt).z;
    std::vector<Pose> poses = {Pose{}, Pose{{0.4, -0.3, drop - kDepth}, kTilt}};
    Placement placement(table);
    placement.update(table, poses.data());
    RayCaster rays(table, poses.data());
    ContactPoint buffer[kMaxPointsPerPair], points[kMaxPointsPerPair];
    int n = 0;
    ContactQuery::plane_points(table, placement, 0, buffer,
                               [&](std::int32_t plane, const ContactPoint* found, int count) {
                                 EXPECT_EQ(plane, 0);  // the ground: no walls here
                                 std::copy(found, found + count, points);
                                 n = count;
                               });
    check_points(std::string(name(k)) + " on the ground", rays, points, n, 1, 0);
  }
}

/// Shape a (body 1) comes toward shape b along `direction` until they touch, then kDepth
/// further; b is body 2, or a static obstacle.
void check_pair(Kind ka, Kind kb, bool b_static) {
  scene::Scene sc;
  sc.settings.world_walls = false;
  sc.bodies.push_back(body(ka));
  if (b_static) {
    scene::Geom g = geom(kb);
    g.pose = {{0, 0, 2}, test::rotation_about({1, 1, 0}, 0.4)};
    sc.obstacles.push_back(g);
  } else {
    sc.bodies.push_back(body(kb));
  }
  const ShapeTable table(sc);
  const Pose pose_b{{0, 0, 2}, test::rotation_about({1, 1, 0}, 0.4)};
  const Vec3 direction = Vec3{-0.6, -0.3, -0.2} / norm(Vec3{-0.6, -0.3, -0.2});
  std::vector<Pose> poses = {Pose{}, Pose{}, pose_b};
  Placement placement(table);
  ContactQuery query(table);
  ContactPoint points[kMaxPointsPerPair];
  const std::int32_t a = 0, b = 1;
  auto points_at = [&](double s) {
    poses[1] = {pose_b.position - direction * s, kTilt};
    placement.update(table, poses.data());
    bool renumbered = false;
    return query.pair_points(table, placement, a, b, points, renumbered);
  };
  double s = 1;
  while (s > 0 && points_at(s) == 0)
    s -= 1e-4;
  const int n = points_at(s - kDepth);
  RayCaster rays(table, poses.data());
  const bool epa = ka == Kind::cylinder || kb == Kind::cylinder;
  check_points(std::string(name(ka)) + " against " + (b_static ? "a static " : "a ") + name(kb),
               rays, points, n, 1, b_static ? 0 : 2, epa ? kEpaSlack : kSlack);
}

TEST(SameGeometry, EveryPairOfKinds) {
  for (Kind ka : {Kind::box, Kind::sphere, Kind::cylinder})
    for (Kind kb : {Kind::box, Kind::sphere, Kind::cylinder}) {
      check_pair(ka, kb, false);
      check_pair(ka, kb, true);
    }
}

}  // namespace
}  // namespace s2sim::collision
