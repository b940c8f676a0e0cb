// The façade's state access for embedders and the Python views: the buffers that stay in place
// (signal_values, axis_positions, body_poses), set_axis_state on one part and on several, and
// reset with a new seed.
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <thread>
#include <vector>

namespace s2sim {
namespace {

namespace fs = std::filesystem;

const fs::path kNxt = fs::path(S2SIM_SOURCE_DIR) / "scenes/nxt";
const fs::path kRobots16 = fs::path(S2SIM_SOURCE_DIR) / "bench/peers/scenes/robots_16";
const fs::path kDefault = fs::path(S2SIM_SOURCE_DIR) / "scenes/default";

std::unique_ptr<Simulation> load(const fs::path& scene, int threads = 1) {
  SimulationOptions o;
  o.threads = threads;
  return Simulation::load(scene, o);
}

std::size_t axis_named(const Simulation& sim, const std::string& path) {
  for (std::size_t a = 0; a < sim.axis_count(); ++a)
    if (sim.axis_path(a) == path) return a;
  ADD_FAILURE() << "no axis " << path;
  return 0;
}

std::vector<double> all_signals(const Simulation& sim) {
  std::vector<double> out(sim.signal_count());
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = sim.signal(i);
  return out;
}

TEST(StateAccess, SignalValuesStayInPlaceAndFollowEveryChange) {
  auto sim = load(kNxt);
  const std::vector<double>& values = sim->signal_values();
  const double* where = values.data();
  const std::size_t time = sim->signal_index("time");
  const std::size_t volts = sim->signal_index("robots/nxt/axes/right/ref_voltage");
  sim->set_input("robots/nxt/axes/right/ref_voltage", 6.0);
  EXPECT_EQ(values[volts], 6.0);
  sim->step(50);
  EXPECT_EQ(values[time], sim->time_s());
  EXPECT_EQ(values, all_signals(*sim));
  const auto snapshot = sim->save();
  sim->run_until(0.2);
  EXPECT_EQ(values, all_signals(*sim));
  sim->restore(snapshot);
  EXPECT_EQ(values[time], 0.05);
  const int brick = 1;
  Pose up = sim->body_pose(brick);
  up.position.z += 0.1;
  sim->place_body(brick, up);
  EXPECT_EQ(values, all_signals(*sim));
  sim->reset();
  EXPECT_EQ(values[time], 0.0);
  EXPECT_EQ(values[volts], 0.0);
  EXPECT_EQ(sim->signal_values().data(), where);
  EXPECT_EQ(sim->body_poses().size(), static_cast<std::size_t>(sim->body_count()));
  EXPECT_EQ(sim->body_path(0), "world");
  EXPECT_EQ(sim->body_path(brick), "robots/nxt/solids/brick");
}

TEST(StateAccess, SetAxisStateWritesOneAxisAndStepsOnAlikeOnOneAndTwoParts) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one hardware thread";
  std::unique_ptr<Simulation> runs[2] = {load(kRobots16, 1), load(kRobots16, 2)};
  std::vector<double> signals[2];
  for (int r = 0; r < 2; ++r) {
    Simulation& sim = *runs[r];
    sim.step(20);
    const std::size_t a = axis_named(sim, "robots/r9/axes/right");
    const std::size_t other = axis_named(sim, "robots/r9/axes/left");
    const double other_position = sim.axis_positions()[other];
    sim.set_axis_state(a, 0.7, -1.5);
    EXPECT_EQ(sim.axis_positions()[a], 0.7);
    EXPECT_EQ(sim.axis_velocities()[a], -1.5);
    EXPECT_EQ(sim.axis_positions()[other], other_position);
    EXPECT_EQ(sim.signal("robots/r9/axes/right/pos"), 0.7);
    EXPECT_EQ(sim.time_s(), 0.02);
    sim.step(200);
    signals[r] = all_signals(sim);
  }
  ASSERT_EQ(signals[0].size(), signals[1].size());
  EXPECT_EQ(std::memcmp(signals[0].data(), signals[1].data(), signals[0].size() * sizeof(double)),
            0)
      << "one part and two differ after set_axis_state";
}

TEST(StateAccess, SetAxisStateRefusesBadValuesAndLoopAxesNamingThem) {
  auto sim = load(kNxt);
  try {
    sim->set_axis_state(0, std::numeric_limits<double>::quiet_NaN(), 0);
    ADD_FAILURE() << "a NaN position was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(sim->axis_path(0)), std::string::npos) << e.what();
  }
  EXPECT_THROW(sim->set_axis_state(sim->axis_count(), 0, 0), Error);
  auto loops = load(kDefault);
  int refused = 0;
  for (std::size_t a = 0; a < loops->axis_count(); ++a) {
    try {
      loops->set_axis_state(a, loops->axis_positions()[a], 0.0);
    } catch (const Error& e) {
      ++refused;
      EXPECT_EQ(e.kind(), ErrorKind::usage);
      EXPECT_NE(std::string(e.what()).find("kinematic loop"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(loops->axis_path(a)), std::string::npos) << e.what();
    }
  }
  EXPECT_GT(refused, 0) << "scenes/default has loop-closing joints";
}

TEST(StateAccess, ResetWithASeedKeepsItAndRepeats) {
  auto sim = load(kNxt);
  EXPECT_EQ(sim->seed(), 1u);
  sim->reset(42);
  EXPECT_EQ(sim->seed(), 42u);
  sim->set_input("robots/nxt/axes/right/ref_voltage", 5.0);
  sim->step(300);
  const auto first = all_signals(*sim);
  sim->reset();
  EXPECT_EQ(sim->seed(), 42u);
  sim->set_input("robots/nxt/axes/right/ref_voltage", 5.0);
  sim->step(300);
  EXPECT_EQ(all_signals(*sim), first);
}

}  // namespace
}  // namespace s2sim

namespace s2sim {
namespace {

// The M⁻¹ column cache holds each axis's column over its own robot's speeds: 4 and 16 robots
// keep 4 and 16 times one robot's numbers (over every speed of the scene, 16 robots kept 64
// times as many as 4 robots' quarter would).
TEST(StateAccess, TheColumnCacheGrowsWithTheRobotsNotTheirSquare) {
  const fs::path robots4 = fs::path(S2SIM_SOURCE_DIR) / "bench/peers/scenes/robots_4";
  std::size_t size[2] = {};
  int i = 0;
  for (const fs::path& scene : {robots4, kRobots16}) {
    auto sim = load(scene);
    sim->step(0.01);  // the columns in use
    const auto snapshot = sim->save();
    size[i++] = snapshot.find("multibody/columns").size;
  }
  ASSERT_GT(size[0], 0u);
  EXPECT_EQ(size[1], 4 * size[0]) << "4 robots: " << size[0] << ", 16 robots: " << size[1];
}

}  // namespace
}  // namespace s2sim
