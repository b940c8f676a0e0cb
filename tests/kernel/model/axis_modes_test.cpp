// Axis friction and bounds solved exactly in the axes' modes (kernel/src/model/axis_modes.cpp).
#include "model_runner.hpp"
#include "scene_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace s2sim::model {
namespace {

using scene::JointType;
using test::Runner;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// A horizontal arm of three hinges about y on the world, light at the shoulder and heavy at
/// the hand: its axes are strongly coupled through M^-1 (as a humanoid's legs are).
scene::Scene arm() {
  scene::Scene s;
  s.bodies.push_back(test::sphere("upper", 0.05, 0.01, {0.1, 0, 1}));
  s.bodies.push_back(test::sphere("fore", 0.5, 0.02, {0.2, 0, 1}));
  s.bodies.push_back(test::sphere("hand", 2.0, 0.03, {0.3, 0, 1}));
  const Vec3 y{0, 1, 0};
  s.joints.push_back(test::joint("shoulder", JointType::hinge, 0, -1, {0, 0, 1}, y));
  s.joints.push_back(test::joint("elbow", JointType::hinge, 1, 0, {0.1, 0, 1}, y));
  s.joints.push_back(test::joint("wrist", JointType::hinge, 2, 1, {0.2, 0, 1}, y));
  test::add_robot(s, "arm");
  return s;
}

/// One tick with Coulomb bounds on the three axes and an optional drive on axis `driven`.
void step(Runner& r, const double (&friction)[3], int driven = -1, double force = 0,
          double damping = 0) {
  *r.mb.axis_drive_count() = 0;
  if (driven >= 0)
    r.mb.axis_drives()[(*r.mb.axis_drive_count())++] =
        AxisDrive{driven, force, damping, -kInf, kInf};
  for (int a = 0; a < 3; ++a)
    r.mb.applied_axis_friction()[a] = friction[a];
  r.step();
}

// Gravity's torques on the axes at rest are 6.9, 4.4 and 2.0 N·m; friction bounds above them
// hold the arm exactly still: no creep from a solve stopped short of the law (block
// Gauss-Seidel alone, capped at 16 sweeps, left the wrist creeping here).
TEST(AxisModes, ACoupledArmHeldByItsFrictionStandsExactlyStill) {
  Runner r(arm());
  const double friction[3] = {10.0, 6.0, 3.0};
  for (int n = 0; n < 2000; ++n) {
    step(r, friction);
    for (int a = 0; a < 3; ++a) {
      ASSERT_EQ(r.vel[a], 0.0) << "axis " << a << " at step " << n;
      ASSERT_EQ(r.pos[a], 0.0) << "axis " << a << " at step " << n;
    }
  }
}

// A drive stronger than the wrist's friction turns it while the shoulder and elbow stick: the
// stuck axes stand exactly still, and the wrist's speed follows its law with its friction
// against it, F − c·v − F_wrist = I·v' where it settles: v = (F − F_wrist) / c.
TEST(AxisModes, ADrivenWristSlidesWhileTheOtherAxesStickExactly) {
  Runner r(arm());
  const double friction[3] = {40.0, 30.0, 3.0};
  const double force = 8.0, damping = 2.0;
  for (int n = 0; n < 3000; ++n) {
    step(r, friction, 2, force - damping * r.vel[2], damping);
    ASSERT_EQ(r.vel[0], 0.0) << "shoulder at step " << n;
    ASSERT_EQ(r.vel[1], 0.0) << "elbow at step " << n;
  }
  EXPECT_GT(std::abs(r.pos[2]), 1.0);  // it turned
  // Over a turn gravity's torque on the wrist (±2.0 N·m) varies: the speed stays within the
  // law's range for it, (F − F_wrist ± 2.0) / c.
  EXPECT_GT(r.vel[2], (force - friction[2] - 2.0) / damping - 1e-9);
  EXPECT_LT(r.vel[2], (force - friction[2] + 2.0) / damping + 1e-9);
}

}  // namespace
}  // namespace s2sim::model
