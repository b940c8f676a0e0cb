// The façade: components loaded from a scene by kind, the tick order, inputs and signals,
// determinism, snapshots and located errors.
#include <s2sim/kernel/simulation.hpp>

#include <gmock/gmock.h>
#include "common/edited_copy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kFixture = fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/components";

SimulationOptions test_options(std::uint64_t seed = 1) {
  SimulationOptions o;
  o.seed = seed;
  // The test plugins, and the first-party drive train that every axis needs.
  o.plugin_path = {fs::path(S2SIM_TEST_PLUGIN_DIR) / "scene", fs::path(S2SIM_PLUGIN_DIR)};
  return o;
}

std::unique_ptr<Simulation> load_fixture(std::uint64_t seed = 1) {
  return Simulation::load(kFixture, test_options(seed));
}

/// A copy of the fixture with one file's text replaced, for error cases.
fs::path fixture_with(const std::string& file, const std::string& from, const std::string& to) {
  return test::edited_copy(kFixture, file, from, to);
}

TEST(Simulation, LoadsThirdPartyComponentsByKindWithTheirSignals) {
  auto sim = load_fixture();
  for (const char* name :
       {"robots/pend/actuators/spring/torque", "controllers/ctl/updates", "actuators/act_echo/seen",
        "sensors/sense_echo/seen", "sensors/noise/value", "robots/pend/axes/J/pos",
        "robots/pend/axes/J/speed", "robots/pend/axes/J/torque", "robots/pend/axes/J/ref_torque",
        "robots/pend/solids/bob/z", "robots/pend/x", "things/box/z", "ref/value", "time"})
    EXPECT_TRUE(sim->find_signal(name)) << name;
  EXPECT_EQ(sim->signal_info(sim->signal_index("robots/pend/axes/J/pos")).unit, "rad");
  EXPECT_EQ(sim->signal_info(sim->signal_index("robots/pend/actuators/spring/torque")).unit, "N*m");
  EXPECT_EQ(sim->signal_info(sim->signal_index("things/box/vz")).unit, "m/s");
}

TEST(Simulation, StagesRunInOrderSensorsControllersActuatorsThenPhysics) {
  auto sim = load_fixture();
  const auto ctl = sim->signal_index("controllers/ctl/updates");
  const auto act = sim->signal_index("actuators/act_echo/seen");
  const auto sense = sim->signal_index("sensors/sense_echo/seen");
  sim->step(10);  // ticks 0..9: the controller's phase is 10 ms
  EXPECT_EQ(sim->signal(ctl), 0.0);
  sim->step(1);  // tick 10: the controller sets 1.5 after the sensor sampled, before the actuator
  EXPECT_EQ(sim->signal(ctl), 1.0);
  EXPECT_EQ(sim->signal(act), 1.5);
  EXPECT_EQ(sim->signal(sense), 0.0);
  sim->step(1);
  EXPECT_EQ(sim->signal(sense), 1.5);
}

TEST(Simulation, PeriodAndPhaseLiveOnTheTickGrid) {
  auto sim = load_fixture();
  sim->run_until(1.0);  // ticks 0..999; updates at 10, 50, ..., 970
  EXPECT_EQ(sim->tick(), 1000);
  EXPECT_EQ(sim->signal("controllers/ctl/updates"), 25.0);
  EXPECT_EQ(sim->signal("ref/value"), 25 * 1.5);
}

TEST(Simulation, ActuatorTorqueAndHeldInputReachTheAxis) {
  auto sim = load_fixture();
  const auto pos = sim->signal_index("robots/pend/axes/J/pos");
  const auto spring = sim->signal_index("robots/pend/actuators/spring/torque");
  const auto applied = sim->signal_index("robots/pend/axes/J/torque");
  sim->set_input("robots/pend/axes/J/ref_torque", 0.25);
  for (int n = 0; n < 200; ++n) {
    const double q = sim->signal(pos);  // the spring sees this position in the coming tick
    sim->step();
    EXPECT_DOUBLE_EQ(sim->signal(spring), -2.0 * (q - 10 * kPi / 180));
    EXPECT_DOUBLE_EQ(sim->signal(applied), sim->signal(spring) + 0.25);
  }
  EXPECT_GT(std::abs(sim->signal(pos)), 0.05);
}

TEST(Simulation, BodyComponentHoldsAThingAgainstGravity) {
  auto sim = load_fixture();
  sim->run_until(1.0);
  EXPECT_NEAR(sim->signal("things/box/z"), 1.0, 1e-9);
  EXPECT_NEAR(sim->signal("robots/pend/solids/bob/z"), sim->signal("robots/pend/z"), 0.0);
}

TEST(Simulation, RandomStreamsFollowTheSeed) {
  auto a = load_fixture(7), b = load_fixture(7), c = load_fixture(8);
  const auto noise = a->signal_index("sensors/noise/value");
  std::vector<double> first;
  double sum = 0, sum2 = 0, differ = 0;
  const int n = 10000;
  for (int i = 0; i < n; ++i) {
    a->step();
    b->step();
    c->step();
    const double v = a->signal(noise);
    first.push_back(v);
    EXPECT_EQ(v, b->signal(noise));
    differ += v != c->signal(noise);
    sum += v;
    sum2 += v * v;
  }
  EXPECT_GT(differ, n - 10);
  const double stdev = std::sqrt(sum2 / n - (sum / n) * (sum / n));
  EXPECT_NEAR(stdev, 0.5, 0.5 * 0.03);
  a->reset();
  for (int i = 0; i < 100; ++i) {
    a->step();
    EXPECT_EQ(a->signal(noise), first[i]) << i;
  }
}

TEST(Simulation, SnapshotRestoresEverythingBitForBit) {
  auto sim = load_fixture();
  sim->set_input("robots/pend/axes/J/ref_torque", 0.1);
  sim->step(333);
  const auto snapshot = sim->save();
  sim->step(500);
  std::vector<double> expected;
  for (std::size_t i = 0; i < sim->signal_count(); ++i)
    expected.push_back(sim->signal(i));
  sim->restore(snapshot);
  EXPECT_EQ(sim->tick(), 333);
  sim->step(500);
  for (std::size_t i = 0; i < sim->signal_count(); ++i)
    EXPECT_EQ(sim->signal(i), expected[i]) << sim->signal_info(i).name;
}

TEST(Simulation, ResetRepeatsTheRunBitForBit) {
  auto sim = load_fixture();
  sim->set_input("robots/pend/axes/J/ref_torque", 0.3);
  sim->step(700);
  const double pos = sim->signal("robots/pend/axes/J/pos");
  sim->reset();
  EXPECT_EQ(sim->time_s(), 0.0);
  EXPECT_EQ(sim->input(sim->input_index("robots/pend/axes/J/ref_torque")), 0.0);
  sim->set_input("robots/pend/axes/J/ref_torque", 0.3);
  sim->step(700);
  EXPECT_EQ(sim->signal("robots/pend/axes/J/pos"), pos);
}

TEST(Simulation, UnknownNamesSuggestCloseOnes) {
  auto sim = load_fixture();
  try {
    (void)sim->signal_index("robots/pend/axes/J/pso");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::usage);
    EXPECT_THAT(e.what(), HasSubstr("did you mean 'robots/pend/axes/J/pos'"));
  }
  EXPECT_THROW(sim->set_input("robots/pend/axes/J/ref_torqe", 1), Error);
  EXPECT_THROW(sim->set_input("robots/pend/axes/J/ref_torque", NAN), Error);
  EXPECT_EQ(sim->match_signals("robots/pend/axes/*/pos").size(), 1u);
}

Error load_error(const fs::path& scene) {
  try {
    Simulation::load(scene, test_options());
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "loading " << scene << " did not fail";
  return Error(ErrorKind::runtime, "none");
}

TEST(Simulation, ComponentParameterErrorsNameFileElementAndAttribute) {
  const Error e = load_error(fixture_with("pendulum.xml", "stiffness='2 * L'", "stiffness='-L'"));
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_THAT(e.what(), HasSubstr("pendulum.xml"));
  EXPECT_THAT(e.what(), HasSubstr("plugin"));
  EXPECT_THAT(e.what(), HasSubstr("stiffness"));
  EXPECT_THAT(e.what(), HasSubstr("-1"));
}

TEST(Simulation, ComponentLookupAndScheduleErrorsNameTheComponent) {
  Error e = load_error(fixture_with("pendulum.xml", "axis='J'", "axis='K'"));
  EXPECT_EQ(e.kind(), ErrorKind::plugin);
  EXPECT_THAT(e.what(), HasSubstr("robots/pend/actuators/spring"));
  EXPECT_THAT(e.what(), HasSubstr("unknown axis 'K'; did you mean 'J'?"));
  e = load_error(fixture_with("scene.xml", "period_ms='40'", "period_ms='2.5'"));
  EXPECT_THAT(e.what(), HasSubstr("not a whole multiple of the physics step"));
  e = load_error(fixture_with("scene.xml", "kind='test_noise'", "kind='test_nois'"));
  EXPECT_EQ(e.kind(), ErrorKind::plugin);
  EXPECT_THAT(e.what(), HasSubstr("test_nois"));
  e = load_error(fixture_with("scene.xml", "solid='things/box'", "solid='things/bx'"));
  EXPECT_THAT(e.what(), HasSubstr("did you mean 'things/box'"));
}

}  // namespace
}  // namespace s2sim
