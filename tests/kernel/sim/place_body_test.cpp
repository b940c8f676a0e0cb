// Simulation::place_body: moving a free body (the viewer's drag, SimTwo's SetRobotPos).
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include <filesystem>

namespace s2sim {
namespace {

namespace fs = std::filesystem;

const fs::path kFixture = fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/components";

std::unique_ptr<Simulation> load_fixture() {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_TEST_PLUGIN_DIR) / "scene", fs::path(S2SIM_PLUGIN_DIR)};
  return Simulation::load(kFixture, o);
}

int body_index(const Simulation& sim, const std::string& id) {
  const auto& bodies = sim.scene().bodies;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (bodies[b].id == id) return static_cast<int>(b) + 1;
  ADD_FAILURE() << "no body " << id;
  return -1;
}

TEST(PlaceBody, MovesAThingAtRestAndTheRunGoesOnFromThere) {
  auto sim = load_fixture();
  sim->run_until(0.2);
  const int box = body_index(*sim, "box");
  Pose target;
  target.position = {-1, 0.5, 2};
  target.rotation = to_matrix(Quat{std::cos(0.3), 0, 0, std::sin(0.3)});
  sim->place_body(box, target);
  EXPECT_DOUBLE_EQ(sim->time_s(), 0.2);
  const Pose& p = sim->body_pose(box);
  EXPECT_NEAR(p.position.x, -1, 1e-12);
  EXPECT_NEAR(p.position.y, 0.5, 1e-12);
  EXPECT_NEAR(p.position.z, 2, 1e-12);
  EXPECT_NEAR(yaw_of(p.rotation), 0.6, 1e-12);
  EXPECT_EQ(norm(sim->body_twist(box).linear_m_s), 0.0);
  sim->step(10);
  EXPECT_NEAR(sim->body_pose(box).position.x, -1, 1e-6) << "the placed thing drifted sideways";
}

TEST(PlaceBody, RefusesAJointedBodyAndTheWorldNamingThem) {
  auto sim = load_fixture();
  const auto& bodies = sim->scene().bodies;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].robot < 0) continue;
    // A robot body hanging from the world by its joint cannot be placed.
    try {
      sim->place_body(static_cast<int>(b) + 1, Pose{});
      ADD_FAILURE() << bodies[b].id << " was placed";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::usage);
      EXPECT_NE(std::string(e.what()).find(bodies[b].id), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(sim->place_body(0, Pose{}), Error);
  EXPECT_THROW(sim->place_body(10000, Pose{}), Error);
}

/// StepContext::request_move and request_velocity (SDK 0.10) through the test_body_mover
/// plugin (tests/kernel/sim/fixtures/mover): a hinged bob turns about its pivot to the asked
/// position and takes the hinge rate that gives it the asked speed; a thing goes exactly there
/// with exactly the asked velocity.
TEST(MoveBody, AJointedBodyGoesAsCloseAsItsJointAllowsAThingExactly) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_TEST_PLUGIN_DIR) / "scene", fs::path(S2SIM_PLUGIN_DIR)};
  auto sim = Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/mover", o);
  const int bob = body_index(*sim, "bob"), box = body_index(*sim, "box");
  sim->run_until(0.1);
  ASSERT_GT(sim->body_pose(bob).position.x, 0.9) << "the bob has fallen too far already";
  sim->step();  // the movers ask at 0.1 s; the tick then runs from there
  // The bob: below its pivot (0, 0, 2) on its 1 m arm, moving at 2 m/s along X (less the tiny
  // share its own spin takes in the inertia metric); one tick of gravity and motion after.
  const Pose& p = sim->body_pose(bob);
  EXPECT_NEAR(p.position.x, 0.002, 1e-4);
  EXPECT_NEAR(p.position.z, 1.0, 1e-4);
  EXPECT_NEAR(std::abs(sim->signal("robots/pend/axes/J/speed")), 2.0, 2e-3);
  EXPECT_NEAR(sim->body_twist(bob).linear_m_s.x, 2.0, 2e-3);
  // The box: there, at 1 m/s along Y and 2 rad/s about Z, one tick of gravity later.
  const Pose& q = sim->body_pose(box);
  EXPECT_NEAR(q.position.x, 3, 1e-9);
  EXPECT_NEAR(q.position.y, 1.001, 1e-9);
  EXPECT_NEAR(q.position.z, 1, 1e-4);
  EXPECT_NEAR(sim->body_twist(box).linear_m_s.y, 1, 1e-9);
  EXPECT_NEAR(sim->body_twist(box).angular_rad_s.z, 2, 1e-9);
}

}  // namespace
}  // namespace s2sim
