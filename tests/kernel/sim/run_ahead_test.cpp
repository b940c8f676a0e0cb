// Running ahead (kernel/src/sim/run_ahead.cpp): step(n) lets the parts step stretches of
// ticks each alone, and the results stay the serial run's bit for bit: while the parts are
// apart, when two parts come close (the stretch goes back and runs tick by tick), and when a
// tick inside a stretch fails.
#include <s2sim/error.hpp>
#include <s2sim/kernel/simulation.hpp>

#include "model/island_plan.hpp"
#include "parallel_runs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace s2sim {
namespace {

using namespace parallel_runs;

TEST(RunAhead, SixteenRobotsRunAheadAndGiveTheSerialSignalsBitForBit) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  auto serial = load_driven(kRobots16, 1);
  auto parallel = load_driven(kRobots16, 2);
  const Vec3 start = serial->body_pose(1).position;
  for (int chunk = 0; chunk < 15; ++chunk) {
    for (int tick = 0; tick < 100; ++tick)
      serial->step();
    parallel->step(100);
    ASSERT_EQ(parallel->tick(), serial->tick());
    ASSERT_TRUE(same_bits(signals(*serial), signals(*parallel))) << "after tick " << serial->tick();
  }
  const Vec3 end = serial->body_pose(1).position;
  EXPECT_GT(std::hypot(end.x - start.x, end.y - start.y), 0.02);  // they moved
  // It ran ahead, never lost a stretch (the parts' rows stay 1.5 m apart), and one thread
  // never does.
  const Simulation::RunAheadCounts ahead = parallel->run_ahead_counts();
  EXPECT_GE(ahead.stretches, 15);
  EXPECT_GE(ahead.ticks, 1400);
  EXPECT_EQ(ahead.lost, 0);
  EXPECT_EQ(serial->run_ahead_counts().stretches + serial->run_ahead_counts().lost, 0);
}

TEST(RunAhead, TurnedOffThePartsStepTickByTickWithTheSameResults) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  auto ahead = load_driven(kRobots16, 2);
  SimulationOptions o;
  o.threads = 2;
  o.run_ahead = false;
  auto lockstep = Simulation::load(kRobots16, o);
  each_voltage(*lockstep,
               [&](std::size_t i, const std::string&) { lockstep->set_input(i, ahead->input(i)); });
  ahead->step(300);
  lockstep->step(300);
  EXPECT_TRUE(same_bits(signals(*ahead), signals(*lockstep)));
  EXPECT_GT(ahead->run_ahead_counts().stretches, 0);
  EXPECT_EQ(lockstep->run_ahead_counts().stretches + lockstep->run_ahead_counts().lost, 0);
}

const std::filesystem::path kDiffbot = kRobots16.parent_path() / "diffbot.xml";

TEST(RunAhead, PartsThatComeCloseGoBackAndGiveTheSerialContactsBitForBit) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  // Four robots in a row, r0 r1 | r2 r3 by part; r1 drives ahead into r2, across the parts.
  const auto row = std::filesystem::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/robots_row";
  std::unique_ptr<Simulation> runs[2] = {load_on(row, 1), load_on(row, 2)};
  for (auto& run : runs) {
    run->set_input("robots/r1/axes/left/ref_voltage", -6.0);
    run->set_input("robots/r1/axes/right/ref_voltage", 6.0);
  }
  Simulation &serial = *runs[0], &parallel = *runs[1];
  std::size_t robots_touching = 0;  // contacts between two robots, at the chunks' ends
  for (int chunk = 0; chunk < 60; ++chunk) {
    if (chunk == 45)  // placed between two calls: the next stretch starts from there
      for (auto& run : runs)
        run->place_body(1, Pose{{-0.2, -0.3, 0.08}, Mat3::identity()});
    ASSERT_TRUE(step_and_compare(serial, parallel, 50, [&](const ContactInfo& c) {
      if (c.body_a.index > 0 && c.body_b.index > 0) ++robots_touching;
    }));
  }
  EXPECT_GT(robots_touching, 0u) << "r1 must reach r2";
  const Simulation::RunAheadCounts ahead = parallel.run_ahead_counts();
  EXPECT_GT(ahead.stretches, 0) << "while the parts are apart, they run ahead";
  EXPECT_GT(ahead.lost, 0) << "r1 must come close to r2 within a stretch";
}

TEST(RunAhead, ThingsGoWithTheirNearestRobotsPartSoThatPartsPushingThemRunAhead) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  // Sixteen robots on a grid, each driving into a ball and a box ahead of it. Each thing is
  // dealt to the part of the robot nearest to it at load; all in part 0, they would lie among
  // part 1's robots, the parts' shapes would overlap and no stretch would ever start.
  const auto scene =
      std::filesystem::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/robots_things";
  std::unique_ptr<Simulation> runs[2] = {load_on(scene, 1), load_on(scene, 2)};
  for (auto& run : runs)
    each_voltage(*run, [&](std::size_t i, const std::string& name) {
      run->set_input(i, name.find("/left/") != std::string::npos ? -6.0 : 6.0);
    });
  Simulation &serial = *runs[0], &parallel = *runs[1];
  const scene::Scene& sc = serial.scene();
  const auto plans = model::plan_parts(sc, model::plan_topology(sc), {}, 2);
  ASSERT_EQ(plans.size(), 2u);
  std::vector<int> part_of_body(sc.bodies.size() + 1, -1);
  for (std::size_t p = 0; p < plans.size(); ++p)
    for (int b : plans[p].bodies)
      part_of_body[static_cast<std::size_t>(b)] = static_cast<int>(p);
  // Thing k (ball k, box k) stands ahead of robot k, whose rows y = 0, 1.5 are part 0's.
  std::vector<int> things;
  for (std::size_t b = 0; b < sc.bodies.size(); ++b)
    if (sc.bodies[b].robot < 0) things.push_back(static_cast<int>(b) + 1);
  ASSERT_EQ(things.size(), 32u);
  for (std::size_t k = 0; k < things.size(); ++k)
    EXPECT_EQ(part_of_body[static_cast<std::size_t>(things[k])], k / 2 < 8 ? 0 : 1)
        << sc.bodies[static_cast<std::size_t>(things[k]) - 1].id;

  std::size_t things_pushed = 0;  // contacts between a robot and a thing, at the chunks' ends
  auto robot_and_thing = [&](const ContactInfo& c) {
    auto is_thing = [&](BodyHandle b) {
      return sc.bodies[static_cast<std::size_t>(b.index) - 1].robot < 0;
    };
    if (c.body_a.index > 0 && c.body_b.index > 0 && is_thing(c.body_a) != is_thing(c.body_b))
      ++things_pushed;
  };
  for (int chunk = 0; chunk < 15; ++chunk)
    ASSERT_TRUE(step_and_compare(serial, parallel, 100, robot_and_thing));
  EXPECT_GT(things_pushed, 50u) << "the robots must push their things";
  const Vec3 ball = serial.body_pose(things[0]).position;
  EXPECT_GT(ball.x, 0.3) << "ball0 was pushed from x = 0.2";
  const Simulation::RunAheadCounts ahead = parallel.run_ahead_counts();
  EXPECT_GE(ahead.ticks, 1400);
  EXPECT_EQ(ahead.lost, 0);
  // Each part's things are its own snapshot segments, and a snapshot brings them back.
  const Simulation::Snapshot snapshot = parallel.save();
  EXPECT_EQ(snapshot.find("multibody/part1/loose/position").size, 7u * 16);
  parallel.step(200);
  const std::vector<double> first = signals(parallel);
  parallel.restore(snapshot);
  parallel.step(200);
  EXPECT_TRUE(same_bits(first, signals(parallel)));
}

/// `scene` with the test plugins (the local controller).
std::unique_ptr<Simulation> load_with_test_plugins(const std::filesystem::path& scene,
                                                   int threads) {
  SimulationOptions o;
  o.threads = threads;
  o.plugin_path = {std::filesystem::path(S2SIM_TEST_PLUGIN_DIR) / "scene",
                   std::filesystem::path(S2SIM_PLUGIN_DIR)};
  return Simulation::load(scene, o);
}

TEST(RunAhead, LocalControllersReadTheirPartsLatestContactsAtEveryTickOfAStretch) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  // Each robot's local controller drives its wheels and publishes the vertical contact force
  // on its brick (its caster's), summed from its part's contact list at every tick: inside a
  // stretch, the list of the tick before, as in the serial run.
  std::string plugins;
  for (int r = 0; r < 4; ++r) {
    const std::string robot = "robots/r" + std::to_string(r);
    plugins += "<plugin kind='test_local_controller' id='c" + std::to_string(r) + "' axes='" +
               robot + "/axes/left " + robot + "/axes/right' body='" + robot +
               "/solids/brick' gain='" + std::to_string(0.5 + 0.25 * r) + "' period_ms='1'/>\n";
  }
  const auto scene = row_scene("run_ahead_touch", kDiffbot, "r", 1.5, plugins);
  auto serial = load_with_test_plugins(scene, 1);
  auto parallel = load_with_test_plugins(scene, 2);
  ASSERT_EQ(parallel->components_serial_reason(), "");
  for (int chunk = 0; chunk < 8; ++chunk) {
    for (int tick = 0; tick < 100; ++tick)
      serial->step();
    parallel->step(100);
    ASSERT_TRUE(same_bits(signals(*serial), signals(*parallel))) << "after tick " << serial->tick();
  }
  EXPECT_GT(serial->signal("controllers/c3/touch"), 0.1);  // its caster's share of ~4.7 N
  EXPECT_GT(parallel->run_ahead_counts().stretches, 8);
}

/// Four robots whose local controller on r2 casts a ray from t = 0.05 s on, which a local
/// component may not: the error, the tick the run stopped at and the stretches it lost.
struct Refused {
  std::string error;
  std::int64_t tick = 0, lost = 0;
};
Refused refused_ray(int threads) {
  const auto scene = row_scene("run_ahead_ray", kDiffbot, "r", 1.5,
                               "<plugin kind='test_local_controller' id='c2' "
                               "axes='robots/r2/axes/left robots/r2/axes/right' act='ray'/>\n");
  auto sim = load_with_test_plugins(scene, threads);
  try {
    sim->step(200);
  } catch (const Error& e) {
    return {e.what(), sim->tick(), sim->run_ahead_counts().lost};
  }
  return {"", sim->tick(), sim->run_ahead_counts().lost};
}

TEST(RunAhead, AnErrorInsideAStretchIsThrownAtItsTickWithTheSerialMessage) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  const Refused serial = refused_ray(1);
  EXPECT_NE(serial.error.find("c2"), std::string::npos) << serial.error;
  EXPECT_EQ(serial.tick, 50);
  const Refused parallel = refused_ray(2);
  EXPECT_EQ(parallel.error, serial.error);
  EXPECT_EQ(parallel.tick, serial.tick);
  EXPECT_EQ(parallel.lost, 1) << "the error came inside a stretch, which went back";
}

}  // namespace
}  // namespace s2sim
