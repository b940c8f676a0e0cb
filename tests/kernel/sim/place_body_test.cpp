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

}  // namespace
}  // namespace s2sim
