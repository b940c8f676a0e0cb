// Calls into components are guarded (kernel/src/sim/component_host.cpp): whatever a plugin
// throws, from configure() or update(), the simulation reports a kernel-owned s2sim::Error
// naming the component, its kind and its plugin; ../shared/repro R07 and R08.
#include <s2sim/kernel/simulation.hpp>

#include "common/edited_copy.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kScene = fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/hostile";

/// Loads the hostile scene in `mode` and steps it 100 ticks; returns the error (copied: by the
/// time it is read the plugin's library is unloaded, which is what crashed before).
Error error_in(const std::string& mode) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_TEST_PLUGIN_DIR) / "hostile"};
  const fs::path scene = test::edited_copy(kScene, "scene.xml", "MODE", mode);
  try {
    auto sim = Simulation::load(scene, o);
    sim->step(100);  // controllers run every 40 ms: ticks 0, 40, 80
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << mode << ": nothing was thrown";
  return Error(ErrorKind::usage, "none");
}

TEST(ComponentHost, AnSdkErrorThrownFromConfigureSurvivesItsPluginAndNamesIt) {
  const Error e = error_in("configure_error");
  EXPECT_EQ(e.kind(), ErrorKind::scene);  // the plugin's own kind
  EXPECT_THAT(e.message(), HasSubstr("controllers/villain (kind 'test_hostile')"));
  EXPECT_THAT(e.message(), HasSubstr("libs2sim_test_hostile_plugin.so, configure: hostile: the "
                                     "parameter 'mode' is not to my liking"));
  EXPECT_EQ(e.where().file, "scene.xml");
  EXPECT_THAT(std::string(e.what()), HasSubstr("scene.xml"));
}

TEST(ComponentHost, NonStandardAndStandardExceptionsFromConfigureArePluginErrors) {
  const Error i = error_in("configure_int");
  EXPECT_EQ(i.kind(), ErrorKind::plugin);
  EXPECT_THAT(i.message(), HasSubstr("configure: threw something that is not an exception"));
  const Error s = error_in("configure_std");
  EXPECT_EQ(s.kind(), ErrorKind::plugin);
  EXPECT_THAT(s.message(), HasSubstr("configure: hostile: a std::runtime_error"));
}

TEST(ComponentHost, ExceptionsFromUpdateNameTheComponentAndAreRuntimeErrors) {
  const Error e = error_in("update_error");
  EXPECT_EQ(e.kind(), ErrorKind::runtime);
  EXPECT_THAT(e.message(), HasSubstr("controllers/villain (kind 'test_hostile') from "));
  EXPECT_THAT(e.message(), HasSubstr("update: hostile: failed in update"));
  for (const char* mode : {"update_std", "update_int"}) {
    const Error x = error_in(mode);
    EXPECT_EQ(x.kind(), ErrorKind::runtime) << mode;
    EXPECT_THAT(x.message(), HasSubstr("controllers/villain (kind 'test_hostile')")) << mode;
  }
}

// A handle that was never looked up (or is out of range) is refused by the StepContext
// accessor, as an error of the component that used it, rather than read out of bounds.
TEST(ComponentHost, AnInvalidHandleInUpdateIsARuntimeErrorNamingTheComponentAndTheAccessor) {
  const std::vector<std::pair<const char*, const char*>> cases = {
      {"unset_body", "StepContext::apply_force: invalid body handle (index -1, valid 0 to "},
      {"unset_axis", "StepContext::apply_axis_force: invalid axis handle (index -1"},
      {"unset_input", "StepContext::set_input: invalid input handle (index -1"},
      {"unset_state", "StepContext::state: invalid state handle (index -1"},
      {"far_body", "StepContext::body_pose: invalid body handle (index 1073741824, valid 0 to "},
  };
  for (const auto& [mode, what] : cases) {
    const Error e = error_in(mode);
    EXPECT_EQ(e.kind(), ErrorKind::runtime) << mode;
    EXPECT_THAT(e.message(), HasSubstr("controllers/villain (kind 'test_hostile')")) << mode;
    EXPECT_THAT(e.message(), HasSubstr(what)) << mode;
  }
}

// ../shared/repro R08 (NaN force): a component's NaN load surfaced as a divergence blamed on
// the body, or as exit 1. It is refused before the physics, naming the body it was applied to.
TEST(ComponentHost, ANonFiniteLoadFromAComponentIsARuntimeErrorNamingTheBody) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_TEST_PLUGIN_DIR) / "hostile"};
  auto sim =
      Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/hostile_body", o);
  try {
    sim->step(100);
    FAIL() << "the NaN torque went unnoticed";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::runtime);
    EXPECT_THAT(e.message(), HasSubstr("a component applied a non-finite force or torque on body "
                                       "'box' (a thing)"));
  }
  for (int b = 0; b < sim->body_count(); ++b)  // the state itself never took the NaN
    EXPECT_TRUE(std::isfinite(sim->body_pose(b).position.z));
}

}  // namespace
}  // namespace s2sim
