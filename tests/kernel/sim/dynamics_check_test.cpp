// The dynamics check (SimulationOptions::check_dynamics, kernel/src/model/checked_dynamics.cpp):
// Simbody's accelerations compared with the small-tree dynamics' at every substep, the run
// stopped where they part, and the checked run's numbers the unchecked run's.
#include <s2sim/error.hpp>
#include <s2sim/kernel/simulation.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kLoops = fs::path(S2SIM_SOURCE_DIR) / "tests/fuzz/seeds/loops/mechanisms";

std::unique_ptr<Simulation> loops(bool checked, bool simbody = false) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  o.check_dynamics = checked;
  o.simbody_dynamics_only = simbody;
  auto sim = Simulation::load(kLoops, o);
  sim->set_input(sim->input_index("robots/walker/axes/hip_front/ref_voltage"), 4);
  sim->set_input(sim->input_index("robots/linkage/axes/crank/ref_voltage"), 6);
  sim->set_input(sim->input_index("robots/slider_crank/axes/crank/ref_voltage"), 8);
  return sim;
}

// Loops on a free walker, a spatial linkage and a slider-crank, driven: until the walker lands,
// Simbody's accelerations are the tree's to 1e-12 of the largest, and checking changes nothing.
TEST(DynamicsCheck, ComparesEverySubstepAndLeavesTheRunAsItIs) {
  auto checked = loops(true);
  auto plain = loops(false);
  EXPECT_EQ(checked->dynamics(), "checked");
  EXPECT_EQ(plain->dynamics(), "tree");
  checked->step(470);
  plain->step(470);
  const Simulation::DynamicsCheck check = checked->dynamics_check();
  EXPECT_EQ(check.compared, 470);
  EXPECT_GT(check.worst_relative, 0.0);  // two computations, not one read twice
  EXPECT_LT(check.worst_relative, 1e-12);
  EXPECT_EQ(check.agreement, 1e-9);
  for (int b = 1; b < plain->body_count(); ++b) {
    EXPECT_EQ(checked->body_pose(b).position.x, plain->body_pose(b).position.x) << b;
    EXPECT_EQ(checked->body_pose(b).position.z, plain->body_pose(b).position.z) << b;
    EXPECT_EQ(checked->body_twist(b).angular_rad_s.y, plain->body_twist(b).angular_rad_s.y) << b;
  }
  EXPECT_EQ(plain->dynamics_check().compared, 0);
}

// As the walker lands, its parallelogram (redundant loop rows) nears a singular pose and the
// two constrained solves part: Simbody's leaves the loop constraints by 1e-6 of the largest
// acceleration where the tree's keeps them. Moved onto the loops, the constrained
// accelerations agree within the agreement over the whole run (docs/models/multibody.md).
TEST(DynamicsCheck, JudgesTheConstrainedAccelerationsWhereTheLoopSolvesPart) {
  auto sim = loops(true);
  sim->step(2000);
  const Simulation::DynamicsCheck check = sim->dynamics_check();
  EXPECT_EQ(check.compared, 2000);
  EXPECT_GT(check.judged_on_loops, 0);
  EXPECT_LT(check.worst_relative, 1e-9);
  EXPECT_LT(check.worst_loop_error, 1e-8);
  EXPECT_GT(check.worst_reference_loop_error, 1e-7);  // Simbody's own solve left the loops
}

// Moving onto the loops hides no difference in the dynamics: a stricter agreement stops the
// loops too, after the move.
TEST(DynamicsCheck, OnTheLoopsAStricterAgreementStillStopsTheRun) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  o.check_dynamics = true;
  o.dynamics_agreement = 1e-13;
  auto sim = Simulation::load(kLoops, o);
  sim->set_input(sim->input_index("robots/walker/axes/hip_front/ref_voltage"), 4);
  try {
    sim->step(2000);
    FAIL() << "the tree and Simbody agreed to 1e-13 on the loops for 2 s";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("both moved onto the loop constraints"));
  }
}

// Beyond the agreement the run stops with a runtime error naming the time, the body and both
// values: the tree and Simbody agree to rounding, not to 1e-16.
TEST(DynamicsCheck, StopsBeyondTheAgreementNamingTheBody) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  o.check_dynamics = true;
  o.dynamics_agreement = 1e-16;
  auto sim = Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "scenes/nxt", o);
  sim->set_input("robots/nxt/axes/left/ref_voltage", 6);
  try {
    sim->step(1000);
    FAIL() << "the tree and Simbody agreed to 1e-16 for a second";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::runtime);
    EXPECT_THAT(e.what(), HasSubstr("the dynamics check failed at t = "));
    EXPECT_THAT(e.what(), HasSubstr("of robot 'nxt'"));
    EXPECT_THAT(e.what(), HasSubstr("beyond the agreement of 1e-16"));
  }
  o.dynamics_agreement = 0.0;
  EXPECT_THROW(Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "scenes/nxt", o), Error);
}

// The reference itself: Simbody's realize chain steps the same scene, its choice reported.
TEST(DynamicsCheck, SimbodyDynamicsAreTheReferenceChosenAtLoad) {
  auto sim = loops(false, true);
  EXPECT_EQ(sim->dynamics(), "simbody");
  sim->step(400);
  auto tree = loops(false);
  tree->step(400);
  for (int b = 1; b < tree->body_count(); ++b)
    EXPECT_NEAR(sim->body_pose(b).position.z, tree->body_pose(b).position.z, 1e-9) << b;
  // Only loose bodies: nothing to choose.
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  o.check_dynamics = true;
  EXPECT_EQ(Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "scenes/pile", o)->dynamics(), "loose");
}

}  // namespace
}  // namespace s2sim
