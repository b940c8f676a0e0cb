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
  EXPECT_LT(deepest, 5e-3) << "an object sank " << deepest * 1e3 << " mm into another";
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

}  // namespace
}  // namespace s2sim
