// SDK 0.7 (kernel/src/sim/component_host.cpp, load.cpp): a controller finds every signal and
// input by name — the kernel's, the drive train's — reads any signal in update() and sets an
// existing input; unknown names are plugin errors with suggestions.
#include <s2sim/kernel/simulation.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include "common/temp_dir.hpp"

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kScene = fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/name_reader";

SimulationOptions options() {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_TEST_PLUGIN_DIR) / "scene", fs::path(S2SIM_PLUGIN_DIR)};
  return o;
}

TEST(ComponentNames, AControllerSeesTheDriveTrainsNamesReadsAnySignalAndSetsAnInput) {
  auto sim = Simulation::load(kScene, options());
  const std::string p = "controllers/reader/";
  // Every signal of the axis, the drive train's (current, voltage...) included.
  EXPECT_EQ(sim->signal(p + "matched"),
            static_cast<double>(sim->match_signals("robots/bench/axes/motor/*").size()));
  EXPECT_GT(sim->signal(p + "matched"), 10.0);
  EXPECT_GE(sim->signal(p + "matched_inputs"), 5.0);  // ref_torque, ref_voltage, ref_speed...
  sim->step(41);                                      // the controller runs at ticks 0 and 40
  EXPECT_DOUBLE_EQ(sim->signal(p + "time_read"), 40 * sim->tick_s());
  EXPECT_DOUBLE_EQ(sim->input(sim->input_index("robots/bench/axes/motor/ref_voltage")), 3.0);
  // The speed it read is the one at the start of tick 40: replay to there and compare.
  auto again = Simulation::load(kScene, options());
  again->step(40);
  EXPECT_DOUBLE_EQ(sim->signal(p + "value_read"), again->signal("robots/bench/axes/motor/speed"));
  EXPECT_GT(sim->signal(p + "value_read"), 0.0);  // 3 V turn the motor
}

/// The fixture with `from` replaced by `to`, in a folder of its own (the robot by absolute path).
fs::path variant(const std::string& from, const std::string& to) {
  std::ifstream in(kScene / "scene.xml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string robot = "../../../../../scenes/motor_bench/nxt_motor.xml";
  text.replace(text.find(robot), robot.size(),
               (fs::path(S2SIM_SOURCE_DIR) / "scenes/motor_bench/nxt_motor.xml").string());
  text.replace(text.find(from), from.size(), to);
  const fs::path dir = s2sim::test::process_temp_dir() / ("s2sim_names_" + to.substr(0, 4));
  fs::create_directories(dir);
  std::ofstream(dir / "scene.xml") << text;
  return dir;
}

TEST(ComponentNames, UnknownNamesArePluginErrorsWithSuggestions) {
  const std::pair<std::string, std::string> cases[] = {
      {"input='robots/bench/axes/motor/ref_voltage'", "input='robots/bench/axes/motor/ref_voltag'"},
      {"read='robots/bench/axes/motor/speed'", "read='robots/bench/axes/motor/sped'"}};
  for (const auto& [from, to] : cases) {
    try {
      Simulation::load(variant(from, to), options());
      ADD_FAILURE() << to << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::plugin) << e.what();
      EXPECT_THAT(e.message(),
                  HasSubstr(to.substr(to.find('\'') + 1, to.size() - to.find('\'') - 2)));
      EXPECT_THAT(e.message(), HasSubstr("did you mean"));
    }
  }
}

}  // namespace
}  // namespace s2sim
