// Stops through resting contacts and held points (docs/models/contact.md, "Stops through
// resting contacts"): the solver alone on hand-made rows, then landings and loads in scenes
// where a penalty spring alone sinks millimetres at 1 ms.
#include "contact/stop_graph.hpp"
#include "contact/contact_world.hpp"
#include "contact_runner.hpp"
#include "model/multibody.hpp"
#include "scene_builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace s2sim::contact {
namespace {

/// Point masses (no rotation) in a row along z, index 0 the world.
struct PointMasses {
  explicit PointMasses(std::vector<double> masses_kg) {
    inverse_mass.push_back(0);
    for (double m : masses_kg)
      inverse_mass.push_back(1 / m);
    const std::size_t n = inverse_mass.size();
    inverse_inertia.assign(n, Mat3{{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}});  // no rotation
    to_body.assign(n, Mat3::identity());
    com_m.assign(n, Vec3{});
    poses.assign(n, Pose{});
    falls_m_s2.assign(n, 0.0);
    wrenches.assign(n, Wrench{});
    graph.reserve(n, 16);
  }
  BodyInertiaView view() {
    return {inverse_mass.data(), inverse_inertia.data(), to_body.data(),
            com_m.data(),        poses.data(),           falls_m_s2.data()};
  }
  /// The velocity change the solved forces give body b over one step h.
  double dvz(int b, double h) const {
    return wrenches[static_cast<std::size_t>(b)].force_N.z * h *
           inverse_mass[static_cast<std::size_t>(b)];
  }
  std::vector<double> inverse_mass, falls_m_s2;
  std::vector<Mat3> inverse_inertia, to_body;
  std::vector<Vec3> com_m;
  std::vector<Pose> poses;
  std::vector<Wrench> wrenches;
  /// A resting point reported as contact `k` (its point and normal read from there).
  void rest(int k, int a, int b, const Vec3& point, double closing_m_s, bool held) {
    info[static_cast<std::size_t>(k)].point_m = point;
    info[static_cast<std::size_t>(k)].normal = {0, 0, 1};
    graph.add_resting(a, b, closing_m_s, held, k, k, 0.0);
  }
  std::vector<ContactInfo> info = std::vector<ContactInfo>(8);
  StopGraph graph;
};

constexpr double kH = 1e-3;
const Vec3 kUp{0, 0, 1};

TEST(StopGraph, OneStopGetsExactlyItsWantedChange) {
  PointMasses p({2.0});
  p.graph.add_stop(1, 0, {0, 0, 0}, kUp, 3.0);  // body 1 on the ground, to lose 3 m/s
  p.graph.solve(p.view(), kH, p.wrenches.data(), p.info.data());
  EXPECT_NEAR(p.dvz(1, kH), 3.0, 1e-12);
}

TEST(StopGraph, AStopIsPassedThroughARestingContactToTheGround) {
  // Body 2 lands on body 1, which rests on the ground: the stop may not push 1 into the
  // ground, so both end at rest (a penalty spring alone would let 1 sink by the momentum).
  PointMasses p({1.0, 1.0});
  p.rest(0, 1, 0, {0, 0, 0}, 0.0, false);         // 1 on the ground, at rest
  p.graph.add_stop(2, 1, {0, 0, 0.1}, kUp, 2.0);  // 2 closing on 1 at 2 m/s
  p.graph.solve(p.view(), kH, p.wrenches.data(), p.info.data());
  // A group this small is solved exactly (Gauss–Seidel, which halves this pair's error at each
  // sweep, left 2^-15 of it after its 16 sweeps).
  EXPECT_NEAR(p.dvz(2, kH), 2.0, 1e-12);
  EXPECT_NEAR(p.dvz(1, kH), 0.0, 1e-12);
  EXPECT_NEAR(p.info[0].force_N.z * kH, 2.0, 1e-12) << "the ground carries the stopped momentum";
}

/// A stack of `count` bodies (first, first + 1, ...) at x, each resting on the one below, the
/// lowest on the ground, the top one stopped at 2 m/s: count + 1 rows, reported as contacts
/// info0, info0 + 1, ...
void stack(PointMasses& p, int first, int count, double x, int info0) {
  if (p.info.size() < static_cast<std::size_t>(info0 + count))
    p.info.resize(static_cast<std::size_t>(info0 + count));
  for (int k = 0; k < count; ++k)
    p.rest(info0 + k, first + k, k == 0 ? 0 : first + k - 1, {x, 0, 0.1 * k}, 0.0, false);
  p.graph.add_stop(first + count - 1, first + count - 2, {x, 0, 0.1 * count}, kUp, 2.0);
}

// A group of rows joined through their bodies is solved as it would be alone: a part of the
// island-parallel step solves its own groups to the same bits (contact_parts.cpp). Group A, a
// 1 kg body stopped on 9 kg resting on the ground, is small and solved exactly; group B, a
// stack of 30 bodies (31 rows, past StopGraph::kExactRows), sweeps until it alone converges.
// Swept together until both converged, A's impulses came out different from A's alone.
TEST(StopGraph, EachGroupOfBodiesIsSolvedAsItWouldBeAlone) {
  constexpr int kTall = 30;
  static_assert(kTall + 1 > StopGraph::kExactRows);
  PointMasses alone_a({9.0, 1.0});
  alone_a.rest(0, 1, 0, {0, 0, 0}, 0.0, false);
  alone_a.graph.add_stop(2, 1, {0, 0, 0.1}, kUp, 2.0);
  alone_a.graph.solve(alone_a.view(), kH, alone_a.wrenches.data(), alone_a.info.data());
  PointMasses alone_b(std::vector<double>(kTall, 1.0));
  stack(alone_b, 1, kTall, 5, 0);
  alone_b.graph.solve(alone_b.view(), kH, alone_b.wrenches.data(), alone_b.info.data());
  // Both groups, B's rows first, on bodies 1 … 30 (B) and 31, 32 (A).
  std::vector<double> masses(kTall, 1.0);
  masses.push_back(9.0);
  masses.push_back(1.0);
  PointMasses both(masses);
  stack(both, 1, kTall, 5, 0);
  both.info.resize(kTall + 1);
  both.rest(kTall, kTall + 1, 0, {0, 0, 0}, 0.0, false);
  both.graph.add_stop(kTall + 2, kTall + 1, {0, 0, 0.1}, kUp, 2.0);
  both.graph.solve(both.view(), kH, both.wrenches.data(), both.info.data());
  EXPECT_EQ(both.wrenches[kTall + 1].force_N.z, alone_a.wrenches[1].force_N.z);
  EXPECT_EQ(both.wrenches[kTall + 2].force_N.z, alone_a.wrenches[2].force_N.z);
  EXPECT_EQ(both.info[kTall].force_N.z, alone_a.info[0].force_N.z);
  for (int b = 1; b <= kTall; ++b)
    EXPECT_EQ(both.wrenches[static_cast<std::size_t>(b)].force_N.z,
              alone_b.wrenches[static_cast<std::size_t>(b)].force_N.z)
        << "body " << b;
  EXPECT_NEAR(both.dvz(kTall + 2, kH), 2.0, 1e-12) << "group A exactly";
  // Group B by its sweeps: the top body loses much of its 2 m/s, the ground carries some of it.
  EXPECT_GT(both.dvz(kTall, kH), 0.5);
  EXPECT_GT(both.info[0].force_N.z, 0.0);
}

TEST(StopGraph, RestingContactsFarFromAnyStopTakeNoPart) {
  PointMasses p({1.0, 1.0, 1.0});
  p.rest(0, 3, 0, {5, 0, 0}, 0.5, false);  // closing, but unreached
  p.graph.add_stop(1, 0, {0, 0, 0}, kUp, 1.0);
  p.graph.solve(p.view(), kH, p.wrenches.data(), p.info.data());
  EXPECT_EQ(p.wrenches[3].force_N.z, 0.0);
  EXPECT_EQ(p.info[0].force_N.z, 0.0);
}

TEST(StopGraph, AHeldPointClosesNoFurtherUnderTheForcesOfItsStep) {
  // A held point (deeper than the hold depth) closing at 0.1 m/s, its body pushed on by
  // 5 N of contact force and by gravity: after the step it does not close at all.
  PointMasses p({0.5});
  p.falls_m_s2[1] = kGravity_m_s2;
  p.wrenches[1].force_N = {0, 0, -5.0};
  p.rest(0, 1, 0, {0, 0, 0}, 0.1, true);
  p.graph.solve(p.view(), kH, p.wrenches.data(), p.info.data());
  const double closing_after = 0.1 - (p.dvz(1, kH) - kGravity_m_s2 * kH);
  EXPECT_NEAR(closing_after, 0.0, 1e-6);
}

TEST(StopGraph, NeverPulls) {
  // Body 1 already separates faster than its stop asks: no impulse.
  PointMasses p({1.0});
  p.wrenches[1].force_N = {0, 0, 5000.0};  // 5 m/s up in one step
  p.graph.add_stop(1, 0, {0, 0, 0}, kUp, 1.0);
  p.graph.solve(p.view(), kH, p.wrenches.data(), p.info.data());
  EXPECT_EQ(p.wrenches[1].force_N.z, 5000.0);
}

using Runner = test::ContactRunner;

TEST(StopGraph, ABoxLandingOnABoxOnTheGroundStaysWithinTwoMillimetres) {
  // 0.5 kg onto 0.5 kg resting on the ground, from 0.5 m (3.1 m/s): the stop on the lower
  // box is passed on to the ground. Before stops reached resting contacts: 4.45 mm.
  const double size = 0.1;
  scene::Scene s;
  s.bodies.push_back(test::box("below", 0.5, {size, size, size}, {0, 0, size / 2}));
  s.bodies.push_back(test::box("above", 0.5, {size, size, size}, {0.01, 0, 1.5 * size + 0.5}));
  Runner run(s);
  double deepest = 0, highest_after = 0;
  for (int n = 0; n < 1500; ++n) {
    run.step();
    deepest = std::max(deepest, run.deepest_m());
    if (n > 400) highest_after = std::max(highest_after, run.poses[2].position.z);
  }
  RecordProperty("deepest_mm", std::to_string(deepest * 1e3));
  EXPECT_LT(deepest, 2e-3);
  EXPECT_LT(highest_after - 1.5 * size, 2e-3) << "the upper box hops";
  EXPECT_NEAR(run.poses[1].position.z, size / 2, 1e-3);
}

TEST(StopGraph, AHeavyBoxOnALightPlateIsHeldNearTheHoldDepth) {
  // 2 kg on a 100 g plate: the plate's corners meet the ground with the plate's own effective
  // mass, springs of about 2 kN/m each, which carry the 20 N only 4 mm deep (measured with the
  // hold off: 4.06 mm, and still sinking at 3 mm/s after 3 s). Held, 1.2 mm.
  scene::Scene s;
  s.bodies.push_back(test::box("plate", 0.1, {0.3, 0.3, 0.01}, {0, 0, 0.005}));
  s.bodies.push_back(test::box("load", 2, {0.15, 0.15, 0.15}, {0, 0, 0.085}));
  Runner run(s);
  double deepest_late = 0;
  for (int n = 0; n < 3000; ++n) {
    run.step();
    if (n > 1000) deepest_late = std::max(deepest_late, run.deepest_m());
  }
  RecordProperty("deepest_mm", std::to_string(deepest_late * 1e3));
  EXPECT_LT(deepest_late, 1.5e-3);
  EXPECT_LT(std::hypot(run.poses[2].position.x, run.poses[2].position.y), 1e-4) << "drifts";
  EXPECT_LT(norm(run.twists[2].linear_m_s), 1e-3) << "not at rest";
}

TEST(StopGraph, TwentyKilogramsOnAFiftyGramPlateAreHeldNearTheHoldDepthAndShareEvenly) {
  // A mass ratio of 400 through two flush faces. Gauss–Seidel, a few sweeps a step, let the
  // plate's held points close a little at every step: 9.05 mm deep after 3 s, the plate
  // tilted. The small group solved exactly (stop_graph.cpp, solve_group_exactly) holds both
  // layers near the hold depth, the load shared evenly by the four corners of each face.
  scene::Scene s;
  s.bodies.push_back(test::box("plate", 0.05, {0.2, 0.2, 0.01}, {0, 0, 0.005}));
  s.bodies.push_back(test::box("load", 20, {0.2, 0.2, 0.2}, {0, 0, 0.11}));
  Runner run(s);
  double deepest_late = 0;
  for (int n = 0; n < 3000; ++n) {
    run.step();
    if (n > 500) deepest_late = std::max(deepest_late, run.deepest_m());
  }
  RecordProperty("deepest_mm", std::to_string(deepest_late * 1e3));
  EXPECT_LT(deepest_late, 1.5e-3);
  EXPECT_LT(norm(run.twists[2].linear_m_s), 1e-4) << "not at rest";
  EXPECT_LT(std::abs(run.poses[1].rotation.m[2][2] - 1), 1e-6) << "the plate tilts";
  // Each face's four corners: the load's weight (and the plate's) in equal shares.
  int corners_plate = 0, corners_load = 0;
  for (std::int32_t c = 0; c < *run.contacts.contact_count(); ++c) {
    const ContactInfo& k = run.contacts.contacts()[c];
    const bool ground = k.body_b.index == 0;
    const double share = ground ? (20.05 * 9.81) / 4 : (20 * 9.81) / 4;
    EXPECT_NEAR(std::abs(k.force_N.z), share, 0.01 * share) << "contact " << c;
    ++(ground ? corners_plate : corners_load);
  }
  EXPECT_EQ(corners_plate, 4);
  EXPECT_EQ(corners_load, 4);
}

}  // namespace
}  // namespace s2sim::contact
