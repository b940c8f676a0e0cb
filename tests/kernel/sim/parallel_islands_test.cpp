// The scene's islands stepped as parts on several threads give the serial run's
// numbers bit for bit (signals, snapshots, errors), and the parts are whole islands.
#include <s2sim/error.hpp>
#include <s2sim/kernel/simulation.hpp>

#include "model/island_plan.hpp"
#include "parallel_runs.hpp"
#include "scene_builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace s2sim {
namespace {

using namespace parallel_runs;

TEST(ParallelIslands, SixteenRobotsGiveTheSerialSignalsBitForBitOnTwoThreads) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  auto serial = load_driven(kRobots16, 1);
  auto parallel = load_driven(kRobots16, 2);
  ASSERT_EQ(serial->signal_count(), parallel->signal_count());
  ASSERT_GT(serial->signal_count(), 100u);
  const Vec3 start = serial->body_pose(1).position;
  for (int tick = 0; tick < 1500; ++tick) {
    serial->step();
    parallel->step();
    ASSERT_TRUE(same_bits(signals(*serial), signals(*parallel))) << "tick " << tick;
  }
  // They moved: the check above compared motion, not rest.
  const Vec3 end = serial->body_pose(1).position;
  EXPECT_GT(std::hypot(end.x - start.x, end.y - start.y), 0.02);  // 56 mm in 1.5 s
  EXPECT_GT(serial->kinetic_energy_J(), 0.0);
  EXPECT_NEAR(parallel->kinetic_energy_J(), serial->kinetic_energy_J(),
              1e-12 * serial->kinetic_energy_J());
}

TEST(ParallelIslands, SixtyFourRobotsMostlyHeldByFrictionGiveTheSerialSignalsBitForBit) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  // Two robots driven, 62 held by their motors' Coulomb friction: the friction sweeps of the
  // axis solve once ran until every tree of the system converged, so a part's robots took
  // other sweep counts than in the whole system (last digits from tick 252 on).
  const auto robots64 = std::filesystem::path(S2SIM_SOURCE_DIR) / "bench/peers/scenes/robots_64";
  std::unique_ptr<Simulation> runs[2] = {load_on(robots64, 1), load_on(robots64, 2)};
  for (auto& sim : runs) {
    sim->set_input("robots/r3/axes/left/ref_voltage", 5.0);
    sim->set_input("robots/r40/axes/right/ref_voltage", -4.0);
  }
  for (int tick = 0; tick < 600; ++tick) {
    runs[0]->step();
    runs[1]->step();
    ASSERT_TRUE(same_bits(signals(*runs[0]), signals(*runs[1]))) << "tick " << tick;
  }
}

TEST(ParallelIslands, OneTreesSweepsOverFrictionAndBoundsLeaveTheOtherPartsBitForBit) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  // r0 (part 0) starts at 9 V, the others at 4.5 V. The axis solve once swept every tree of
  // the system over its bounds and friction when any one tree needed it, so the other part's
  // robots took other last bits alone than beside r0 (from tick 2 on).
  // Four robots in a row (on the peers' 2 x 2 grid the last bits happened to agree).
  const auto row =
      row_scene("parallel_islands_row", kRobots16.parent_path() / "diffbot.xml", "r", 1.5);
  std::unique_ptr<Simulation> runs[2] = {load_on(row, 1), load_on(row, 2)};
  for (auto& sim : runs)
    for (std::size_t i = 0; i < sim->input_count(); ++i) {
      const std::string& name = sim->input_info(i).name;
      if (name.size() > 12 && name.compare(name.size() - 12, 12, "/ref_voltage") == 0)
        sim->set_input(i, name.rfind("robots/r0/", 0) == 0 ? 9.0 : 4.5);
    }
  for (int tick = 0; tick < 300; ++tick) {
    runs[0]->step();
    runs[1]->step();
    ASSERT_TRUE(same_bits(signals(*runs[0]), signals(*runs[1]))) << "tick " << tick;
  }
}

TEST(ParallelIslands, HumanoidsBrakedAtEveryJointGiveTheSerialSignalsBitForBit) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  // Four humanoids in a row, each standing on 20 hinges held by Coulomb friction, their
  // shoulders driven at different voltages: every tree's friction and bounds are solved in
  // their modes (kernel/src/model/axis_modes.cpp) on its own part's thread.
  const auto row = row_scene(
      "parallel_islands_humanoids",
      std::filesystem::path(S2SIM_SOURCE_DIR) / "bench/peers/scenes/humanoid/robot.xml", "h", 2.0);
  std::unique_ptr<Simulation> runs[2] = {load_on(row, 1), load_on(row, 2)};
  for (auto& sim : runs)
    for (int r = 0; r < 4; ++r)
      for (const char* side : {"l", "r"})
        sim->set_input(
            "robots/h" + std::to_string(r) + "/axes/shoulder_pitch_" + side + "/ref_voltage",
            1.0 + 1.5 * r);
  for (int tick = 0; tick < 400; ++tick) {
    runs[0]->step();
    runs[1]->step();
    ASSERT_TRUE(same_bits(signals(*runs[0]), signals(*runs[1]))) << "tick " << tick;
  }
  // The arms swung: the check above compared motion, not rest.
  EXPECT_GT(std::abs(runs[0]->signal("robots/h3/axes/shoulder_pitch_l/speed")), 0.01);
}

TEST(ParallelIslands, MechanismsOfEveryTreeJointKindGiveTheSerialSignalsBitForBit) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  // A gimbal (universal joints), pendulums and a cart-pole in two parts. When the fast path
  // refused universal joints, the serial system went to Simbody's dynamics while the part
  // without the gimbal took the fast path, equal only to rounding (the pendulum's speed 1 ulp
  // apart from the first tick); a system one of whose trees the fast path refuses still takes
  // Simbody's dynamics in every part (MultibodyIslands). Now every part takes the fast path.
  const auto scene =
      std::filesystem::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/mechanisms_without_loop";
  std::unique_ptr<Simulation> runs[2] = {load_on(scene, 1), load_on(scene, 2)};
  for (int tick = 0; tick < 300; ++tick) {
    runs[0]->step();
    runs[1]->step();
    ASSERT_TRUE(same_bits(signals(*runs[0]), signals(*runs[1]))) << "tick " << tick;
  }
  EXPECT_GT(std::abs(runs[0]->signal("robots/pendulum/axes/swing/speed")), 0.01);  // it swings
}

TEST(ParallelIslands, RobotsWithBallJointsAreDealtToPartsAndGiveTheSerialSignalsBitForBit) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  // Four robots, each with a mast on a Ball joint; r1 and r2 drive into each other across the
  // parts. A Ball joint anywhere once kept the scene in one part (Simbody's quaternion rates).
  const auto scene =
      std::filesystem::path(S2SIM_SOURCE_DIR) / "tests/fuzz/seeds/parallel/robots_with_ball_masts";
  std::unique_ptr<Simulation> runs[2] = {load_on(scene, 1), load_on(scene, 2)};
  const scene::Scene& sc = runs[1]->scene();
  EXPECT_EQ(model::plan_parts(sc, model::plan_topology(sc), {}, 2).size(), 2u);
  for (auto& run : runs)
    for (const char* robot : {"r1", "r2"}) {
      run->set_input(std::string("robots/") + robot + "/axes/left/ref_voltage", -6.0);
      run->set_input(std::string("robots/") + robot + "/axes/right/ref_voltage", 6.0);
    }
  for (int chunk = 0; chunk < 12; ++chunk) {
    for (int tick = 0; tick < 50; ++tick)
      runs[0]->step();
    runs[1]->step(50);
    ASSERT_TRUE(same_bits(signals(*runs[0]), signals(*runs[1])))
        << "after tick " << runs[0]->tick();
  }
  EXPECT_GT(runs[1]->run_ahead_counts().stretches, 0);
  // The masts swing on their quaternions: the brick's and the mast's orientations part.
  int mast = -1;
  for (std::size_t b = 0; b < sc.bodies.size(); ++b)
    if (sc.bodies[b].id == "mast" && sc.bodies[b].robot >= 0 &&
        sc.robots[static_cast<std::size_t>(sc.bodies[b].robot)].id == "r1")
      mast = static_cast<int>(b) + 1;
  ASSERT_GT(mast, 0);
  EXPECT_LT(runs[0]->body_pose(mast).rotation.m[2][2], 0.9999);  // tilted from upright
}

TEST(ParallelIslands, ASnapshotOfTheParallelRunReplaysItBitForBit) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  auto sim = load_driven(kRobots16, 2);
  sim->step(300);
  const Simulation::Snapshot snapshot = sim->save();
  sim->step(300);
  const std::vector<double> first = signals(*sim);
  sim->restore(snapshot);
  sim->step(300);
  EXPECT_TRUE(same_bits(first, signals(*sim)));
  // Its layout has a segment per part: a serial run's snapshot is refused, naming it.
  auto serial = load_driven(kRobots16, 1);
  EXPECT_THROW(serial->restore(snapshot), Error);
}

// Robots driven into each other, into a wall (FCL's box–box), into loose boxes and a ball, and
// a robot of part 0 into a plank of part 1 (a loose body goes with its nearest robot's part):
// every signal and every contact (bodies, point, normal, force, depth, in order) equal the
// serial run's, also after a robot is placed elsewhere between two ticks.
TEST(ParallelIslands, RobotsMeetingAcrossThePartsGiveTheSerialContactsBitForBit) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  std::unique_ptr<Simulation> runs[2] = {load_meeting(1), load_meeting(2)};
  // Which part integrates each body, as MultibodyIslands deals them.
  const scene::Scene& plan_scene = runs[1]->scene();
  const auto parts = model::plan_parts(plan_scene, model::plan_topology(plan_scene), {}, 2);
  ASSERT_EQ(parts.size(), 2u);
  std::vector<int> part_of_body(plan_scene.bodies.size() + 1, 0);
  for (std::size_t p = 0; p < parts.size(); ++p)
    for (int b : parts[p].bodies)
      part_of_body[static_cast<std::size_t>(b)] = static_cast<int>(p);
  std::size_t body_pairs = 0, across_parts = 0;
  const int ticks = 2500;
  for (int tick = 0; tick < ticks; ++tick) {
    if (tick == 1500)
      for (auto& run : runs)
        run->place_body(1, Pose{{0.1, -0.3, 0.08}, Mat3::identity()});
    runs[0]->step();
    runs[1]->step();
    ASSERT_TRUE(same_bits(signals(*runs[0]), signals(*runs[1]))) << "tick " << tick;
    ASSERT_EQ(runs[0]->contact_count(), runs[1]->contact_count()) << "tick " << tick;
    for (std::size_t c = 0; c < runs[0]->contact_count(); ++c) {
      ASSERT_TRUE(same_contact(*runs[0], *runs[1], c)) << "tick " << tick << ", contact " << c;
      const ContactInfo& a = runs[0]->contact(c);
      if (a.body_a.index > 0 && a.body_b.index > 0) {
        ++body_pairs;
        if (part_of_body[static_cast<std::size_t>(a.body_a.index)] !=
            part_of_body[static_cast<std::size_t>(a.body_b.index)])
          ++across_parts;
      }
    }
  }
  EXPECT_GT(body_pairs, 100u) << "the robots must meet each other, the things and the wall";
  EXPECT_GT(across_parts, 10u) << "a part's robot must push the other part's plank";
}

/// The error of a run whose robots in `blown` get an absurd torque (empty: none thrown).
std::string divergence(int threads, const std::vector<std::string>& blown) {
  auto sim = load_on(kRobots16, threads);
  for (const auto& robot : blown)
    sim->set_input("robots/" + robot + "/axes/left/ref_torque", 1e8);  // the largest it takes
  try {
    sim->step(10);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::runtime);
    return e.message();
  }
  return {};
}

TEST(ParallelIslands, ADivergenceInAnyPartIsReportedAsTheSerialRunReportsIt) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  // Robots r0–r7 are dealt to part 0, r8–r15 to part 1 (equal islands in kernel order).
  for (const std::vector<std::string>& blown :
       {std::vector<std::string>{"r9"}, {"r4", "r9"}, {"r9", "r4", "r12"}}) {
    const std::string serial = divergence(1, blown);
    ASSERT_FALSE(serial.empty());
    EXPECT_EQ(divergence(2, blown), serial);
  }
  EXPECT_NE(divergence(2, {"r9", "r4"}).find("robot 'r4'"), std::string::npos);
}

TEST(ParallelIslands, ThreadCountsOutsideTheMachinesAreAUsageError) {
  SimulationOptions o;
  o.threads = 0;
  try {
    Simulation::load(kRobots16, o);
    FAIL() << "threads = 0 was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::usage);
    EXPECT_NE(e.message().find("got 0"), std::string::npos) << e.message();
  }
  o.threads = static_cast<int>(std::thread::hardware_concurrency()) + 1;
  EXPECT_THROW(Simulation::load(kRobots16, o), Error);
}

TEST(ParallelIslands, IslandsAreDealtWholeAndBalanced) {
  auto sim = Simulation::load(kRobots16);
  const scene::Scene& scene = sim->scene();
  const model::Topology topology = model::plan_topology(scene);
  const auto parts = model::plan_parts(scene, topology, {}, 2);
  ASSERT_EQ(parts.size(), 2u);
  std::size_t bodies = 0, axes = 0, edges = 0;
  for (const auto& part : parts) {
    bodies += part.bodies.size();
    axes += part.global_axis.size();
    edges += part.topology.tree.size();
    // Whole robots: every body of a robot in the same part as its first body.
    for (int b : part.bodies) {
      const int robot = scene.bodies[static_cast<std::size_t>(b - 1)].robot;
      for (const auto& other : parts) {
        if (&other == &part) continue;
        for (int o : other.bodies)
          EXPECT_NE(scene.bodies[static_cast<std::size_t>(o - 1)].robot, robot);
      }
    }
  }
  EXPECT_EQ(bodies, scene.bodies.size());
  EXPECT_EQ(axes, topology.axes.size());
  EXPECT_EQ(edges, topology.tree.size());
  EXPECT_EQ(parts[0].bodies.size(), parts[1].bodies.size());  // 8 robots each
  // Equal islands in kernel order cut in halves: robot k's bodies in part k / 8, so that each
  // part's bodies lie together in the scene-wide arrays.
  for (std::size_t p = 0; p < 2; ++p)
    for (int b : parts[p].bodies) {
      const int robot = scene.bodies[static_cast<std::size_t>(b - 1)].robot;
      EXPECT_EQ(scene.robots[static_cast<std::size_t>(robot)].id.substr(1), std::to_string(robot));
      EXPECT_EQ(static_cast<std::size_t>(robot) / 8, p) << "body " << b;
    }
  // One part for one thread, and for a scene of one island.
  EXPECT_EQ(model::plan_parts(scene, topology, {}, 1).size(), 1u);
  auto one = Simulation::load(std::filesystem::path(S2SIM_SOURCE_DIR) / "scenes/nxt");
  EXPECT_EQ(model::plan_parts(one->scene(), model::plan_topology(one->scene()), {}, 2).size(), 1u);
}

// Islands in kernel order cut into runs when that is as balanced as the greedy deal, else the
// greedy deal: chains of 1, 3 and 1 hinged links (weights 2, 6, 2: bodies + axes) cut in runs
// would give 2 | 8, so the long chain gets a part of its own; four equal chains go 2 | 2.
TEST(ParallelIslands, IslandsAreCutInRunsOnlyWhenThatIsAsBalanced) {
  auto chains = [](const std::vector<int>& lengths) {
    scene::Scene s;
    double x = 0;
    for (const int length : lengths) {
      for (int k = 0; k < length; ++k) {
        const int body = static_cast<int>(s.bodies.size());
        s.bodies.push_back(
            test::box("b" + std::to_string(body), 1, {0.1, 0.1, 0.1}, {x, 0, 0.5 - 0.2 * k}));
        s.joints.push_back(test::joint("j" + std::to_string(body), scene::JointType::hinge,
                                       k == 0 ? -1 : body - 1, body, {x, 0, 0.6 - 0.2 * k},
                                       {1, 0, 0}));
      }
      x += 1;
    }
    return s;
  };
  auto part_of_first_bodies = [](const scene::Scene& s, std::vector<int> firsts) {
    const auto parts = model::plan_parts(s, model::plan_topology(s), {}, 2);
    std::vector<int> out;
    for (const int b : firsts)
      for (std::size_t p = 0; p < parts.size(); ++p)
        if (std::find(parts[p].bodies.begin(), parts[p].bodies.end(), b + 1) !=
            parts[p].bodies.end())
          out.push_back(static_cast<int>(p));
    return out;
  };
  EXPECT_EQ(part_of_first_bodies(chains({1, 3, 1}), {0, 1, 4}), (std::vector<int>{1, 0, 1}));
  EXPECT_EQ(part_of_first_bodies(chains({1, 1, 1, 1}), {0, 1, 2, 3}),
            (std::vector<int>{0, 0, 1, 1}));
}

}  // namespace
}  // namespace s2sim
