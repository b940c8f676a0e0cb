// The contact layer against analytic answers (docs/models/contact.md), at a 1 ms step.
#include "contact/contact_world.hpp"
#include "contact_runner.hpp"
#include "model/multibody.hpp"
#include "scene_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace s2sim::contact {
namespace {

using scene::JointType;
constexpr double kG = kGravity_m_s2;

/// A multibody model with the contact layer as its substep force.
using Runner = test::ContactRunner;

void set_mu(scene::Body& b, double mu, double bounce = 0) {
  for (auto& g : b.geoms) {
    g.surface.explicit_surface = true;
    g.surface.mu = mu;
    g.surface.bounce = bounce;
  }
}

/// Height of the slopes' pivot: well clear of the ground.
const Vec3 kPivot{0, 0, 3};

/// A static slab whose top face passes through kPivot, tilted by `angle` about Y so that
/// down-slope is +X.
scene::Geom slope(double angle) {
  scene::Geom g;
  g.id = "slope";
  g.shape.type = scene::ShapeType::box;
  g.shape.size_m = {4, 2, 0.2};
  const Mat3 r = test::rotation_about({0, 1, 0}, angle);
  g.pose = {kPivot + r * Vec3{0, 0, -0.1}, r};
  return g;
}

/// Distance travelled down the slope (+X of the slope frame).
double along(const Mat3& slope_rotation, const Vec3& p) {
  return dot(slope_rotation.column(0), p);
}

/// The acceleration down the slope of body 1 (scene body 0), from its positions 0.2, 0.7 and
/// 1.2 s after release (second difference).
double slope_acceleration(const scene::Scene& s, const Mat3& slope_rotation) {
  Runner run(s);
  double x[3];
  run.step(200);
  for (int k = 0; k < 3; ++k) {
    if (k > 0) run.step(500);
    x[k] = along(slope_rotation, run.poses[1].position);
  }
  return (x[2] - 2 * x[1] + x[0]) / (0.5 * 0.5);
}

TEST(Contact, BlockOnAnInclineHoldsBelowTheFrictionAngle) {
  const double angle = 20 * kPi / 180, mu = 0.5;  // tan 20° = 0.36 < 0.5
  const Mat3 r = test::rotation_about({0, 1, 0}, angle);
  scene::Scene s;
  s.settings.world_walls = false;
  s.obstacles.push_back(slope(angle));
  s.bodies.push_back(test::box("block", 1.0, {0.1, 0.1, 0.1}, kPivot + r * Vec3{0, 0, 0.0501}, r));
  set_mu(s.bodies[0], mu);
  Runner run(s);
  run.step(500);  // settle
  const double start = along(r, run.poses[1].position);
  run.step(10000);
  const double drift = along(r, run.poses[1].position) - start;
  RecordProperty("drift_m", std::to_string(drift));
  EXPECT_LT(std::abs(drift), 1e-3) << "the block crept " << drift << " m in 10 s";
}

TEST(Contact, BlockOnASteepInclineSlidesAtGTimesSinMinusMuCos) {
  const double angle = 30 * kPi / 180, mu = 0.3;
  const Mat3 r = test::rotation_about({0, 1, 0}, angle);
  scene::Scene s;
  s.settings.world_walls = false;
  s.obstacles.push_back(slope(angle));
  s.bodies.push_back(
      test::box("block", 1.0, {0.1, 0.1, 0.1}, kPivot + r * Vec3{-1.5, 0, 0.0501}, r));
  set_mu(s.bodies[0], mu);
  const double measured = slope_acceleration(s, r);
  const double expected = kG * (std::sin(angle) - mu * std::cos(angle));
  RecordProperty("acceleration", std::to_string(measured));
  EXPECT_NEAR(measured, expected, 0.02 * expected);
}

TEST(Contact, SphereRollsDownAnInclineAtFiveSeventhsGSin) {
  const double angle = 15 * kPi / 180, radius = 0.05;
  const Mat3 r = test::rotation_about({0, 1, 0}, angle);
  scene::Scene s;
  s.settings.world_walls = false;
  s.obstacles.push_back(slope(angle));
  s.bodies.push_back(test::sphere("ball", 0.5, radius, kPivot + r * Vec3{-1.5, 0, radius}));
  set_mu(s.bodies[0], 0.8);
  const double measured = slope_acceleration(s, r);
  const double expected = 5.0 / 7.0 * kG * std::sin(angle);
  RecordProperty("acceleration", std::to_string(measured));
  EXPECT_NEAR(measured, expected, 0.02 * expected);
}

TEST(Contact, BallReboundsToRestitutionSquaredTimesTheDropHeight) {
  for (double e : {0.5, 0.8}) {
    const double radius = 0.05, drop = 1.0;
    scene::Scene s;
    s.bodies.push_back(test::sphere("ball", 0.2, radius, {0, 0, radius + drop}));
    set_mu(s.bodies[0], 0.5, e);
    Runner run(s);
    bool bounced = false;
    double apex = 0;
    for (int n = 0; n < 2000; ++n) {
      run.step();
      const double vz = run.twists[1].linear_m_s.z;
      if (!bounced && vz > 0) bounced = true;
      if (bounced) apex = std::max(apex, run.poses[1].position.z - radius);
      if (bounced && vz < 0) break;
    }
    const double expected = e * e * drop;
    EXPECT_NEAR(apex, expected, 0.1 * expected) << "restitution " << e;
    RecordProperty("rebound_e" + std::to_string(e), std::to_string(apex));
  }
}

TEST(Contact, BoxRestingOnTheGroundSinksAndDriftsLessThanAMillimetre) {
  scene::Scene s;
  s.bodies.push_back(test::box("box", 2.0, {0.2, 0.3, 0.1}, {0.5, 0.5, 0.05}));
  Runner run(s);
  run.step(10000);
  const Vec3 p = run.poses[1].position;
  RecordProperty("sink_mm", std::to_string((0.05 - p.z) * 1e3));
  RecordProperty("drift_mm", std::to_string(std::hypot(p.x - 0.5, p.y - 0.5) * 1e3));
  EXPECT_LT(0.05 - p.z, 1e-3);
  EXPECT_GT(0.05 - p.z, 0.0);
  EXPECT_LT(std::hypot(p.x - 0.5, p.y - 0.5), 1e-3);
}

TEST(Contact, AStackOffCentreByAFifthOfAMillimetreStandsStill) {
  // Three boxes, the middle one 0.2 mm off. Each point's damping solved for itself alone, the
  // four corners under a box overshot together: the bottom box rocked at +-0.84 rad/s every
  // other step at the friction limit and the stack walked 7.5 mm in 10 s. Shared (each point
  // its share of the body's speed per step), nothing moves.
  scene::Scene s;
  const double size = 0.1;
  for (int i = 0; i < 3; ++i)
    s.bodies.push_back(test::box("b" + std::to_string(i), 0.5, {size, size, size},
                                 {i == 1 ? 2e-4 : 0.0, 0, size / 2 + i * size}));
  Runner run(s);
  run.step(1000);
  std::vector<Vec3> settled;
  for (int i = 1; i <= 3; ++i)
    settled.push_back(run.poses[static_cast<std::size_t>(i)].position);
  double fastest_turn = 0;
  for (int n = 0; n < 4000; ++n) {
    run.step();
    for (int i = 1; i <= 3; ++i)
      fastest_turn =
          std::max(fastest_turn, norm(run.twists[static_cast<std::size_t>(i)].angular_rad_s));
  }
  for (int i = 1; i <= 3; ++i) {
    const Vec3 moved =
        run.poses[static_cast<std::size_t>(i)].position - settled[static_cast<std::size_t>(i - 1)];
    EXPECT_LT(std::hypot(moved.x, moved.y), 1e-5) << "box " << i << " walks";
  }
  EXPECT_LT(fastest_turn, 1e-3) << "the stack rocks";
}

TEST(Contact, StackOfFiveBoxesStandsTenSeconds) {
  scene::Scene s;
  const double size = 0.1;
  for (int i = 0; i < 5; ++i)
    s.bodies.push_back(
        test::box("b" + std::to_string(i), 0.5, {size, size, size}, {0, 0, size / 2 + i * size}));
  Runner run(s);
  run.step(10000);
  for (int i = 0; i < 5; ++i) {
    const Vec3 p = run.poses[i + 1].position;
    EXPECT_LT(std::hypot(p.x, p.y), 1e-3) << "box " << i;
    EXPECT_NEAR(p.z, size / 2 + i * size, 3e-3) << "box " << i;
  }
}

// Surfaces are combined once per pair of distinct surfaces at load, up to 64 of them;
// past that, per point as before. A leaning stack of boxes with three frictions and a bouncy
// sphere, alone and with 70 far-away obstacles of distinct friction (which force the per-point
// path): the same poses bit for bit.
TEST(Contact, TabulatedSurfacesGiveTheSameForcesAsCombiningPerPoint) {
  auto make = [](int extra_surfaces) {
    scene::Scene s;
    for (int i = 0; i < 4; ++i) {
      s.bodies.push_back(test::box("b" + std::to_string(i), 0.5, {0.1, 0.1, 0.1},
                                   {0.02 * i, 0.01 * i, 0.06 + 0.1 * i}));
      if (i % 3 != 0) set_mu(s.bodies.back(), 0.3 + 0.2 * i);
    }
    s.bodies.push_back(test::sphere("ball", 0.3, 0.05, {0.05, 0, 0.5}));
    set_mu(s.bodies.back(), 0.6, 0.5);
    for (int k = 0; k < extra_surfaces; ++k) {
      scene::Geom g;
      g.id = "far" + std::to_string(k);
      g.shape.type = scene::ShapeType::box;
      g.shape.size_m = {0.1, 0.1, 0.1};
      g.pose = {{5.0 + 0.2 * k, 5, 0.05}, Mat3::identity()};
      g.surface.explicit_surface = true;
      g.surface.mu = 0.01 * (k + 1);
      s.obstacles.push_back(g);
    }
    return s;
  };
  Runner tabulated(make(0)), per_point(make(70));
  tabulated.step(1500);
  per_point.step(1500);
  for (int b = 1; b <= 5; ++b) {
    const Pose &x = tabulated.poses[b], &y = per_point.poses[b];
    EXPECT_EQ(x.position.x, y.position.x) << "body " << b;
    EXPECT_EQ(x.position.y, y.position.y) << "body " << b;
    EXPECT_EQ(x.position.z, y.position.z) << "body " << b;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        EXPECT_EQ(x.rotation.m[i][j], y.rotation.m[i][j]) << "body " << b;
  }
  // Both paths were exercised: the stack and the ball rest on contacts.
  EXPECT_GT(*tabulated.contacts.contact_count(), 8);
}

TEST(Contact, DrivenWheelRollsAtRadiusTimesSpinWithinHalfAPercent) {
  // A carriage on a frictionless rail along X carries a wheel on an axle along Y; a speed
  // loop on the axle torque spins the wheel, the ground drives the carriage.
  // The axle runs 0.5 mm lower than the radius: the tread is pressed into the ground.
  const double radius = 0.04, axle = radius - 5e-4;
  scene::Scene s;
  s.bodies.push_back(test::box("carriage", 1.0, {0.1, 0.1, 0.02}, {0, 0, axle}));
  scene::Body wheel = test::sphere("wheel", 0.1, radius, {0, 0, axle});
  wheel.geoms[0].shape.type = scene::ShapeType::cylinder;
  wheel.geoms[0].shape.length_m = 0.02;
  wheel.geoms[0].pose.rotation = test::rotation_about({1, 0, 0}, kPi / 2);
  set_mu(wheel, 1.0);
  s.bodies.push_back(wheel);
  s.joints.push_back(test::joint("rail", JointType::slider, 0, -1, {0, 0, axle}, {1, 0, 0}));
  s.joints.push_back(test::joint("axle", JointType::hinge, 1, 0, {0, 0, axle}, {0, 1, 0}));
  test::add_robot(s, "cart");
  Runner run(s);
  const double target = 10;  // rad/s
  for (int n = 0; n < 3000; ++n) {
    run.mb.applied_axis_forces()[1] = 0.05 * (target - run.vel[1]);
    run.step();
  }
  const double speed = run.vel[0], spin = run.vel[1];
  ASSERT_GT(spin, 5);
  EXPECT_NEAR(speed, radius * spin, 0.005 * radius * spin);
  RecordProperty("slip", std::to_string(speed / (radius * spin) - 1));
}

}  // namespace
}  // namespace s2sim::contact

namespace s2sim::contact {
namespace {

/// A carriage on a rail along X carries a wheel whose axle is along X too, pressed into the
/// ground; a force pushes the carriage along the rail, i.e. along the axle. Returns the
/// carriage's travel after 1 s.
double push_along_the_axle(scene::FrictionKind kind, double force_N) {
  const double radius = 0.03, axle = radius - 1e-4;
  scene::Scene s;
  s.bodies.push_back(test::box("carriage", 1.0, {0.1, 0.1, 0.02}, {0, 0, axle}));
  scene::Body wheel = test::sphere("wheel", 0.1, radius, {0, 0, axle});
  wheel.geoms[0].shape.type = scene::ShapeType::cylinder;
  wheel.geoms[0].shape.length_m = 0.02;
  wheel.geoms[0].pose.rotation = test::rotation_about({0, 1, 0}, kPi / 2);  // Z along X
  wheel.geoms[0].friction = kind;
  wheel.geoms[0].surface.explicit_surface = true;
  wheel.geoms[0].surface.mu = 1.0;
  wheel.geoms[0].surface.mu2 = 0.001;
  s.bodies.push_back(wheel);
  s.joints.push_back(test::joint("rail", JointType::slider, 0, -1, {0, 0, axle}, {1, 0, 0}));
  s.joints.push_back(test::joint("axle", JointType::hinge, 1, 0, {0, 0, axle}, {1, 0, 0}));
  test::add_robot(s, "cart");
  Runner run(s);
  for (int n = 0; n < 1000; ++n) {
    run.mb.applied_axis_forces()[0] = force_N;
    run.step();
  }
  return run.pos[0];
}

TEST(Contact, OmniWheelSlidesAlongItsAxleWhereAPlainWheelGrips) {
  // The wheel presses with about 10 N (0.1 mm at the contact stiffness); 2 N along the axle.
  const double plain = push_along_the_axle(scene::FrictionKind::isotropic, 2.0);
  const double omni = push_along_the_axle(scene::FrictionKind::omni, 2.0);
  EXPECT_LT(std::abs(plain), 1e-3) << "a plain wheel holds sideways";
  // Omni: mu2 = 0.001 along the axle, so nearly free: x = F/(2m)·t² for 1.1 kg.
  EXPECT_NEAR(omni, 0.5 * 2.0 / 1.1, 0.02) << "an omni wheel rolls on its rollers";
  // Mecanum rollers at 45°: the axle direction is half gripped, half free: in between.
  const double mecanum = push_along_the_axle(scene::FrictionKind::mecanum_left, 2.0);
  EXPECT_GT(mecanum, 0.01);
  EXPECT_LT(mecanum, omni);
}

}  // namespace
}  // namespace s2sim::contact
