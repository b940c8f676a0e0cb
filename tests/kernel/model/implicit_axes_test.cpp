// Axis drives and Coulomb friction solved implicitly (kernel/src/model/implicit_axes.cpp).
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

/// A gravity-free rotor about a hinge on the world: a bob of mass m at radius L, inertia
/// m·L² (plus the bob's own).
scene::Scene rotor(double mass_kg, double radius_m) {
  scene::Scene s;
  s.bodies.push_back(test::sphere("bob", mass_kg, 0.001, {radius_m, 0, 1}));
  s.bodies[0].gravity = false;
  s.joints.push_back(test::joint("J", JointType::hinge, 0, -1, {0, 0, 1}, {0, 0, 1}));
  test::add_robot(s, "rotor");
  return s;
}
double rotor_inertia(double m, double L) {
  return m * L * L + 0.4 * m * 0.001 * 0.001;
}

/// One tick with one drive on axis 0 (and the given friction bound), as a component writes it.
void step_with_drive(Runner& r, double force, double damping, double low = -kInf,
                     double high = kInf, double friction = 0) {
  *r.mb.axis_drive_count() = 0;
  r.mb.axis_drives()[(*r.mb.axis_drive_count())++] = AxisDrive{0, force, damping, low, high};
  r.mb.applied_axis_friction()[0] = friction;
  r.step();
}

// A drive F − c·(v − v0) read at the tick's start, on an axis whose explicit damping would be
// h·c/I = 1e4: every step is the linearly implicit Euler step, v1 = v0 + κ(F − c(v1 − v0))/I
// (κ = h/2 on the first step), and the speed rises monotonically to F/c, never past it.
TEST(ImplicitAxes, StiffDriveIsLinearlyImplicitEulerAndNeverOvershoots) {
  const double m = 1e-3, L = 0.01, I = rotor_inertia(m, L), h = 1e-3;
  const double c = 1e4 * I / h, target = 2.0;  // F − c·v vanishes at v = 2 rad/s
  Runner r(rotor(m, L));
  double v = 0;
  for (int n = 0; n < 200; ++n) {
    const double F = c * (target - v);  // the drive's value at the speed read
    step_with_drive(r, F, c);
    const double kick = n == 0 ? 0.5 * h : h;
    const double expected = v + kick * F / (I + kick * c);
    EXPECT_NEAR(r.vel[0], expected, 1e-10 * target) << "step " << n;
    EXPECT_LE(r.vel[0], target * (1 + 1e-12)) << "overshoot at step " << n;
    EXPECT_GE(r.vel[0], v) << "the speed fell back at step " << n;
    v = r.vel[0];
  }
  EXPECT_NEAR(v, target, 1e-9 * target);
}

// A bounded drive (a motor at its current limit) pushes with exactly its bound until the law
// falls inside it: I·v' = 0.5 N·m until F − c·v = 0.5.
TEST(ImplicitAxes, BoundedDriveAcceleratesAtItsBoundThenFollowsItsLaw) {
  const double m = 1.0, L = 1.0, I = rotor_inertia(m, L), h = 1e-3;
  const double c = 1.0, bound = 0.5;
  Runner r(rotor(m, L));
  double v = 0;
  for (int n = 0; n < 1000; ++n) {  // 1 s: v reaches about 0.5, still in the bounded phase
    step_with_drive(r, 10.0 - c * v, c, -bound, bound);
    v = r.vel[0];
  }
  // Mid-step speeds: after the half kick and 999 full kicks, v = (0.5·h + 999·h)·bound/I.
  EXPECT_NEAR(v, 0.9995 * bound / I, 1e-12);
  for (int n = 1000; n < 30000; ++n) {  // the bound holds until v = 9.5 (19 s), then the law
    step_with_drive(r, 10.0 - c * v, c, -bound, bound);
    v = r.vel[0];
    if (n == 18000 - 1) {
      EXPECT_NEAR(v, (18.0 - 0.5 * h) * bound / I, 1e-9);
    }
  }
  EXPECT_NEAR(v, 10.0, 1e-4);  // 10 − 0.5·e^(−11) after the bounded phase
}

// Friction and drive on one axis are solved together: a drive weaker than the friction bound
// leaves the axis exactly still (no creep); a stronger one turns it, and it settles where the
// drive's law equals the friction.
TEST(ImplicitAxes, DriveAndCoulombFrictionOnOneAxisStickOrSlideTogether) {
  const double m = 1e-3, L = 0.01, I = rotor_inertia(m, L), h = 1e-3;
  const double c = 1e3 * I / h, friction = 2e-3;
  {
    Runner r(rotor(m, L));
    for (int n = 0; n < 2000; ++n)
      step_with_drive(r, 1e-3 - c * r.vel[0], c, -kInf, kInf, friction);
    EXPECT_EQ(r.vel[0], 0.0);
    EXPECT_EQ(r.pos[0], 0.0);
  }
  {
    Runner r(rotor(m, L));
    const double F = 3e-3;
    for (int n = 0; n < 2000; ++n)
      step_with_drive(r, F - c * r.vel[0], c, -kInf, kInf, friction);
    EXPECT_NEAR(r.vel[0], (F - friction) / c, 1e-9 * F / c);
  }
}

// Two stiff drives on a chain (a double pendulum without gravity): coupled through M^-1, solved
// together, both axes reach their targets without ringing.
TEST(ImplicitAxes, CoupledStiffDrivesOnAChainSettleWithoutRinging) {
  scene::Scene s;
  s.bodies.push_back(test::sphere("a", 0.01, 0.005, {0.05, 0, 1}));
  s.bodies.push_back(test::sphere("b", 0.01, 0.005, {0.10, 0, 1}));
  for (auto& b : s.bodies)
    b.gravity = false;
  s.joints.push_back(test::joint("J1", JointType::hinge, 0, -1, {0, 0, 1}, {0, 0, 1}));
  s.joints.push_back(test::joint("J2", JointType::hinge, 1, 0, {0.05, 0, 1}, {0, 0, 1}));
  test::add_robot(s, "chain");
  Runner r(s);
  const double c = 10.0, targets[2] = {1.0, -2.0};  // c·h over these inertias: 1e2..1e3
  std::vector<double> previous(2, 0.0);
  int sign_changes = 0;
  double last_delta[2] = {0, 0};
  for (int n = 0; n < 3000; ++n) {
    *r.mb.axis_drive_count() = 2;
    for (int a = 0; a < 2; ++a)
      r.mb.axis_drives()[a] = AxisDrive{a, c * (targets[a] - r.vel[a]), c, -kInf, kInf};
    r.step();
    for (int a = 0; a < 2; ++a) {
      const double delta = r.vel[a] - previous[a];
      if (n > 10 && delta * last_delta[a] < 0 && std::abs(delta) > 1e-9) ++sign_changes;
      last_delta[a] = delta;
      previous[a] = r.vel[a];
    }
  }
  EXPECT_NEAR(r.vel[0], targets[0], 1e-6);
  EXPECT_NEAR(r.vel[1], targets[1], 1e-6);
  EXPECT_EQ(sign_changes, 0) << "the speeds ring from step to step";
}

}  // namespace
}  // namespace s2sim::model
