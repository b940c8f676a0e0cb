// S2Sim's own contact scenes: the pile (scenes/pile).
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace s2sim {
namespace {

namespace fs = std::filesystem;

TEST(PileScene, HundredBoxesAndFiftySpheresSettleWithoutPassingThroughAnything) {
  auto sim = Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "scenes/pile");
  ASSERT_EQ(sim->scene().things.size(), 150u);
  // Nothing is flung away: contact never adds energy, so the total never rises above the
  // energy at release (it may only be dissipated), and nothing rises above the top layer.
  const double released = sim->kinetic_energy_J() + sim->potential_energy_J();
  double deepest = 0, highest = 0, most_energy = released;
  while (sim->time_s() < 5.0) {
    sim->step();  // throws on a non-finite state
    for (std::size_t c = 0; c < sim->contact_count(); ++c)
      deepest = std::max(deepest, sim->contact(c).depth_m);
    for (int b = 1; b < sim->body_count(); ++b)
      highest = std::max(highest, sim->body_pose(b).position.z);
    most_energy = std::max(most_energy, sim->kinetic_energy_J() + sim->potential_energy_J());
  }
  RecordProperty("deepest_mm", std::to_string(deepest * 1e3));
  EXPECT_LT(deepest, 2e-3) << "an object sank " << deepest * 1e3 << " mm into another";
  // 0.2 %: the kinetic energy is read from mid-step velocities (leapfrog), h/2 behind.
  EXPECT_LE(most_energy, released + 2e-3 * std::abs(released)) << "contact added energy";
  EXPECT_LT(highest, 0.89) << "an object was thrown up";  // the top layer starts at 0.88 m
  // Everything lies on something; the boxes have almost all come to rest (the balls roll on:
  // there is no rolling resistance, and they still knock a few boxes).
  int boxes = 0, resting = 0;
  for (int b = 1; b < sim->body_count(); ++b) {
    const auto& body = sim->scene().bodies[b - 1];
    EXPECT_GT(sim->body_pose(b).position.z, 0.045) << body.id;
    if (body.kind != scene::SolidKind::cuboid) continue;
    ++boxes;
    if (norm(sim->body_twist(b).linear_m_s) < 0.02) ++resting;
  }
  EXPECT_GE(resting, boxes * 9 / 10);
}

TEST(PileScene, AtOneMillisecondWithoutSubstepsNothingSinksTwoMillimetres) {
  // The peers' configuration (bench/peers). The scene starts with every
  // object apart (scripts/make-pile-scene.py), so the deepest point is the simulator's own.
  SimulationOptions options;
  options.physics_step_s = 1e-3;
  options.substeps = 1;
  auto sim = Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "scenes/pile", options);
  double deepest = 0, first = 0;
  while (sim->time_s() < 2.0) {
    sim->step();
    for (std::size_t c = 0; c < sim->contact_count(); ++c)
      deepest = std::max(deepest, sim->contact(c).depth_m);
    if (sim->time_s() < 0.0015) first = deepest;
  }
  RecordProperty("deepest_mm", std::to_string(deepest * 1e3));
  EXPECT_LT(first, 1e-4) << "the scene starts with objects inside one another";
  EXPECT_LT(deepest, 2e-3);
}

}  // namespace
}  // namespace s2sim

namespace s2sim {
namespace {

// Contact memory (bristles, impacts) and the brakes' cached M^-1 columns are part of a
// snapshot: a restored run repeats the original bit for bit.
TEST(ContactSnapshot, ARestoredRunRepeatsTheOriginalBitForBit) {
  // Standing (brakes holding, columns reused) and driving (brakes sliding).
  for (const auto& [scene, volts] : {std::pair<const char*, double>{"scenes/nxt", 0.0},
                                     {"scenes/nxt", 3.0},
                                     {"scenes/omni3", 3.0}}) {
    auto sim = Simulation::load(std::filesystem::path(S2SIM_SOURCE_DIR) / scene);
    for (std::size_t i = 0; i < sim->input_count(); ++i)
      if (sim->input_info(i).name.find("ref_voltage") != std::string::npos)
        sim->set_input(i, volts);
    sim->run_until(0.5);
    const Simulation::Snapshot snapshot = sim->save();
    sim->run_until(1.0);
    std::vector<Pose> first;
    for (int b = 0; b < sim->body_count(); ++b)
      first.push_back(sim->body_pose(b));
    sim->restore(snapshot);
    sim->run_until(1.0);
    for (int b = 0; b < sim->body_count(); ++b) {
      EXPECT_EQ(sim->body_pose(b).position, first[b].position) << scene << " body " << b;
      EXPECT_EQ(sim->body_pose(b).rotation, first[b].rotation) << scene << " body " << b;
    }
  }
}

// A robot placed by hand 5 mm into the floor (SetRobotPos, the viewer's drag) rises out of it
// without being thrown, and the overlap's relaxation is in the snapshot: restored mid-way, the
// run repeats bit for bit.
TEST(ContactSnapshot, ARobotPlacedIntoTheFloorRisesOutGentlyAndARestoredRunRepeats) {
  auto sim = Simulation::load(std::filesystem::path(S2SIM_SOURCE_DIR) / "scenes/nxt");
  int root = -1;
  for (int b = 0; b < sim->body_count() && root < 0; ++b)
    if (sim->body_path(b).find("nxt") != std::string::npos) root = b;
  ASSERT_GE(root, 0);
  sim->run_until(0.5);  // settled on the floor
  const double resting_z = sim->body_pose(root).position.z;
  Pose sunk = sim->body_pose(root);
  sunk.position.z -= 0.005;
  sim->place_body(root, sunk);
  const double placed_at = sim->time_s();
  double fastest = 0, highest = 0;
  Simulation::Snapshot snapshot;
  bool saved = false;
  while (sim->time_s() < placed_at + 1.0 - 1e-9) {
    sim->step(1);
    if (!saved && sim->time_s() >= placed_at + 0.05 - 1e-9) {
      snapshot = sim->save();
      saved = true;
    }
    fastest = std::max(fastest, std::abs(sim->body_twist(root).linear_m_s.z));
    highest = std::max(highest, sim->body_pose(root).position.z - resting_z);
  }
  std::printf(
      "  nxt placed 5 mm into the floor: fastest rise %.4f m/s, highest %.6f m above its "
      "rest, after 1 s %.6f m\n",
      fastest, highest, sim->body_pose(root).position.z - resting_z);
  EXPECT_LT(fastest, 0.1) << "thrown out of the floor";
  EXPECT_LT(highest, 5e-4) << "hopped";
  EXPECT_NEAR(sim->body_pose(root).position.z, resting_z, 2e-4) << "not back at rest";
  std::vector<Pose> first;
  for (int b = 0; b < sim->body_count(); ++b)
    first.push_back(sim->body_pose(b));
  const double end = sim->time_s();
  sim->restore(snapshot);
  sim->run_until(end);
  for (int b = 0; b < sim->body_count(); ++b) {
    EXPECT_EQ(sim->body_pose(b).position, first[b].position) << "body " << b;
    EXPECT_EQ(sim->body_pose(b).rotation, first[b].rotation) << "body " << b;
  }
}

}  // namespace
}  // namespace s2sim
