// The tick pipeline (kernel/src/sim/step.cpp): its stages, their order and their timing, and
// what a tick that diverges reports.
#include <s2sim/kernel/simulation.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

SimulationOptions plugins() {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  return o;
}

// Every stage runs in every tick (the physics ones once per substep) and the profile says so;
// turning it off empties it, turning it on again starts from zero.
TEST(Step, ProfileCountsEveryStageOfThePipeline) {
  SimulationOptions o = plugins();
  o.substeps = 2;
  auto sim = Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "scenes/nxt", o);
  EXPECT_TRUE(sim->stage_times().empty());
  sim->set_profiling(true);
  sim->step(10);
  const auto stages = sim->stage_times();
  std::vector<std::string> names;
  for (const auto& s : stages) {
    names.push_back(s.stage);
    EXPECT_GE(s.seconds, 0.0) << s.stage;
  }
  EXPECT_THAT(names, ::testing::ElementsAre("sense", "control", "motor control", "actuate",
                                            "collide", "prepare axes", "accelerations", "kick",
                                            "axes", "drift", "project", "finish", "read out"));
  // Each stage timed once where it runs: once per tick, or once per substep.
  for (const auto& s : stages) {
    const bool per_substep = s.stage != "sense" && s.stage != "control" &&
                             s.stage != "motor control" && s.stage != "actuate" &&
                             s.stage != "finish" && s.stage != "read out";
    EXPECT_EQ(s.calls, per_substep ? 20 : 10) << s.stage;
  }
  sim->set_profiling(false);
  EXPECT_TRUE(sim->stage_times().empty());
  sim->set_profiling(true);
  sim->step(1);
  EXPECT_EQ(sim->stage_times().front().calls, 1);
}

// ../shared/repro R02: a blow-up inside Simbody ended as "internal error" (exit 1) with no word
// of where. It is a runtime error (exit 5) naming the time and the first body that diverged.
TEST(Step, DivergenceIsARuntimeErrorNamingTheBodyAndTheTime) {
  auto sim = Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/stiff_spring",
                              plugins());
  try {
    sim->run_until(1.0);
    FAIL() << "a 1e12 N·m/rad spring on a 1 kg bob at 1 ms did not diverge";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::runtime);
    EXPECT_EQ(exit_code(e.kind()), 5);
    EXPECT_THAT(e.message(), HasSubstr("at t = "));
    EXPECT_THAT(e.message(), HasSubstr("body 'bob' of robot 'pendulum'"));
    EXPECT_THAT(e.message(), HasSubstr("; its last finite state, at t = "));
    EXPECT_THAT(e.message(), HasSubstr(" m, velocity ("));
  }
}

}  // namespace
}  // namespace s2sim
