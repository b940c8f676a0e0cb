// The `jointforce` sensor (docs/models/sensors.md): the reaction a joint transmits, against
// statics and a coasting rotor, from the fixture tests/plugins/sensors/fixtures/jointforce.
#include <s2sim/kernel/simulation.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>
#include "common/temp_dir.hpp"

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr double kG = kGravity_m_s2;
const fs::path kFixture = fs::path(S2SIM_SOURCE_DIR) / "tests/plugins/sensors/fixtures/jointforce";

SimulationOptions options(std::uint64_t seed = 1) {
  SimulationOptions o;
  o.seed = seed;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  return o;
}

double sig(const Simulation& sim, const std::string& sensor, const std::string& field) {
  return sim.signal(sim.signal_index("robots/rig/sensors/" + sensor + "/" + field));
}

TEST(JointForce, AHangingBobAtRestPullsItsHingeWithItsWeight) {
  auto sim = Simulation::load(kFixture, options());
  const double weight = 2 * kG;  // bob of 2 kg: the hinge carries m·g upward on it
  sim->step(1);                  // the first sample (tick 0) reads the initial state, not zeros
  EXPECT_NEAR(sig(*sim, "hang_ft", "fz") / weight, 1.0, 1e-3);
  sim->step(200);
  EXPECT_NEAR(sig(*sim, "hang_ft", "fz") / weight, 1.0, 1e-3);
  EXPECT_NEAR(sig(*sim, "hang_ft", "fx"), 0.0, 1e-3 * weight);
  EXPECT_NEAR(sig(*sim, "hang_ft", "fy"), 0.0, 1e-3 * weight);
  for (const char* t : {"tx", "ty", "tz"})  // the weight passes through the anchor
    EXPECT_NEAR(sig(*sim, "hang_ft", t), 0.0, 1e-6) << t;
  // A Fixed joint (a Weld mobilizer) reports its reaction too.
  EXPECT_NEAR(sig(*sim, "weld_ft", "fz") / (3 * kG), 1.0, 1e-3);
}

TEST(JointForce, WhenBody1IsTheParentItReadsTheBobPullingItDown) {
  // The bob's hinge written <connect B1='block' B2='bob'/> (the block is welded to the world;
  // with the world the loader makes the solid body1, as SimTwo): body1 is now the mobilizer's
  // parent, and the sensor reports body2's (the bob's) load on it, in the block's frame.
  const fs::path dir = s2sim::test::process_temp_dir() / "s2sim_jointforce_parent";
  fs::remove_all(dir);
  fs::copy(kFixture, dir, fs::copy_options::recursive);
  std::ifstream in(dir / "rig.xml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "<connect B1='bob' B2='world'/>";
  text.replace(text.find(from), from.size(), "<connect B1='block' B2='bob'/>");
  std::ofstream(dir / "rig.xml") << text;
  auto sim = Simulation::load(dir, options());
  sim->step(200);
  EXPECT_NEAR(sig(*sim, "hang_ft", "fz") / (-2 * kG), 1.0, 1e-3);
  for (const char* t : {"tx", "ty", "tz"})  // about the anchor: the bob hangs right under it
    EXPECT_NEAR(sig(*sim, "hang_ft", t), 0.0, 1e-6) << t;
  // The weld now carries both weights, and the bob's, hanging at the anchor (0, 0, 1.5) 2 m
  // beside the block's origin (2, 0, 0.5), as a torque of 2 kg·g·2 m about +Y.
  EXPECT_NEAR(sig(*sim, "weld_ft", "fz") / (5 * kG), 1.0, 1e-3);
  EXPECT_NEAR(sig(*sim, "weld_ft", "ty") / (2 * kG * 2), 1.0, 1e-3);
  EXPECT_NEAR(sig(*sim, "weld_ft", "tx"), 0.0, 1e-6);
}

TEST(JointForce, ALoopClosingJointReadsZeroWithALoadTimeWarning) {
  // A second hinge from the bob to the block, on the bob's own axis: the tree reaches the
  // block through it, so the block's weld to the world closes a loop (a Weld constraint).
  const fs::path dir = s2sim::test::process_temp_dir() / "s2sim_jointforce_loop";
  fs::remove_all(dir);
  fs::copy(kFixture, dir, fs::copy_options::recursive);
  std::ifstream in(dir / "rig.xml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string at = "  </articulations>";
  text.replace(text.find(at), 0,
               "    <joint>\n      <ID value='link'/>\n      <type value='Hinge'/>\n"
               "      <connect B1='bob' B2='block'/>\n      <pos x='0' y='0' z='1.5'/>\n"
               "      <axis x='0' y='1' z='0'/>\n      <motor active='0'/>\n"
               "      <friction bv='0' fc='0'/>\n    </joint>\n");
  std::ofstream(dir / "rig.xml") << text;
  auto sim = Simulation::load(dir, options());
  bool warned = false;
  for (const auto& w : sim->warnings())
    if (w.find("weld_ft") != std::string::npos && w.find("'weld'") != std::string::npos &&
        w.find("closes a kinematic loop") != std::string::npos)
      warned = true;
  EXPECT_TRUE(warned);
  sim->step(50);
  for (const char* f : {"fx", "fy", "fz", "tx", "ty", "tz"})
    EXPECT_EQ(sig(*sim, "weld_ft", f), 0.0) << f;
}

TEST(JointForce, AnArmHeldHorizontalByItsDriveReadsTheGravityTorqueMgL) {
  auto sim = Simulation::load(kFixture, options());
  // Arm of 1 kg, centre of mass 0.2 m out along +X, hinge about +Y: gravity turns it the
  // positive way with m·g·L; the ref_torque holds it exactly.
  const double mgl = 1 * kG * 0.2;
  sim->set_input(sim->input_index("robots/rig/axes/hold/ref_torque"), -mgl);
  sim->step(300);
  EXPECT_NEAR(sim->axis_position(1), 0.0, 1e-9);  // it stays horizontal
  // The torque on the arm about the anchor is the drive's, balancing gravity's.
  EXPECT_NEAR(sig(*sim, "hold_ft", "ty") / -mgl, 1.0, 1e-3);
  EXPECT_NEAR(sig(*sim, "hold_ft", "fz") / kG, 1.0, 1e-3);
  EXPECT_NEAR(sig(*sim, "hold_ft", "fx"), 0.0, 1e-3);
  // Without the drive the arm falls: the hinge can no longer carry a torque about its axis.
  sim->set_input(sim->input_index("robots/rig/axes/hold/ref_torque"), 0.0);
  sim->step(11);  // the 10 ms sensor samples again on a step without the drive
  EXPECT_NEAR(sig(*sim, "hold_ft", "ty"), 0.0, 1e-6);
}

TEST(JointForce, ACoastingRotorPullsItsHingeWithTheCentripetalForce) {
  auto sim = Simulation::load(kFixture, options());
  const auto torque = sim->input_index("robots/rig/axes/spin/ref_torque");
  sim->set_input(torque, 0.5);  // spin up, then coast (no friction, no motor)
  sim->step(200);
  sim->set_input(torque, 0.0);
  sim->step(100);
  const double w = sim->axis_velocity(2);
  ASSERT_GT(w, 5.0);
  // Rotor of 0.5 kg, centre of mass 0.15 m from the axis along its own +X: the hinge pulls it
  // inward (−X in its frame) with m·ω²·r, and holds its weight.
  const double centripetal = 0.5 * w * w * 0.15;
  EXPECT_NEAR(sig(*sim, "spin_ft", "fx") / -centripetal, 1.0, 1e-2);
  EXPECT_NEAR(sig(*sim, "spin_ft", "fy"), 0.0, 1e-3 * centripetal);  // no tangential load
  EXPECT_NEAR(sig(*sim, "spin_ft", "fz") / (0.5 * kG), 1.0, 1e-3);
  EXPECT_NEAR(sig(*sim, "spin_ft", "tz"), 0.0, 1e-6);  // free about its axis
}

TEST(JointForce, ASnapshotRestoresTheReadingsExactly) {
  auto sim = Simulation::load(kFixture, options());
  sim->set_input(sim->input_index("robots/rig/axes/spin/ref_torque"), 0.5);
  sim->step(100);
  const auto snapshot = sim->save();
  sim->step(1);
  const double fx = sig(*sim, "spin_ft", "fx"), fy = sig(*sim, "spin_ft", "fy");
  sim->step(50);
  sim->restore(snapshot);
  sim->step(1);  // the sensor reads the reaction saved with the state
  EXPECT_EQ(sig(*sim, "spin_ft", "fx"), fx);
  EXPECT_EQ(sig(*sim, "spin_ft", "fy"), fy);
}

TEST(JointForce, NoiseHasTheStdevOfItsNoiseElement) {
  auto sim = Simulation::load(kFixture, options(5));
  const auto k = sim->signal_index("robots/rig/sensors/hang_noisy/fz");
  double sum = 0, sum2 = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    sim->step(1);
    const double v = sim->signal(k) - 2 * kG;
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / n, stdev = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 4 * 0.5 / std::sqrt(n));
  EXPECT_NEAR(stdev / 0.5, 1.0, 0.05);
  // The clean sensor on the same joint is not disturbed.
  EXPECT_NEAR(sig(*sim, "hang_ft", "fz") / (2 * kG), 1.0, 1e-3);
}

TEST(JointForce, AnUnknownJointIsAnErrorNamingFileElementAndValue) {
  const fs::path dir = s2sim::test::process_temp_dir() / "s2sim_jointforce_unknown";
  fs::remove_all(dir);
  fs::copy(kFixture, dir, fs::copy_options::recursive);
  std::ifstream in(dir / "rig.xml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "<joint id='hang'/>";
  text.replace(text.find(from), from.size(), "<joint id='hagn'/>");
  std::ofstream(dir / "rig.xml") << text;
  try {
    Simulation::load(dir, options());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("rig.xml"));
    EXPECT_THAT(e.what(), HasSubstr("jointforce"));
    EXPECT_THAT(e.what(), HasSubstr("joint@id"));
    EXPECT_THAT(e.what(), HasSubstr("'hagn'"));
    EXPECT_THAT(e.what(), HasSubstr("'hang'"));  // did you mean
  }
}

}  // namespace
}  // namespace s2sim
