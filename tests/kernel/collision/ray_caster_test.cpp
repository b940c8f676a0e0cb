// Ray casting: every primitive, the ground and the walls, the ignored body, materials, and
// the broad phase against brute force on a random cluttered scene.
#include "collision/ray_caster.hpp"
#include "collision/ray_primitives.hpp"
#include "kernel/model/scene_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace s2sim::collision {
namespace {

constexpr double kTol = 1e-12;

Mat3 rot_axis(const Vec3& axis, double angle) {
  return test::rotation_about(axis, angle);
}

scene::Geom box_geom(Vec3 size, Pose pose) {
  scene::Geom g;
  g.shape.type = scene::ShapeType::box;
  g.shape.size_m = size;
  g.pose = pose;
  return g;
}
scene::Geom sphere_geom(double r, Pose pose) {
  scene::Geom g;
  g.shape.type = scene::ShapeType::sphere;
  g.shape.radius_m = r;
  g.pose = pose;
  return g;
}
scene::Geom cylinder_geom(double r, double len, Pose pose) {
  scene::Geom g;
  g.shape.type = scene::ShapeType::cylinder;
  g.shape.radius_m = r;
  g.shape.length_m = len;
  g.pose = pose;
  return g;
}

TEST(RayPrimitives, BoxSlabEntersTheNearFaceWithItsNormal) {
  double t = 0;
  Vec3 n;
  ASSERT_TRUE(ray_box({-3, 0.2, 0.1}, {1, 0, 0}, {1, 0.5, 0.5}, 10, t, n));
  EXPECT_NEAR(t, 2, kTol);
  EXPECT_EQ(n, (Vec3{-1, 0, 0}));
  ASSERT_TRUE(ray_box({0.3, 0.1, 5}, {0, 0, -1}, {1, 0.5, 0.5}, 10, t, n));
  EXPECT_NEAR(t, 4.5, kTol);
  EXPECT_EQ(n, (Vec3{0, 0, 1}));
  EXPECT_FALSE(ray_box({-3, 0.2, 0.1}, {1, 0, 0}, {1, 0.5, 0.5}, 1.9, t, n));  // too short
  EXPECT_FALSE(ray_box({-3, 0.6, 0.1}, {1, 0, 0}, {1, 0.5, 0.5}, 10, t, n));   // beside
  EXPECT_FALSE(ray_box({3, 0, 0}, {1, 0, 0}, {1, 0.5, 0.5}, 10, t, n));        // behind
  EXPECT_FALSE(ray_box({0, 0, 0}, {1, 0, 0}, {1, 0.5, 0.5}, 10, t, n));        // inside
  const double s = 1 / std::sqrt(2.0);
  ASSERT_TRUE(ray_box({-2, -2, 0}, {s, s, 0}, {1, 1, 1}, 10, t, n));  // through the corner
  EXPECT_NEAR(t, std::sqrt(2.0), 1e-12);
}

TEST(RayPrimitives, SphereEntryPointAndNormal) {
  double t = 0;
  Vec3 n;
  ASSERT_TRUE(ray_sphere({0, 0, 5}, {0, 0, -1}, 2, 10, t, n));
  EXPECT_NEAR(t, 3, kTol);
  EXPECT_NEAR(n.z, 1, kTol);
  ASSERT_TRUE(ray_sphere({-5, 1, 0}, {1, 0, 0}, 2, 10, t, n));
  EXPECT_NEAR(t, 5 - std::sqrt(3.0), kTol);
  EXPECT_FALSE(ray_sphere({-5, 2.01, 0}, {1, 0, 0}, 2, 10, t, n));
  EXPECT_FALSE(ray_sphere({0, 0, 0}, {1, 0, 0}, 2, 10, t, n));  // inside
}

TEST(RayPrimitives, CylinderSideAndCapsAlongLocalZ) {
  double t = 0;
  Vec3 n;
  // Side: radius 0.5, length 2 (z in -1..1).
  ASSERT_TRUE(ray_cylinder({-3, 0, 0.9}, {1, 0, 0}, 0.5, 1, 10, t, n));
  EXPECT_NEAR(t, 2.5, kTol);
  EXPECT_NEAR(n.x, -1, kTol);
  EXPECT_FALSE(ray_cylinder({-3, 0, 1.1}, {1, 0, 0}, 0.5, 1, 10, t, n));  // above the top cap
  // Caps.
  ASSERT_TRUE(ray_cylinder({0.2, 0.1, 4}, {0, 0, -1}, 0.5, 1, 10, t, n));
  EXPECT_NEAR(t, 3, kTol);
  EXPECT_EQ(n, (Vec3{0, 0, 1}));
  ASSERT_TRUE(ray_cylinder({0.2, 0.1, -4}, {0, 0, 1}, 0.5, 1, 10, t, n));
  EXPECT_EQ(n, (Vec3{0, 0, -1}));
  EXPECT_FALSE(ray_cylinder({0.6, 0, 4}, {0, 0, -1}, 0.5, 1, 10, t, n));  // beside the cap
  // Oblique through the rim of the cap.
  const Vec3 d = Vec3{1, 0, -1} / std::sqrt(2.0);
  ASSERT_TRUE(ray_cylinder({-1.0, 0, 1.5}, d, 0.5, 1, 10, t, n));
  const Vec3 p = Vec3{-1.0, 0, 1.5} + d * t;
  EXPECT_NEAR(p.z, 1, 1e-12);  // enters through the top cap at x = -0.5
  EXPECT_FALSE(ray_cylinder({0, 0, 0}, {1, 0, 0}, 0.5, 1, 10, t, n));  // inside
}

/// A scene with one robot body (two geoms) and one obstacle.
struct Fixture {
  scene::Scene sc;
  std::vector<Pose> poses;
  Fixture() {
    scene::Geom wall = box_geom({0.2, 4, 1}, {{3, 0, 0.5}, {}});
    wall.material.metallic = true;
    sc.obstacles.push_back(wall);
    scene::Body b;
    b.id = "base";
    b.geoms.push_back(box_geom({0.4, 0.4, 0.2}, {}));
    b.geoms.push_back(sphere_geom(0.05, {{0.3, 0, 0}, {}}));  // a shell in front
    b.geoms.back().material.rfid_tag = true;
    sc.bodies.push_back(b);
    scene::Body c;
    c.id = "other";
    c.geoms.push_back(cylinder_geom(0.1, 0.5, {}));
    sc.bodies.push_back(c);
    poses.resize(3);
    poses[1] = {{0, 0, 0.3}, {}};
    poses[2] = {{1.5, 0, 0.3}, {}};
  }
};

TEST(RayCaster, GroundWallsObstaclesAndBodies) {
  Fixture f;
  const ShapeTable table(f.sc);
  RayCaster rc(table, f.poses.data());
  // Straight down from above the floor, clear of everything.
  RayHit h = rc.cast({-5, 5, 2}, {0, 0, -1}, 10, -1);
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.distance_m, 2, kTol);
  EXPECT_EQ(h.body.index, 0);
  EXPECT_EQ(h.normal, (Vec3{0, 0, 1}));
  // Toward -X: the wall plane at x = -12.
  h = rc.cast({-5, 5, 0.5}, {-1, 0, 0}, 100, -1);
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.distance_m, 7, kTol);
  EXPECT_EQ(h.normal, (Vec3{1, 0, 0}));
  h = rc.cast({-5, 5, 0.5}, {0, 1, 0}, 100, -1);
  EXPECT_NEAR(h.distance_m, 7, kTol);
  h = rc.cast({-5, 5, 0.5}, {-1, 0, 0}, 6.9, -1);  // too short
  EXPECT_FALSE(h.hit);
  // Up into the sky: nothing.
  EXPECT_FALSE(rc.cast({0, 5, 0.5}, {0, 0, 1}, 1000, -1).hit);
  // From the robot's shell toward +X: the other body's cylinder at x = 1.5 - 0.1.
  h = rc.cast({0.36, 0, 0.3}, {1, 0, 0}, 10, -1);
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.distance_m, 1.4 - 0.36, 1e-12);
  EXPECT_EQ(h.body.index, 2);
  // Above the cylinder (top at 0.55): the metallic obstacle at x = 2.9.
  h = rc.cast({0.0, 0, 0.7}, {1, 0, 0}, 10, -1);
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.distance_m, 2.9, 1e-12);
  EXPECT_EQ(h.body.index, 0);
  EXPECT_EQ(h.material, material_metallic);
}

TEST(RayCaster, WallsCanBeTurnedOffOrMoved) {
  Fixture f;
  f.sc.settings.world_walls = false;
  const ShapeTable table_off(f.sc);
  RayCaster off(table_off, f.poses.data());
  EXPECT_FALSE(off.cast({-5, 5, 0.5}, {-1, 0, 0}, 100, -1).hit);
  f.sc.settings.world_walls = true;
  f.sc.settings.world_wall_distance_m = 20;
  const ShapeTable table_far(f.sc);
  RayCaster far(table_far, f.poses.data());
  EXPECT_NEAR(far.cast({-5, 5, 0.5}, {-1, 0, 0}, 100, -1).distance_m, 15, kTol);
}

TEST(RayCaster, IgnoresTheSensorsOwnBodyButSeesTheOthers) {
  Fixture f;
  const ShapeTable table(f.sc);
  RayCaster rc(table, f.poses.data());
  // From outside the robot (at x = -1) toward +X: the robot's own box first...
  RayHit h = rc.cast({-1, 0, 0.3}, {1, 0, 0}, 10, -1);
  ASSERT_TRUE(h.hit);
  EXPECT_EQ(h.body.index, 1);
  EXPECT_NEAR(h.distance_m, 0.8, kTol);
  // ...unless it is the sensor's body: then the other robot body.
  h = rc.cast({-1, 0, 0.3}, {1, 0, 0}, 10, 1);
  ASSERT_TRUE(h.hit);
  EXPECT_EQ(h.body.index, 2);
  // Ignoring the world (0) ignores nothing.
  EXPECT_EQ(rc.cast({-1, 0, 0.3}, {1, 0, 0}, 10, 0).body.index, 1);
  // Material of the shell sphere (RFID tag).
  h = rc.cast({0.3, 0, 1}, {0, 0, -1}, 10, -1);
  ASSERT_TRUE(h.hit);
  EXPECT_EQ(h.material, material_rfid_tag);
  EXPECT_NEAR(h.distance_m, 0.7 - 0.05, kTol);
}

TEST(RayCaster, FollowsMovedAndRotatedBodiesAfterInvalidate) {
  Fixture f;
  const ShapeTable table(f.sc);
  RayCaster rc(table, f.poses.data());
  EXPECT_EQ(rc.cast({1.5, -1, 0.3}, {0, 1, 0}, 10, -1).body.index, 2);
  // Lay the cylinder along X at y = 2: a ray along y meets its side.
  f.poses[2] = {{1.5, 2, 0.3}, rot_axis({0, 1, 0}, kPi / 2)};
  rc.invalidate();
  const RayHit h = rc.cast({1.7, -1, 0.3}, {0, 1, 0}, 10, -1);
  ASSERT_TRUE(h.hit);
  EXPECT_EQ(h.body.index, 2);
  EXPECT_NEAR(h.distance_m, 2.9, 1e-12);
  EXPECT_NEAR(h.normal.y, -1, 1e-12);
}

TEST(RayCaster, BroadPhaseAgreesWithBruteForceOnAClutteredScene) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  scene::Scene sc;
  auto random_rotation = [&] { return rot_axis({u(rng), u(rng), u(rng) + 1e-3}, 3 * u(rng)); };
  auto random_geom = [&](Pose pose) {
    const int k = static_cast<int>((u(rng) + 1) * 1.5);
    if (k == 0) return box_geom({0.1 + 0.5 * (u(rng) + 1), 0.1 + 0.5 * (u(rng) + 1), 0.3}, pose);
    if (k == 1) return sphere_geom(0.05 + 0.3 * (u(rng) + 1), pose);
    return cylinder_geom(0.05 + 0.2 * (u(rng) + 1), 0.2 + u(rng) + 1, pose);
  };
  for (int i = 0; i < 400; ++i)
    sc.obstacles.push_back(
        random_geom({{8 * u(rng), 8 * u(rng), 0.5 + 0.5 * u(rng)}, random_rotation()}));
  std::vector<Pose> poses(1);
  for (int b = 0; b < 60; ++b) {
    scene::Body body;
    body.geoms.push_back(random_geom({}));
    body.geoms.push_back(random_geom({{0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng)}, {}}));
    sc.bodies.push_back(body);
    poses.push_back({{9 * u(rng), 9 * u(rng), 1 + u(rng)}, random_rotation()});
  }
  const ShapeTable table(sc);
  RayCaster rc(table, poses.data());
  EXPECT_EQ(rc.static_geom_count(), 400u);
  EXPECT_EQ(rc.moving_geom_count(), 120u);
  int hits = 0, body_hits = 0;
  for (int round = 0; round < 3; ++round) {
    for (int i = 0; i < 4000; ++i) {
      const Vec3 o{10 * u(rng), 10 * u(rng), 1 + u(rng)};
      Vec3 d{u(rng), u(rng), 0.5 * u(rng)};
      if (i % 7 == 0) d = {0, 0, -1};  // straight down
      if (i % 11 == 0) d = {1, 0, 0};  // axis-aligned
      const double len = 0.5 + 10 * (u(rng) + 1);
      const int ignore = i % 5 == 0 ? 1 + static_cast<int>((u(rng) + 1) * 29) : -1;
      const RayHit a = rc.cast(o, d, len, ignore);
      const RayHit b = rc.cast_brute_force(o, d, len, ignore);
      ASSERT_EQ(a.hit, b.hit) << i;
      if (!a.hit) continue;
      ++hits;
      body_hits += a.body.index > 0;
      ASSERT_NEAR(a.distance_m, b.distance_m, 1e-12) << i;
      ASSERT_EQ(a.body.index, b.body.index) << i;
    }
    // Move every body and check again.
    for (std::size_t b = 1; b < poses.size(); ++b)
      poses[b].position += Vec3{0.3 * u(rng), 0.3 * u(rng), 0.1 * u(rng)};
    rc.invalidate();
  }
  EXPECT_GT(hits, 5000);
  EXPECT_GT(body_hits, 300);
}

TEST(RayCaster, FanCullingAgreesWithBruteForceForRaysSharingAnOrigin) {
  // Few obstacles (fan culling on): fans of rays from one origin, as a ranger casts them,
  // from origins in the open and inside boxes, with vertical rays mixed in.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  scene::Scene sc;
  for (int i = 0; i < 12; ++i)
    sc.obstacles.push_back(
        box_geom({0.2 + 0.5 * (u(rng) + 1), 0.2 + 0.5 * (u(rng) + 1), 0.5},
                 {{4 * u(rng), 4 * u(rng), 0.25}, rot_axis({0, 0, 1}, 3 * u(rng))}));
  std::vector<Pose> poses(1);
  for (int b = 0; b < 30; ++b) {
    scene::Body body;
    body.geoms.push_back(b % 2 ? sphere_geom(0.1 + 0.2 * (u(rng) + 1), {})
                               : cylinder_geom(0.1 + 0.1 * (u(rng) + 1), 0.4, {}));
    sc.bodies.push_back(body);
    poses.push_back({{4 * u(rng), 4 * u(rng), 0.3 + 0.2 * u(rng)}, rot_axis({1, 0, 0}, u(rng))});
  }
  const ShapeTable table(sc);
  RayCaster rc(table, poses.data());
  int hits = 0;
  for (int fan = 0; fan < 300; ++fan) {
    if (fan % 10 == 0) {  // a new tick: bodies move
      for (std::size_t b = 1; b < poses.size(); ++b)
        poses[b].position += Vec3{0.2 * u(rng), 0.2 * u(rng), 0};
      rc.invalidate();
    }
    // Some fans start inside a body or right at a box's corner region.
    Vec3 o{4 * u(rng), 4 * u(rng), 0.3 + 0.2 * u(rng)};
    if (fan % 7 == 0) o = poses[1 + static_cast<std::size_t>(fan) % 30].position;
    const int ignore = fan % 3 == 0 ? 1 + fan % 30 : -1;
    for (int i = 0; i < 120; ++i) {
      const double phi = 2 * kPi * i / 120 + 0.01 * u(rng);
      Vec3 d{std::cos(phi), std::sin(phi), 0.3 * u(rng)};
      if (i % 17 == 0) d = {0, 0, -1};
      const RayHit a = rc.cast(o, d, 6, ignore);
      const RayHit b = rc.cast_brute_force(o, d, 6, ignore);
      ASSERT_EQ(a.hit, b.hit) << fan << " " << i;
      if (!a.hit) continue;
      ++hits;
      ASSERT_NEAR(a.distance_m, b.distance_m, 1e-12) << fan << " " << i;
      ASSERT_EQ(a.body.index, b.body.index) << fan << " " << i;
    }
  }
  EXPECT_GT(hits, 20000);
  EXPECT_EQ(rc.fan_builds(), 300u);  // one per fan: the culling was used
}

TEST(RayCaster, FanKeptAcrossTicksAgreesWithBruteForce) {
  // A ranger's fan tick after tick from an origin that creeps (as on a slow robot), bodies
  // moving by a few millimetres per tick and now and then jumping: the fan is kept while they
  // stay within its margins, rebuilt otherwise, and always agrees with the brute force.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  scene::Scene sc;
  for (int i = 0; i < 6; ++i)
    sc.obstacles.push_back(
        box_geom({0.3 + 0.3 * (u(rng) + 1), 0.3 + 0.3 * (u(rng) + 1), 0.5},
                 {{3 * u(rng), 3 * u(rng), 0.25}, rot_axis({0, 0, 1}, 3 * u(rng))}));
  std::vector<Pose> poses(1);
  for (int b = 0; b < 12; ++b) {
    scene::Body body;
    body.geoms.push_back(b % 2 ? box_geom({0.2, 0.3, 0.2}, {})
                               : cylinder_geom(0.05 + 0.1 * (u(rng) + 1), 0.3, {}));
    sc.bodies.push_back(body);
    poses.push_back({{3 * u(rng), 3 * u(rng), 0.2}, rot_axis({0, 0, 1}, 3 * u(rng))});
  }
  const ShapeTable table(sc);
  RayCaster rc(table, poses.data());
  Vec3 o{0.1, -0.2, 0.2};
  int hits = 0;
  for (int tick = 0; tick < 200; ++tick) {
    for (std::size_t b = 1; b < poses.size(); ++b) {
      const double step = tick % 25 == 0 ? 0.1 : 0.004;
      poses[b].position += Vec3{step * u(rng), step * u(rng), 0};
      poses[b].rotation = rot_axis({0, 0, 1}, 0.01 * u(rng)) * poses[b].rotation;
    }
    o += Vec3{0.003 * u(rng), 0.003 * u(rng), 0};
    rc.invalidate();
    const int ignore = tick % 3 == 0 ? 1 + tick % 12 : -1;
    for (int i = 0; i < 77; ++i) {
      const double phi = 2 * kPi * ((tick % 10) * 77 + i) / 770;
      const Vec3 d{std::cos(phi), std::sin(phi), 0.05 * u(rng)};
      const RayHit a = rc.cast(o, d, 5, ignore);
      const RayHit b = rc.cast_brute_force(o, d, 5, ignore);
      ASSERT_EQ(a.hit, b.hit) << tick << " " << i;
      if (!a.hit) continue;
      ++hits;
      ASSERT_NEAR(a.distance_m, b.distance_m, 1e-12) << tick << " " << i;
      ASSERT_EQ(a.body.index, b.body.index) << tick << " " << i;
    }
  }
  EXPECT_GT(hits, 5000);
  EXPECT_GT(rc.fan_builds(), 8u);    // rebuilt after the jumps and the creep...
  EXPECT_LT(rc.fan_builds(), 150u);  // ...but mostly kept
}

}  // namespace
}  // namespace s2sim::collision
