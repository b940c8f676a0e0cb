// Independent trees of the implicit axis solve (kernel/src/model/axis_trees.cpp): robots that
// do not touch each other are solved as their own blocks. A robot's motion does not depend on
// another robot far away, to the last bit, and the number of robots costs linearly (a dense
// solve over every axis of the scene once took 183 ms per step for 200 robots).
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>
#include "common/temp_dir.hpp"

namespace s2sim {
namespace {

namespace fs = std::filesystem;

/// A scene of NXT robots (scenes/nxt) side by side, 3 m apart along x.
fs::path nxt_scene(const std::string& name, int robots) {
  const fs::path dir = s2sim::test::process_temp_dir() / ("axis_trees_" + name);
  fs::create_directories(dir);
  fs::copy_file(fs::path(S2SIM_SOURCE_DIR) / "scenes/nxt/nxt.xml", dir / "nxt.xml",
                fs::copy_options::overwrite_existing);
  std::ofstream scene(dir / "scene.xml");
  scene << "<scene>\n";
  for (int r = 0; r < robots; ++r)
    scene << "<robot><ID name='r" << r << "'/><pos x='" << 3 * r
          << "' y='0' z='0'/><body file='nxt.xml'/></robot>\n";
  scene << "</scene>\n";
  return dir;
}

SimulationOptions options() {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  return o;
}

/// Robot r0's wheel speeds and pose over 1.5 s at 6 V on its right motor and 4 V on its left;
/// the other robots drive otherwise (they turn, which changes their mass matrices' blocks).
std::vector<double> first_robot_run(int robots) {
  auto sim = Simulation::load(nxt_scene(std::to_string(robots), robots), options());
  sim->set_input("robots/r0/axes/right/ref_voltage", 6);
  sim->set_input("robots/r0/axes/left/ref_voltage", -4);
  for (int r = 1; r < robots; ++r) {
    sim->set_input("robots/r" + std::to_string(r) + "/axes/right/ref_voltage", -3.0 * r);
    sim->set_input("robots/r" + std::to_string(r) + "/axes/left/ref_voltage", 5);
  }
  std::vector<double> trace;
  for (int k = 0; k < 1500; ++k) {
    sim->step(1);
    for (const char* s : {"robots/r0/axes/right/speed", "robots/r0/axes/left/speed", "robots/r0/x",
                          "robots/r0/y", "robots/r0/yaw"})
      trace.push_back(sim->signal(s));
  }
  return trace;
}

TEST(AxisTrees, ARobotMovesBitForBitAsAloneBesideOthersThatDoNotTouchIt) {
  const std::vector<double> alone = first_robot_run(1);
  const std::vector<double> with_two = first_robot_run(3);
  ASSERT_EQ(alone.size(), with_two.size());
  for (std::size_t i = 0; i < alone.size(); ++i)
    ASSERT_EQ(alone[i], with_two[i]) << "value " << i % 5 << " at tick " << i / 5 + 1;
  // It did move: a test of a robot standing still would prove nothing.
  EXPECT_GT(std::abs(alone[alone.size() - 5]), 1.0);  // right wheel speed, rad/s
  EXPECT_GT(std::abs(alone.back()), 0.1);             // it turned, rad
}

}  // namespace
}  // namespace s2sim
