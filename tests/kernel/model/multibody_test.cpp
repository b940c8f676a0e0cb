// Physics of the multibody model against analytic answers (docs/models/multibody.md).
#include "model/multibody.hpp"
#include "common/state_layout.hpp"
#include "model_runner.hpp"
#include "scene_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace s2sim::model {
namespace {

using scene::JointType;
constexpr double kG = kGravity_m_s2;

using test::Runner;

TEST(Multibody, FreeFallMatchesHalfGTSquared) {
  scene::Scene s;
  s.bodies.push_back(test::sphere("ball", 0.3, 0.1, {0.5, -0.2, 10.0}));
  s.things.push_back(0);
  Runner r(s);
  for (int n = 1; n <= 2000; ++n) {
    r.step();
    if (n % 250 != 0) continue;
    const double t = n * 1e-3;
    const double drop = 0.5 * kG * t * t;
    EXPECT_NEAR(10.0 - r.poses[1].position.z, drop, 1e-6 * drop) << "t = " << t;
    EXPECT_NEAR(r.poses[1].position.x, 0.5, 1e-12);
  }
}

double pendulum_period(double amplitude_rad, double dt) {
  // A 1 kg ball of radius 2 cm on a 1 m massless arm, hinged to the world about Y.
  scene::Scene s;
  const double L = 1.0, radius = 0.02, m = 1.0;
  const Vec3 pivot{0, 0, 2};
  s.bodies.push_back(test::sphere(
      "bob", m, radius, {L * std::sin(amplitude_rad), 0, 2 - L * std::cos(amplitude_rad)}));
  s.joints.push_back(test::joint("J", JointType::hinge, 0, -1, pivot, {0, 1, 0}));
  test::add_robot(s, "pendulum");
  Runner r(s, dt);
  // Turning points: the axis speed changes sign. Interpolate each crossing linearly.
  std::vector<double> turns;
  double prev = r.vel[0];
  for (int n = 1; turns.size() < 11 && n < 200000; ++n) {
    r.step();
    const double v = r.vel[0];
    if (prev != 0 && (prev < 0) != (v < 0)) turns.push_back(dt * (n - 1 + prev / (prev - v)));
    prev = v;
  }
  EXPECT_EQ(turns.size(), 11u);
  return (turns.back() - turns.front()) / 5.0;  // ten half periods
}

TEST(Multibody, HingePendulumLargeAnglePeriodWithinTwoTenthsOfAPercent) {
  const double L = 1.0, radius = 0.02, m = 1.0;
  const double inertia_pivot = 0.4 * m * radius * radius + m * L * L;
  for (double amplitude_deg : {10.0, 90.0, 150.0}) {
    const double a = amplitude_deg * kPi / 180;
    const double exact =
        4.0 * std::sqrt(inertia_pivot / (m * kG * L)) * test::elliptic_k(std::sin(a / 2));
    const double period = pendulum_period(a, 1e-3);
    EXPECT_NEAR(period, exact, 0.002 * exact) << "amplitude " << amplitude_deg << " deg";
    char error[32];
    std::snprintf(error, sizeof error, "%.3e", (period - exact) / exact);
    RecordProperty("period_error_" + std::to_string(int(amplitude_deg)) + "deg", error);
  }
}

TEST(Multibody, SliderUnderGravityFollowsGSinAlpha) {
  // A block on a frictionless rail inclined 30 degrees below the horizontal, along +X.
  const double alpha = 30 * kPi / 180;
  const Vec3 axis{std::cos(alpha), 0, -std::sin(alpha)};
  scene::Scene s;
  s.bodies.push_back(test::box("block", 2.0, {0.1, 0.1, 0.1}, {0, 0, 5}));
  s.joints.push_back(test::joint("rail", JointType::slider, 0, -1, {0, 0, 5}, axis));
  test::add_robot(s, "slider");
  Runner r(s);
  for (int n = 1; n <= 1000; ++n)
    r.step();
  const double t = 1.0, expected = 0.5 * kG * std::sin(alpha) * t * t;
  EXPECT_NEAR(r.pos[0], expected, 1e-6 * expected);
  // The block stays on the rail.
  EXPECT_NEAR(r.poses[1].position.x, expected * axis.x, 1e-9);
  EXPECT_NEAR(r.poses[1].position.z, 5 + expected * axis.z, 1e-9);
  EXPECT_NEAR(r.poses[1].position.y, 0, 1e-12);
}

TEST(Multibody, PassiveDoublePendulumEnergyDriftBelowHalfAPercentOver10s) {
  // Two 0.5 m rods, the first hinged to the world, released horizontal and at 45 degrees.
  scene::Scene s;
  const Vec3 pivot{0, 0, 2};
  const double Lr = 0.5;
  s.bodies.push_back(test::box("upper", 1.0, {Lr, 0.04, 0.04}, {Lr / 2, 0, 2}));
  const Mat3 r45 = test::rotation_about({0, 1, 0}, 45 * kPi / 180);
  const Vec3 elbow{Lr, 0, 2};
  s.bodies.push_back(
      test::box("lower", 0.8, {Lr, 0.04, 0.04}, elbow + r45 * Vec3{Lr / 2, 0, 0}, r45));
  s.joints.push_back(test::joint("shoulder", JointType::hinge, 0, -1, pivot, {0, 1, 0}));
  s.joints.push_back(test::joint("elbow", JointType::hinge, 1, 0, elbow, {0, 1, 0}));
  test::add_robot(s, "double");
  Runner r(s);
  const double e0 = r.mb.kinetic_energy_J() + r.mb.potential_energy_J();
  // The energy scale: what the pendulum can turn into motion (both rods hanging down).
  const double e_rest = (1.0 * kG * (2 - Lr / 2)) + 0.8 * kG * (2 - Lr - Lr / 2);
  const double scale = e0 - e_rest;
  ASSERT_GT(scale, 1.0);
  // Leapfrog speeds live mid-step, so the instantaneous energy oscillates by O(h); the drift is
  // the change of its one-second mean between the first and the last second.
  double first = 0, last = 0, worst = 0;
  const int steps = 10000;
  for (int n = 1; n <= steps; ++n) {
    r.step();
    const double e = r.mb.kinetic_energy_J() + r.mb.potential_energy_J();
    worst = std::max(worst, std::abs(e - e0) / scale);
    if (n <= 1000) first += e / 1000;
    if (n > steps - 1000) last += e / 1000;
  }
  const double drift = std::abs(last - first) / scale;
  EXPECT_LT(drift, 0.005);
  RecordProperty("energy_drift", std::to_string(drift));
  // Not a bound: the half-step kinetic energy makes this oscillate by a few percent at 1 ms.
  RecordProperty("energy_worst_instantaneous", std::to_string(worst));
}

TEST(Multibody, AxisValueIsBody1RelativeToBody2AndTorquePushesItUp) {
  // Same hinge written both ways round: positive axis torque must raise the axis value, and
  // the value is body1's rotation relative to body2 about the axis (ODE convention).
  for (bool base_is_body1 : {false, true}) {
    scene::Scene s;
    s.bodies.push_back(test::box("base", 5.0, {0.2, 0.2, 0.2}, {0, 0, 1}));
    s.bodies.push_back(test::box("arm", 1.0, {0.4, 0.05, 0.05}, {0.3, 0, 1}));
    s.bodies[0].gravity = s.bodies[1].gravity = false;
    s.joints.push_back(base_is_body1
                           ? test::joint("J", JointType::hinge, 0, 1, {0.1, 0, 1}, {0, 0, 1})
                           : test::joint("J", JointType::hinge, 1, 0, {0.1, 0, 1}, {0, 0, 1}));
    test::add_robot(s, "r");
    Runner r(s);
    for (int n = 0; n < 200; ++n) {
      r.mb.applied_axis_forces()[0] = 0.05;
      r.step();
    }
    EXPECT_GT(r.pos[0], 0.01) << "base_is_body1 = " << base_is_body1;
    EXPECT_GT(r.vel[0], 0.0);
    // body1 turns positively about +Z relative to body2.
    const int b1 = base_is_body1 ? 1 : 2, b2 = base_is_body1 ? 2 : 1;
    const double relative_yaw = yaw_of(r.poses[b2].rotation.transposed() * r.poses[b1].rotation);
    EXPECT_NEAR(relative_yaw, r.pos[0], 1e-9);
  }
}

TEST(Multibody, HingeStopHoldsAPendulum) {
  scene::Scene s;
  s.bodies.push_back(test::sphere("bob", 1.0, 0.02, {1, 0, 2}));
  auto j = test::joint("J", JointType::hinge, 0, -1, {0, 0, 2}, {0, 1, 0});
  // Falling from the horizontal turns the bob positively about +Y; stop it at 45 degrees.
  j.limits1 = {-kPi / 2, kPi / 4, true};
  s.joints.push_back(j);
  test::add_robot(s, "p");
  Runner r(s);
  double max_angle = 0;
  for (int n = 0; n < 5000; ++n) {
    r.step();
    max_angle = std::max(max_angle, r.pos[0]);
  }
  EXPECT_LT(max_angle, kPi / 4 + 3 * kPi / 180);  // overshoot of the compliant stop
  EXPECT_NEAR(r.pos[0], kPi / 4, 2 * kPi / 180);  // resting on it
  EXPECT_LT(std::abs(r.vel[0]), 0.05);
}

/// A horizontal arm on a hinge about world Y: gravity loads it with m·g·L.
scene::Scene horizontal_arm(double mass_kg, double length_m) {
  scene::Scene s;
  s.bodies.push_back(test::sphere("bob", mass_kg, 0.01, {length_m, 0, 1}));
  s.joints.push_back(test::joint("J", JointType::hinge, 0, -1, {0, 0, 1}, {0, 1, 0}));
  test::add_robot(s, "arm");
  return s;
}

TEST(Multibody, CoulombBrakeHoldsALoadBelowItsBoundWithoutCreep) {
  const double m = 1.0, L = 0.5, load = m * kG * L;
  Runner r(horizontal_arm(m, L));
  for (int n = 0; n < 10000; ++n) {  // 10 s
    r.mb.applied_axis_friction()[0] = 1.01 * load;
    r.step();
  }
  EXPECT_EQ(r.pos[0], 0.0);
  EXPECT_EQ(r.vel[0], 0.0);
}

TEST(Multibody, CoulombBrakeAboveItsBoundSlidesAgainstTheFullBound) {
  // Just after release the arm is near horizontal: theta'' = (m g L - F) / I.
  const double m = 1.0, L = 0.5, load = m * kG * L, bound = 0.5 * load;
  const double inertia = m * L * L + 0.4 * m * 0.01 * 0.01;
  Runner r(horizontal_arm(m, L));
  for (int n = 0; n < 20; ++n) {
    r.mb.applied_axis_friction()[0] = bound;
    r.step();
  }
  const double t = 0.02, expected = 0.5 * (load - bound) / inertia * t * t;
  EXPECT_NEAR(r.pos[0], expected, 0.01 * expected);
}

TEST(Multibody, DeclaredAxisInertiaAddsToTheAxis) {
  // A torque on a gravity-free hinge: theta'' = T / (I_body + J), J a reflected rotor inertia
  // N^2 J_rotor declared for the axis (ConfigureContext::add_axis_inertia).
  scene::Scene s = horizontal_arm(1.0, 0.5);
  s.bodies[0].gravity = false;
  const double inertia = 0.25 + 0.4 * 0.01 * 0.01 + 48.0 * 48.0 * 1e-5;
  Runner r(s, std::vector<double>{48.0 * 48.0 * 1e-5});
  for (int n = 0; n < 100; ++n) {
    r.mb.applied_axis_forces()[0] = 0.1;
    r.step();
  }
  const double t = 0.1, expected = 0.5 * 0.1 / inertia * t * t;
  EXPECT_NEAR(r.pos[0], expected, 1e-6 * expected);
}

TEST(Multibody, FixedUniversalAndBallJoints) {
  scene::Scene s;
  s.bodies.push_back(test::box("base", 2.0, {0.2, 0.2, 0.2}, {0, 0, 2}));
  s.bodies.push_back(test::box("glued", 0.5, {0.1, 0.1, 0.1}, {0.2, 0, 2}));
  s.bodies.push_back(test::box("cardan", 0.5, {0.1, 0.1, 0.4}, {0, 0, 1.7}));
  s.bodies.push_back(test::sphere("ball", 0.5, 0.05, {0.3, 0.3, 1.5}));
  s.joints.push_back(test::joint("post", JointType::fixed, 0, -1, {0, 0, 2}));
  s.joints.push_back(test::joint("glue", JointType::fixed, 1, 0, {0.2, 0, 2}));
  auto u = test::joint("u", JointType::universal, 2, 0, {0, 0, 1.9}, {1, 0, 0});
  u.axis2 = {0, 1, 0};
  s.joints.push_back(u);
  s.joints.push_back(test::joint("socket", JointType::ball, 3, 1, {0.2, 0, 2}));
  test::add_robot(s, "r");
  Runner r(s);
  ASSERT_EQ(r.mb.axes().size(), 2u + 0u);  // fixed and ball joints have no axis
  EXPECT_EQ(r.mb.axes()[0].name, "u");
  EXPECT_EQ(r.mb.axes()[1].name, "u:2");
  const double e0 = r.mb.kinetic_energy_J() + r.mb.potential_energy_J();
  for (int n = 0; n < 2000; ++n) {
    r.mb.applied_axis_forces()[0] = n < 100 ? 0.2 : 0.0;  // kick the cardan about X
    r.step();
  }
  // Welded bodies keep their poses; the ball keeps its distance to the socket.
  EXPECT_NEAR(r.poses[1].position.z, 2.0, 1e-9);
  EXPECT_NEAR(r.poses[2].position.x, 0.2, 1e-9);
  const Vec3 socket{0.2, 0, 2};
  EXPECT_NEAR(norm(r.poses[4].position - socket), norm(Vec3{0.3, 0.3, 1.5} - socket), 1e-6);
  EXPECT_GT(std::abs(r.pos[0]), 0.01);
  EXPECT_TRUE(std::isfinite(r.mb.kinetic_energy_J() + r.mb.potential_energy_J() - e0));
}

TEST(Multibody, KinematicLoopIsClosedByConstraints) {
  Runner r(test::four_bar());
  int loops = 0;
  for (const auto& a : r.mb.axes())
    loops += a.loop;
  EXPECT_EQ(loops, 1);
  double peak = 0, worst_parallel = 0, worst_level = 0, worst_loop_axis = 0;
  for (int n = 0; n < 3000; ++n) {
    r.mb.applied_axis_forces()[0] = n < 200 ? 2.0 : 0.0;
    r.step();
    peak = std::max(peak, std::abs(r.pos[0]));
    // The cranks stay parallel (equal angles) and the coupler level; the loop joint D reads
    // the coupler's rotation relative to crank2, i.e. minus crank2's angle.
    worst_parallel = std::max(worst_parallel, std::abs(r.pos[0] - r.pos[1]));
    worst_level = std::max(worst_level, std::abs(r.poses[3].rotation.m[2][0]));
    worst_loop_axis = std::max(worst_loop_axis, std::abs(r.pos[3] + r.pos[1]));
  }
  EXPECT_GT(peak, 0.1);
  EXPECT_LT(worst_parallel, 1e-6);
  EXPECT_LT(worst_level, 1e-6);
  EXPECT_LT(worst_loop_axis, 1e-6);
}

TEST(Multibody, SaveAndRestoreContinueBitForBit) {
  scene::Scene s;
  s.bodies.push_back(test::box("upper", 1.0, {0.5, 0.04, 0.04}, {0.25, 0, 2}));
  s.bodies.push_back(test::box("lower", 1.0, {0.5, 0.04, 0.04}, {0.75, 0, 2}));
  s.joints.push_back(test::joint("a", JointType::hinge, 0, -1, {0, 0, 2}, {0, 1, 0}));
  s.joints.push_back(test::joint("b", JointType::hinge, 1, 0, {0.5, 0, 2}, {0, 1, 0}));
  test::add_robot(s, "r");
  Runner r(s);
  for (int n = 0; n < 300; ++n)
    r.step();
  common::StateLayout layout;
  r.mb.declare_state(layout);
  std::vector<double> saved;
  layout.save(saved);
  for (int n = 0; n < 500; ++n)
    r.step();
  const auto first = r.pos;
  layout.restore(layout.id(), layout.entries(), saved);
  r.mb.restored();
  for (int n = 0; n < 500; ++n)
    r.step();
  EXPECT_EQ(r.pos, first);
  r.mb.reset();
  r.read();
  EXPECT_EQ(r.mb.time_s(), 0.0);
  EXPECT_EQ(r.pos[0], 0.0);
}

}  // namespace
}  // namespace s2sim::model

namespace s2sim::model {
namespace {

/// A tumbling box under gravity, a constant push and a torque, integrated by LooseBodies and
/// by a Simbody Free mobilizer: the same law, so the same motion.
TEST(LooseBodies, MatchSimbodysFreeMobilizer) {
  for (bool offset_com : {false, true}) {
    scene::Scene s;
    s.bodies.push_back(
        test::box("box", 2.0, {0.3, 0.2, 0.1}, {0, 0, 1}, test::rotation_about({1, 2, 3}, 0.4)));
    if (offset_com) s.bodies[0].com_m = {0.05, -0.02, 0.01};
    Runner loose(s);
    Multibody reference(s, 1e-3, 1, true);
    std::vector<Pose> poses(2);
    std::vector<Twist> twists(2);
    std::vector<double> none;
    for (int n = 0; n < 1000; ++n) {
      for (Multibody* mb : {&loose.mb, &reference}) {
        mb->applied_wrenches()[1] = Wrench{{0.02, -0.01, 0.03}, {1.0, 0.5, 0}};
        test::physics_tick(*mb, nullptr);
      }
    }
    loose.read();
    reference.read(poses.data(), twists.data(), none.data(), none.data());
    const double tolerance = offset_com ? 1e-4 : 1e-9;
    EXPECT_LT(norm(loose.poses[1].position - poses[1].position), tolerance) << offset_com;
    EXPECT_LT(norm(loose.twists[1].angular_rad_s - twists[1].angular_rad_s), 100 * tolerance);
    EXPECT_LT(norm(loose.twists[1].linear_m_s - twists[1].linear_m_s), 100 * tolerance);
    for (int c = 0; c < 3; ++c)
      EXPECT_LT(norm(loose.poses[1].rotation.column(c) - poses[1].rotation.column(c)), tolerance);
    // Off the COM, Simbody drifts the body origin and LooseBodies the COM: equal to O(h).
    const double ke = reference.kinetic_energy_J(), pe = reference.potential_energy_J();
    EXPECT_NEAR(loose.mb.kinetic_energy_J(), ke, (offset_com ? 1e-5 : 1e-9) * std::abs(ke));
    EXPECT_NEAR(loose.mb.potential_energy_J(), pe, (offset_com ? 1e-5 : 1e-9) * std::abs(pe));
  }
}

}  // namespace
}  // namespace s2sim::model

namespace s2sim::model {
namespace {

// Multibody::contact_mobility (contact's effective mass at a point on a jointed body): a 1 kg
// chassis, free, and a 0.1 kg wheel hinged to it about Y, their centres of mass at one point.
// Analytic: a force at the wheel's COM moves both bodies, a/F = 1/1.1 kg along any axis; a
// torque about the hinge spins the wheel alone, α/τ = 1/I_wheel,yy; a torque about X turns
// both rigidly, α/τ = 1/(I_chassis,xx + I_wheel,xx). The wheel's own inertia, which the
// contact used before, says 1/I_wheel,xx for the last: 78 times too free here.
TEST(ContactMobility, AWheelHingedToAFreeChassisAnswersAsTheTreeItDrags) {
  scene::Scene s;
  const Vec3 centre{0, 0, 0.5};
  s.bodies.push_back(test::box("chassis", 1.0, {0.2, 0.2, 0.2}, centre));
  s.bodies.push_back(test::box("wheel", 0.1, {0.1, 0.02, 0.1}, centre));
  s.joints.push_back(test::joint("axle", JointType::hinge, 1, 0, centre, {0, 1, 0}));
  test::add_robot(s, "cart");
  Runner r(s);
  const auto mobility = r.mb.contact_mobility();
  ASSERT_EQ(mobility.size(), 3u);
  EXPECT_EQ(mobility[1].root, 1) << "the chassis is its own tree's base";
  EXPECT_EQ(mobility[2].root, 1) << "the wheel's axes are the chassis's";
  const auto& phi = mobility[2].phi;
  const double chassis_xx = 1.0 * (0.04 + 0.04) / 12, wheel_xx = 0.1 * (0.0004 + 0.01) / 12,
               wheel_yy = 0.1 * (0.01 + 0.01) / 12;
  for (int axis = 3; axis < 6; ++axis)
    EXPECT_NEAR(phi[axis][axis], 1 / 1.1, 1e-9) << "force along " << axis - 3;
  EXPECT_NEAR(phi[1][1], 1 / wheel_yy, 1e-9 / wheel_yy) << "about the hinge";
  EXPECT_NEAR(phi[0][0], 1 / (chassis_xx + wheel_xx), 1e-9 / chassis_xx) << "about X";
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      EXPECT_NEAR(phi[i][j], phi[j][i], 1e-9 * (1 + std::abs(phi[i][j]))) << "symmetric";
}

}  // namespace
}  // namespace s2sim::model

namespace s2sim::model {
namespace {

// contact_mobility and apparent_mass_kg load one body of every tree at once: each tree answers
// its own loads only, so two carts side by side (one heavier, turned, farther) give each cart's
// numbers exactly as the cart alone gives them.
TEST(ContactMobility, TreesLoadedTogetherAnswerBitForBitAsAlone) {
  auto cart = [](scene::Scene& s, const std::string& id, double mass_kg, Vec3 centre, Vec3 axle) {
    const int first = static_cast<int>(s.bodies.size());
    s.bodies.push_back(test::box(id + "_chassis", mass_kg, {0.2, 0.3, 0.1}, centre));
    s.bodies.push_back(test::box(id + "_wheel", 0.1, {0.1, 0.02, 0.1}, centre + Vec3{0.05, 0, 0}));
    s.joints.push_back(test::joint(id + "_axle", JointType::hinge, first + 1, first,
                                   centre + Vec3{0.05, 0, 0}, axle));
  };
  scene::Scene both, first_alone, second_alone;
  cart(both, "a", 1.0, {0, 0, 0.5}, {0, 1, 0});
  cart(both, "b", 3.0, {2, 1, 0.5}, {1, 1, 0});
  cart(first_alone, "a", 1.0, {0, 0, 0.5}, {0, 1, 0});
  cart(second_alone, "b", 3.0, {2, 1, 0.5}, {1, 1, 0});
  for (scene::Scene* s : {&both, &first_alone, &second_alone})
    test::add_robot(*s, "carts");
  Runner together(both), a(first_alone), b(second_alone);
  const auto mobility = together.mb.contact_mobility();
  const auto mass = together.mb.apparent_mass_kg();
  ASSERT_EQ(mobility.size(), 5u);
  const std::vector<Multibody::Mobility> alone[2] = {a.mb.contact_mobility(),
                                                     b.mb.contact_mobility()};
  const std::vector<double> alone_mass[2] = {a.mb.apparent_mass_kg(), b.mb.apparent_mass_kg()};
  for (int cart_index = 0; cart_index < 2; ++cart_index)
    for (int body = 1; body <= 2; ++body) {
      const auto& together_phi = mobility[static_cast<std::size_t>(2 * cart_index + body)];
      const auto& alone_phi = alone[cart_index][static_cast<std::size_t>(body)];
      EXPECT_EQ(together_phi.root, alone_phi.root + 2 * cart_index);
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
          EXPECT_EQ(together_phi.phi[i][j], alone_phi.phi[i][j])
              << "cart " << cart_index << " body " << body << " (" << i << ", " << j << ")";
      EXPECT_EQ(mass[static_cast<std::size_t>(2 * cart_index + body)],
                alone_mass[cart_index][static_cast<std::size_t>(body)]);
    }
  EXPECT_NE(mobility[1].phi[3][3], mobility[3].phi[3][3]) << "the carts differ";
}

}  // namespace
}  // namespace s2sim::model
