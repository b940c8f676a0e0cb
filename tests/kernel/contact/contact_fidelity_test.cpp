// Contact fidelity (docs/models/contact.md, "Friction" and "Overlap recovery"): a tyre held to
// its robot by static friction, gentle recovery from overlaps, no force spikes. At 1 ms
// without substeps, on small hand-built scenes. The tests still  state targets the
// contact law does not meet yet (the doc gives their numbers).
#include "contact/contact_world.hpp"
#include "contact_runner.hpp"
#include "model/multibody.hpp"
#include "scene_builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace s2sim::contact {
namespace {

using scene::JointType;
using Runner = test::ContactRunner;
constexpr double kG = kGravity_m_s2;

void set_mu(scene::Body& b, double mu) {
  for (auto& g : b.geoms) {
    g.surface.explicit_surface = true;
    g.surface.mu = mu;
  }
}

/// A four-wheeled robot: a 1 kg chassis with its centre of mass at the axles' height and four
/// 0.1 kg tyres (radius 5 cm, 2 cm wide) on hinges along Y, resting on the ground.
struct Rover {
  static constexpr double kRadius = 0.05, kWheelMass = 0.1, kChassisMass = 1.0;
  static constexpr double kSpinInertia = 0.5 * kWheelMass * kRadius * kRadius;
  static constexpr double kTotalMass = kChassisMass + 4 * kWheelMass;
  static scene::Scene build(double mu) {
    scene::Scene s;
    s.settings.world_walls = false;
    const double z = kRadius - 1e-4;  // resting about its load's sink
    s.bodies.push_back(test::box("chassis", kChassisMass, {0.3, 0.2, 0.04}, {0, 0, z}));
    const double xs[2] = {-0.1, 0.1}, ys[2] = {-0.13, 0.13};
    for (double x : xs)
      for (double y : ys) {
        scene::Body w = test::sphere("wheel", kWheelMass, kRadius, {x, y, z});
        w.geoms[0].shape.type = scene::ShapeType::cylinder;
        w.geoms[0].shape.length_m = 0.02;
        w.geoms[0].pose.rotation = test::rotation_about({1, 0, 0}, kPi / 2);  // Z along Y
        const double across = kWheelMass * (3 * kRadius * kRadius + 0.02 * 0.02) / 12;
        w.inertia_kg_m2 = {{{across, 0, 0}, {0, kSpinInertia, 0}, {0, 0, across}}};
        set_mu(w, mu);
        const int index = static_cast<int>(s.bodies.size());
        s.bodies.push_back(w);
        s.joints.push_back(test::joint("axle", JointType::hinge, index, 0, {x, y, z}, {0, 1, 0}));
      }
    test::add_robot(s, "rover");
    return s;
  }
  /// The rigid-rolling acceleration of the chassis under `torque_Nm` on each axle.
  static double rolling_acceleration(double torque_Nm) {
    return 4 * torque_Nm / (kRadius * (kTotalMass + 4 * kSpinInertia / (kRadius * kRadius)));
  }
};

/// The slip speed at a tyre's lowest point (the contact), world frame, along X.
double tread_slip_m_s(const Runner& run, int body) {
  const Twist& t = run.twists[static_cast<std::size_t>(body)];
  return (t.linear_m_s + cross(t.angular_rad_s, Vec3{0, 0, -Rover::kRadius})).x;
}

void apply_axle_torques(Runner& run, double torque_Nm) {
  for (int a = 0; a < 4; ++a)
    run.mb.applied_axis_forces()[a] = torque_Nm;
}

TEST(ContactFidelity, RollingUnderTorqueBelowTheFrictionLimitFollowsRigidRolling) {
  // 0.02 N·m per axle: 1.0 m/s², a friction of 0.35 N per tyre under 3.4 N of load (mu = 1).
  const double torque = 0.02, h = 1e-3;
  Runner run(Rover::build(1.0));
  run.step(500);  // settle on the ground
  const double expected = Rover::rolling_acceleration(torque);
  double worst_error = 0, worst_slip = 0, v_last = run.twists[1].linear_m_s.x;
  double sign = 0;
  for (int n = 1; n <= 300; ++n) {
    apply_axle_torques(run, torque);
    run.step();
    const double v = run.twists[1].linear_m_s.x;
    const double a = (v - v_last) / h;
    v_last = v;
    if (n == 1) sign = a >= 0 ? 1 : -1;
    if (n >= 3) worst_error = std::max(worst_error, std::abs(sign * a - expected) / expected);
    for (int w = 2; w <= 5; ++w)
      worst_slip = std::max(worst_slip, std::abs(tread_slip_m_s(run, w)));
  }
  RecordProperty("worst_acceleration_error", std::to_string(worst_error));
  RecordProperty("worst_slip_m_s", std::to_string(worst_slip));
  EXPECT_LT(worst_error, 0.01) << "chassis acceleration off the rigid-rolling " << expected
                               << " m/s² by up to " << worst_error * 100 << " %";
  EXPECT_LT(worst_slip, 1e-3) << "a tyre slipped at " << worst_slip << " m/s";
}

TEST(ContactFidelity, A50HzTorqueSwingsTheWheelAsRigidRollingDoes) {
  const double torque = 0.02, frequency = 50, h = 1e-3;
  Runner run(Rover::build(1.0));
  run.step(500);
  double low = 1e9, high = -1e9;
  for (int n = 1; n <= 400; ++n) {
    apply_axle_torques(run, torque * std::sin(2 * kPi * frequency * (n - 1) * h));
    run.step();
    // The tyre's own spin (the axis rate adds the chassis's pitching on its contacts).
    const double spin = run.twists[2].angular_rad_s.y;
    if (n > 200) low = std::min(low, spin), high = std::max(high, spin);
  }
  const double amplitude = 0.5 * (high - low);
  const double omega = 2 * kPi * frequency;
  const double rigid = Rover::rolling_acceleration(torque) / (omega * Rover::kRadius);
  const double free_wheel = torque / (Rover::kSpinInertia * omega);
  RecordProperty("wheel_speed_amplitude_rad_s", std::to_string(amplitude));
  RecordProperty("rigid_rolling_rad_s", std::to_string(rigid));
  RecordProperty("free_wheel_rad_s", std::to_string(free_wheel));
  EXPECT_NEAR(amplitude, rigid, 0.1 * rigid)
      << "the free wheel would swing " << free_wheel << " rad/s";
}

TEST(ContactFidelity, AboveTheFrictionLimitTheTyresSlideAtMuG) {
  // 0.2 N·m per axle against a grip of about mu·N·r = 0.04 N·m: every tyre spins and slides.
  const double torque = 0.2, mu = 0.5;
  Runner run(Rover::build(mu));
  run.step(500);
  double v[2] = {0, 0};
  for (int n = 1; n <= 300; ++n) {
    apply_axle_torques(run, torque);
    run.step();
    if (n == 100) v[0] = run.twists[1].linear_m_s.x;
    if (n == 300) v[1] = run.twists[1].linear_m_s.x;
  }
  const double a = std::abs(v[1] - v[0]) / 0.2;
  RecordProperty("acceleration_m_s2", std::to_string(a));
  EXPECT_NEAR(a, mu * kG, 0.01 * mu * kG);
  EXPECT_GT(std::abs(tread_slip_m_s(run, 2)), 0.1) << "the tyres slide";
}

/// Runs `s` for 0.5 s: the largest speed any body reached (how fast the overlap threw it), the
/// bodies' largest speed at the end, the deepest contact at the end and the highest body.
struct Recovery {
  double peak_m_s = 0, final_m_s = 0, final_depth_m = 0, peak_height_m = 0;
};
Recovery recover(const scene::Scene& s) {
  Runner run(s);
  Recovery r;
  for (int n = 0; n < 500; ++n) {
    run.step();
    double fastest = 0;
    for (std::size_t b = 1; b < run.twists.size(); ++b) {
      fastest = std::max(fastest, norm(run.twists[b].linear_m_s));
      r.peak_height_m = std::max(r.peak_height_m, run.poses[b].position.z);
    }
    r.peak_m_s = std::max(r.peak_m_s, fastest);
    r.final_m_s = fastest;
  }
  r.final_depth_m = run.deepest_m();
  return r;
}

TEST(ContactFidelity, ABoxStartedACentimetreIntoAnotherSeparatesGently) {
  // Side by side on the floor, 1 cm into each other: pushed apart along X.
  scene::Scene s;
  s.settings.world_walls = false;
  s.bodies.push_back(test::box("left", 1.0, {0.1, 0.1, 0.1}, {-0.05 + 0.005, 0, 0.05}));
  s.bodies.push_back(test::box("right", 1.0, {0.1, 0.1, 0.1}, {0.05 - 0.005, 0, 0.05}));
  const Recovery r = recover(s);
  RecordProperty("peak_speed_m_s", std::to_string(r.peak_m_s));
  RecordProperty("final_speed_m_s", std::to_string(r.final_m_s));
  RecordProperty("final_depth_m", std::to_string(r.final_depth_m));
  EXPECT_LE(r.peak_m_s, 0.1) << "pushed apart too fast";
  EXPECT_LE(r.final_m_s, 0.1);
  EXPECT_LT(r.final_depth_m, 2e-3) << "still overlapping after 0.5 s";
}

TEST(ContactFidelity, ABoxStartedNineCentimetresIntoALargerBodySeparatesWithoutFlyingOff) {
  scene::Scene s;
  s.settings.world_walls = false;
  s.bodies.push_back(test::box("base", 10.0, {0.5, 0.5, 0.2}, {0, 0, 0.1}));
  s.bodies.push_back(test::box("sheet", 1.0, {0.3, 0.3, 0.1}, {0, 0, 0.2 + 0.05 - 0.09}));
  const Recovery r = recover(s);
  RecordProperty("peak_speed_m_s", std::to_string(r.peak_m_s));
  RecordProperty("final_speed_m_s", std::to_string(r.final_m_s));
  RecordProperty("final_depth_m", std::to_string(r.final_depth_m));
  RecordProperty("peak_height_m", std::to_string(r.peak_height_m));
  EXPECT_LE(r.peak_m_s, 0.5) << "thrown out";
  EXPECT_LE(r.final_m_s, 0.5);
  EXPECT_LT(r.final_depth_m, 2e-3) << "still overlapping after 0.5 s";
}

/// The scene's recovery speed applies: at a tenth of it the sheet 9 cm into its base is still
/// deep inside after 0.5 s, where it has left at the default.
TEST(ContactFidelity, TheScenesRecoverySpeedSetsHowFastAnOverlapIsLeft) {
  auto depth_after = [](double recovery_m_s) {
    scene::Scene s;
    s.settings.world_walls = false;
    s.settings.contact_recovery_speed_m_s = recovery_m_s;
    s.bodies.push_back(test::box("base", 10.0, {0.5, 0.5, 0.2}, {0, 0, 0.1}));
    s.bodies.push_back(test::box("sheet", 1.0, {0.3, 0.3, 0.1}, {0, 0, 0.2 + 0.05 - 0.09}));
    return recover(s).final_depth_m;
  };
  const double slow = depth_after(0.03),
               usual = depth_after(scene::Settings{}.contact_recovery_speed_m_s);
  RecordProperty("depth_after_half_a_second_at_0.03_m_s", std::to_string(slow));
  EXPECT_GT(slow, 0.05);
  EXPECT_LT(usual, 2e-3);
}

/// A 2 kg body on two free-turning 0.2 kg tyres at the back and two hinged legs with box feet
/// at the front, the legs held at zero by stiff implicit drives, set `sink_m` into the floor
/// (SimTwo's robots often start a little inside it). Over 2 s: the peak of the summed contact
/// forces, and how high a tyre's lowest point rose.
struct Standing {
  double peak_N = 0, highest_tread_m = 0, weight_N = 0;
  double final_depth_m = 0;  ///< the deepest contact at the end
};
Standing stand(double sink_m) {
  const double radius = 0.06, z = 0.12 - sink_m;
  scene::Scene s;
  s.settings.world_walls = false;
  s.bodies.push_back(test::box("body", 2.0, {0.4, 0.25, 0.06}, {0, 0, z}));
  for (double y : {-0.16, 0.16}) {
    scene::Body w = test::sphere("wheel", 0.2, radius, {-0.15, y, radius - sink_m});
    w.geoms[0].shape.type = scene::ShapeType::cylinder;
    w.geoms[0].shape.length_m = 0.03;
    w.geoms[0].pose.rotation = test::rotation_about({1, 0, 0}, kPi / 2);
    const int index = static_cast<int>(s.bodies.size());
    s.bodies.push_back(w);
    s.joints.push_back(
        test::joint("axle", JointType::hinge, index, 0, {-0.15, y, radius - sink_m}, {0, 1, 0}));
  }
  for (double y : {-0.1, 0.1}) {
    const int index = static_cast<int>(s.bodies.size());
    s.bodies.push_back(test::box("leg", 0.3, {0.04, 0.04, 0.12}, {0.15, y, 0.06 - sink_m}));
    s.joints.push_back(
        test::joint("hip", JointType::hinge, index, 0, {0.15, y, 0.12 - sink_m}, {0, 1, 0}));
  }
  test::add_robot(s, "walker");
  Standing out;
  out.weight_N = (2.0 + 2 * 0.2 + 2 * 0.3) * kG;
  Runner run(s);
  for (int n = 0; n < 2000; ++n) {
    std::int32_t& count = *run.mb.axis_drive_count();
    count = 0;
    for (int a = 2; a < 4; ++a)  // the hips held at zero: a stiff PD, implicit
      run.mb.axis_drives()[count++] = {a, -200.0 * run.pos[static_cast<std::size_t>(a)], 5.0, -50.0,
                                       50.0};
    run.step();
    double total = 0;
    for (std::int32_t i = 0; i < *run.contacts.contact_count(); ++i)
      total += norm(run.contacts.contacts()[i].force_N);
    out.peak_N = std::max(out.peak_N, total);
    for (std::size_t w = 2; w <= 3; ++w)  // kernel bodies: 1 the body, 2 and 3 the tyres
      out.highest_tread_m = std::max(out.highest_tread_m, run.poses[w].position.z - radius);
  }
  for (std::int32_t i = 0; i < *run.contacts.contact_count(); ++i)
    out.final_depth_m = std::max(out.final_depth_m, run.contacts.contacts()[i].depth_m);
  return out;
}

void expect_standing(double sink_m, const std::string& at) {
  const Standing r = stand(sink_m);
  ::testing::Test::RecordProperty("peak_total_contact_force_N" + at, std::to_string(r.peak_N));
  ::testing::Test::RecordProperty("highest_tread_m" + at, std::to_string(r.highest_tread_m));
  ::testing::Test::RecordProperty("final_depth_m" + at, std::to_string(r.final_depth_m));
  std::printf(
      "  set %.3f m into the floor: peak %.1f N (weight %.1f N), highest tread %.5f m, deepest "
      "contact after 2 s %.6f m\n",
      sink_m, r.peak_N, r.weight_N, r.highest_tread_m, r.final_depth_m);
  EXPECT_LT(r.peak_N, 3 * r.weight_N)
      << "weight " << r.weight_N << " N, set " << sink_m << " m into the floor";
  EXPECT_LT(r.highest_tread_m, 1e-3) << "a wheel left the floor, set " << sink_m << " m into it";
  EXPECT_LT(r.final_depth_m, 2e-4) << "still inside the floor after 2 s, set " << sink_m << " m";
}

TEST(ContactFidelity, AWheeledLeggedRobotStandsWithoutForceSpikesOrHops) {
  expect_standing(0.0, "_on_the_floor");
}

// Set 5 mm into the floor, the whole spring threw it: 4 312 N at once, its tyres 26 mm up. Its
// points are born deeper than their motion explains, and the overlap relaxes instead.
TEST(ContactFidelity, AWheeledLeggedRobotSetIntoTheFloorStandsWithoutForceSpikes) {
  expect_standing(0.005, "_5_mm_into_the_floor");
}

/// Set 3 cm in, deeper than its feet are tall across: it rises out at the bounded speed.
TEST(ContactFidelity, AWheeledLeggedRobotSetThreeCentimetresIntoTheFloorRisesOutGently) {
  expect_standing(0.03, "_30_mm_into_the_floor");
}

}  // namespace
}  // namespace s2sim::contact
