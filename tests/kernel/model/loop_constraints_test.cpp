// Loop joints on the fast path (kernel/src/model/loop_constraints.cpp) against Simbody's loop
// forward dynamics and projections: every kind of constraint row (a ball's three, a constant
// angle's one), on trees hinged to the world and on a free root, with drives and friction on
// the loop joint's own axis; and the semidefinite solve of redundant rows (common/cholesky.hpp).
#include "common/cholesky.hpp"
#include "common/state_layout.hpp"
#include "fast_path_comparison.hpp"
#include "model/multibody.hpp"
#include "model_runner.hpp"
#include "scene_builder.hpp"

#include <s2sim/error.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace s2sim::model {
namespace {

using scene::JointType;

/// A free chassis carrying a parallelogram: two legs hinged under it, a foot bar hinged to
/// both (the second foot hinge closes the loop: a ball and two constant angles).
scene::Scene walker() {
  scene::Scene s;
  const Vec3 y{0, 1, 0};
  s.bodies.push_back(test::box("chassis", 4.0, {0.6, 0.3, 0.1}, {0, 0, 1.0},
                               test::rotation_about({1, 2, 3}, 0.2)));
  s.bodies[0].com_m = {0.02, -0.01, 0.01};
  const Mat3 R = s.bodies[0].pose.rotation;
  const Vec3 c = s.bodies[0].pose.position;
  auto at = [&](Vec3 local) { return c + R * local; };
  s.bodies.push_back(test::box("front", 0.5, {0.02, 0.02, 0.4}, at({0.2, 0, -0.25}), R));
  s.bodies.push_back(test::box("back", 0.5, {0.02, 0.02, 0.4}, at({-0.2, 0, -0.25}), R));
  s.bodies.push_back(test::box("foot", 0.8, {0.4, 0.04, 0.02}, at({0, 0, -0.45}), R));
  const Vec3 axis = R * y;
  s.joints.push_back(test::joint("hip_front", JointType::hinge, 1, 0, at({0.2, 0, -0.05}), axis));
  s.joints.push_back(test::joint("hip_back", JointType::hinge, 2, 0, at({-0.2, 0, -0.05}), axis));
  s.joints.push_back(test::joint("ankle_front", JointType::hinge, 3, 1, at({0.2, 0, -0.45}), axis));
  s.joints.push_back(test::joint("ankle_back", JointType::hinge, 3, 2, at({-0.2, 0, -0.45}), axis));
  test::add_robot(s, "walker");
  return s;
}

/// A spatial loop closed by a ball: four links on skew hinges from the world, the last one's
/// tip held at a point of the world (three equations, one degree of freedom left).
scene::Scene spatial_ball_loop() {
  scene::Scene s;
  s.bodies.push_back(test::box("crank", 0.6, {0.02, 0.3, 0.02}, {0, 0.15, 2}));
  s.bodies.push_back(test::box("link1", 0.4, {0.3, 0.02, 0.02}, {0.15, 0.3, 2}));
  s.bodies.push_back(test::box("link2", 0.4, {0.02, 0.02, 0.3}, {0.3, 0.3, 1.85}));
  s.bodies.push_back(test::box("link3", 0.7, {0.02, 0.3, 0.02}, {0.3, 0.15, 1.7}));
  s.joints.push_back(test::joint("crank", JointType::hinge, 0, -1, {0, 0, 2}, {1, 0, 0}));
  s.joints.push_back(test::joint("elbow", JointType::hinge, 1, 0, {0, 0.3, 2}, {0, 1, 1}));
  s.joints.push_back(test::joint("wrist", JointType::hinge, 2, 1, {0.3, 0.3, 2}, {1, 0.4, 1}));
  s.joints.push_back(test::joint("knee", JointType::hinge, 3, 2, {0.3, 0.3, 1.7}, {1, 0, 0.3}));
  s.joints.push_back(test::joint("tip", JointType::ball, 3, -1, {0.3, 0, 1.7}));
  test::add_robot(s, "linkage");
  return s;
}

/// Spin the first axis up: the velocity-product terms must count.
void spin_first_axis(Multibody& mb, int tick) {
  mb.applied_axis_forces()[0] += tick < 150 ? 4.0 : 0.0;
}

/// A drive on every loop axis and on the first axis (the implicit solve's rows: the loop
/// axes' columns through the tree), and Coulomb friction on the loop axes.
void drive_loop_axes(Multibody& mb, int tick) {
  *mb.axis_drive_count() = 0;
  for (std::size_t a = 0; a < mb.axes().size(); ++a) {
    if (!mb.axes()[a].loop && a != 0) continue;
    const double f = 0.4 * std::sin(0.01 * tick + static_cast<double>(a));
    mb.axis_drives()[(*mb.axis_drive_count())++] =
        AxisDrive{static_cast<std::int32_t>(a), f, 0.05, -0.3, 0.3};
    if (mb.axes()[a].loop) mb.applied_axis_friction()[a] = 0.02;
  }
}

int loop_axes(const Multibody& mb) {
  int n = 0;
  for (const auto& a : mb.axes())
    n += a.loop;
  return n;
}

// The tolerance on planar loops: the projections are Simbody's (the same errors, weights,
// thresholds and Newton steps), so the ticks agree to rounding.
constexpr test::FastPathTolerance kLoopTolerance{1e-13, 1e-11};

/// Compares the fast path with Simbody on `s` (whose loop joints have `expected_loop_axes`
/// axes) tick by tick, under loads everywhere, drives on the loop axes and `spin`; prints and
/// returns the worst relative difference of a velocity change.
double driven_difference(const scene::Scene& s, int expected_loop_axes,
                         void (*spin)(Multibody&, int), const char* name) {
  test::Runner probe(s);
  EXPECT_EQ(loop_axes(probe.mb), expected_loop_axes) << name;
  const double worst =
      test::worst_relative_difference(s, 400, kLoopTolerance, [spin](Multibody& mb, int tick) {
        drive_loop_axes(mb, tick);
        if (spin != nullptr) spin(mb, tick);
      });
  std::printf("%s: worst relative difference of the velocity change %.3g\n", name, worst);
  return worst;
}

/// The scene with joint `j` turned into a slider along `axis`.
scene::Scene with_slider(scene::Scene s, int j, const Vec3& axis) {
  s.joints[static_cast<std::size_t>(j)].type = JointType::slider;
  s.joints[static_cast<std::size_t>(j)].axis1 = axis;
  return s;
}

TEST(LoopConstraints, FourBarWithDrivenLoopAxisMatchesSimbodysLoopDynamics) {
  EXPECT_LT(driven_difference(test::four_bar(), 1, spin_first_axis, "four-bar"), 1e-11);
}

TEST(LoopConstraints, FreeWalkerParallelogramMatchesSimbody) {
  EXPECT_LT(driven_difference(walker(), 1, nullptr, "walker"), 1e-11);
}

// A spatial loop: its position errors after a drift are larger (1e-5 m here), and the
// projection's second Newton step depends on where the ball's row is taken on body 1 (Simbody:
// at the point of body 1 where p2 is, not at p1). Checked to the same tolerance as the planar
// loops, and the loop's closure on its own: the last link's tip stays on its point of the world.
TEST(LoopConstraints, SpatialBallLoopMatchesSimbody) {
  test::Runner probe(spatial_ball_loop());
  EXPECT_EQ(loop_axes(probe.mb), 0);  // a ball has no axis
  const double worst =
      test::worst_relative_difference(spatial_ball_loop(), 400, kLoopTolerance, spin_first_axis);
  std::printf("spatial ball loop: worst relative difference of the velocity change %.3g\n", worst);
  EXPECT_LT(worst, 1e-10);
  test::Runner r(spatial_ball_loop());
  ASSERT_TRUE(r.mb.uses_tree_fast_path());
  const Vec3 tip_in_link3 =
      r.poses[4].rotation.transposed() * (Vec3{0.3, 0, 1.7} - r.poses[4].position);
  double worst_gap = 0, fastest = 0;
  for (int tick = 0; tick < 400; ++tick) {
    test::load_everywhere(r.mb, tick);
    spin_first_axis(r.mb, tick);
    r.step();
    worst_gap = std::max(worst_gap, norm(r.poses[4] * tip_in_link3 - Vec3{0.3, 0, 1.7}));
    fastest = std::max(fastest, std::abs(r.vel[0]));
  }
  std::printf("spatial ball loop: the tip's worst gap %.3g m\n", worst_gap);
  EXPECT_GT(fastest, 1.0);
  EXPECT_LT(worst_gap, 2e-10);
}

// Two seconds of a driven four-bar, each side on its own (not re-synchronised): the fast path
// follows Simbody's trajectory, and its loop stays closed.
TEST(LoopConstraints, TwoSecondsOfADrivenFourBarFollowSimbodysTrajectory) {
  test::Runner fast(test::four_bar()), simbody(test::four_bar());
  simbody.mb.choose_dynamics(model::DynamicsChoice::simbody);
  ASSERT_TRUE(fast.mb.uses_tree_fast_path());
  double worst = 0, worst_closure = 0, travel = 0;
  for (int tick = 0; tick < 2000; ++tick) {
    for (test::Runner* r : {&fast, &simbody}) {
      r->mb.applied_axis_forces()[0] = tick < 300 ? 3.0 : -0.5;
      drive_loop_axes(r->mb, tick);
    }
    fast.step();
    simbody.step();
    for (int b = 1; b < fast.mb.body_count(); ++b)
      worst = std::max(worst, norm(fast.poses[b].position - simbody.poses[b].position));
    // The loop axis D reads the coupler relative to crank2: minus crank2's angle.
    worst_closure = std::max(worst_closure, std::abs(fast.pos[3] + fast.pos[1]));
    travel = std::max(travel, std::abs(fast.pos[0]));
  }
  std::printf("four-bar, 2 s: worst position difference %.3g m, loop %.3g rad\n", worst,
              worst_closure);
  EXPECT_GT(travel, 0.5);
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(worst_closure, 1e-12);
}

// A slider closing the loop: a constant orientation (three angles) and a point on a line.
// (The four-bar's loop is B, met last: crank2 is reached through the coupler first.)
TEST(LoopConstraints, SliderLoopMatchesSimbody) {
  const scene::Scene s = with_slider(test::four_bar(), 1, {1, 0, 0});
  EXPECT_LT(driven_difference(s, 1, spin_first_axis, "slider loop"), 1e-11);
}

/// A free chassis with two legs hinged under it, and a bar hinged to the first leg's foot and
/// welded to the second's (a fixed joint closing the loop: three angles and a ball).
scene::Scene welded_frame() {
  scene::Scene s;
  const Mat3 R = test::rotation_about({2, -1, 3}, 0.4);
  const Vec3 c{0.2, -0.1, 1.0};
  auto at = [&](Vec3 local) { return c + R * local; };
  s.bodies.push_back(test::box("chassis", 3.0, {0.4, 0.2, 0.1}, c, R));
  s.bodies.push_back(test::box("leg_a", 0.3, {0.02, 0.02, 0.3}, at({0.1, 0, -0.2}), R));
  s.bodies.push_back(test::box("leg_b", 0.3, {0.02, 0.02, 0.3}, at({-0.1, 0, -0.2}), R));
  s.bodies.push_back(test::box("bar", 0.2, {0.2, 0.02, 0.02}, at({0, 0, -0.35}), R));
  const Vec3 y = R * Vec3{0, 1, 0};
  s.joints.push_back(test::joint("hip_a", JointType::hinge, 1, 0, at({0.1, 0, -0.05}), y));
  s.joints.push_back(test::joint("hip_b", JointType::hinge, 2, 0, at({-0.1, 0, -0.05}), y));
  s.joints.push_back(test::joint("knee", JointType::hinge, 3, 1, at({0.1, 0, -0.35}), y));
  s.joints.push_back(test::joint("weld", JointType::fixed, 3, 2, at({-0.1, 0, -0.35})));
  test::add_robot(s, "frame");
  return s;
}

/// Spin the free chassis (kernel body 1) for the first 200 ticks.
void spin_chassis(Multibody& mb, int tick) {
  if (tick < 200) mb.applied_wrenches()[1].torque_Nm += Vec3{0.6, -0.4, 0.9};
}

TEST(LoopConstraints, WeldedFrameOnAFreeRootMatchesSimbody) {
  EXPECT_LT(driven_difference(welded_frame(), 0, spin_chassis, "welded frame"), 1e-11);
}

// The same frame with the bar sliding along itself in the second leg: a line whose base body
// turns (its normals' rates count), on a free root.
TEST(LoopConstraints, SliderBetweenTurningBodiesMatchesSimbody) {
  const scene::Scene frame = welded_frame();
  const scene::Scene s = with_slider(frame, 3, frame.bodies[0].pose.rotation * Vec3{1, 0, 0});
  EXPECT_LT(driven_difference(s, 1, spin_chassis, "sliding frame"), 1e-11);
}

// A loop that no correction can close: a bar hinged to the world about z at one end, its other
// end held at its load position by a ball to the world (nothing left free). Restored half a
// turn about the hinge, the tip's error (twice the bar's length) is perpendicular to every
// correction the hinge allows, so the projection's Gauss-Newton steps move nothing: the tick
// stops with a runtime error saying so, rather than stepping on with the loop open.
TEST(LoopConstraints, ALoopThatCannotBeClosedStopsTheTickWithAnError) {
  scene::Scene s;
  s.bodies.push_back(test::box("bar", 1.0, {0.5, 0.04, 0.04}, {0.25, 0, 1}));
  s.joints.push_back(test::joint("hinge", JointType::hinge, 0, -1, {0, 0, 1}, {0, 0, 1}));
  s.joints.push_back(test::joint("tip", JointType::ball, 0, -1, {0.5, 0, 1}));
  test::add_robot(s, "pinned bar");
  test::Runner r(s);
  ASSERT_TRUE(r.mb.uses_tree_fast_path());
  ASSERT_EQ(r.mb.axes().size(), 1u);
  r.step(20);  // closed at load: it stays so
  EXPECT_LT(std::abs(r.pos[0]), 1e-12);

  common::StateLayout layout;
  r.mb.declare_state(layout);
  std::vector<double> state;
  layout.save(state);
  const auto ranges = common::StateLayout::locate(layout.entries(), state);
  std::size_t q = 0;
  while (layout.entries()[q].name != "multibody/q")
    ++q;
  ASSERT_EQ(ranges[q].size, 1u);  // the hinge's angle
  state[ranges[q].offset] = M_PI;
  layout.restore(layout.id(), layout.entries(), state);
  r.mb.restored();
  try {
    r.step();
    ADD_FAILURE() << "a loop open by 1 m stepped on";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::runtime);
    EXPECT_NE(std::string(e.what()).find("the loop joints could not be closed"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("RMS error"), std::string::npos) << e.what();
    std::printf("%s\n", e.what());
  }
}

// Redundant rows: a planar loop's five equations have rank two. The solve leaves the redundant
// unknowns at zero and still solves A·x = b exactly for b in A's range.
TEST(SemidefiniteSolve, RankDeficientSystemsAreSolvedOnTheirRange) {
  // G: 5 x 3 of rank 2 (rows 1, 3, 4 combinations of rows 0 and 2).
  const double G[5][3] = {
      {0.4, -0.4, 0.0}, {0.8, -0.8, 0.0}, {0.5, 0.0, 0.5}, {0.9, -0.4, 0.5}, {-0.1, -0.4, -0.5}};
  const double u[3] = {0.3, -0.7, 0.2};
  double A[25], b[5], x[5];
  int order[5];
  for (int r = 0; r < 5; ++r) {
    b[r] = 0;
    for (int k = 0; k < 3; ++k)
      b[r] += G[r][k] * u[k];
    for (int c = 0; c < 5; ++c) {
      A[r * 5 + c] = 0;
      for (int k = 0; k < 3; ++k)
        A[r * 5 + c] += G[r][k] * G[c][k];
    }
  }
  double A0[25], b0[5];
  std::copy(A, A + 25, A0);
  std::copy(b, b + 5, b0);
  double scratch[5 * 5 + 2 * 5];
  EXPECT_EQ(common::semidefinite_solve(A, 5, b, x, order, scratch, 1e-12), 2);
  for (int r = 0; r < 5; ++r) {
    double Ax = 0;
    for (int c = 0; c < 5; ++c)
      Ax += A0[r * 5 + c] * x[c];
    EXPECT_NEAR(Ax, b0[r], 1e-14) << "row " << r;
  }
  // u − Gᵀx is u's projection on G's null space: G·(u − Gᵀx) = 0.
  double projected[3];
  for (int k = 0; k < 3; ++k) {
    projected[k] = u[k];
    for (int r = 0; r < 5; ++r)
      projected[k] -= G[r][k] * x[r];
  }
  for (int r = 0; r < 5; ++r)
    EXPECT_NEAR(G[r][0] * projected[0] + G[r][1] * projected[1] + G[r][2] * projected[2], 0.0,
                1e-15);
  // A full-rank system: the plain solution.
  double B[4] = {4, 1, 1, 3}, c[2] = {1, 2}, y[2];
  int order2[2];
  double scratch2[2 * 2 + 2 * 2];
  EXPECT_EQ(common::semidefinite_solve(B, 2, c, y, order2, scratch2, 1e-12), 2);
  EXPECT_NEAR(4 * y[0] + y[1], 1, 1e-15);
  EXPECT_NEAR(y[0] + 3 * y[1], 2, 1e-15);
}

}  // namespace
}  // namespace s2sim::model
