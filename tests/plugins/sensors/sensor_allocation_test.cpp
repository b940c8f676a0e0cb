// Sensors in the step loop allocate nothing: every operator new of this binary is counted and
// a simulation with sensors must allocate exactly what the bare Simbody model does.
#include <s2sim/kernel/simulation.hpp>

#include "common/counting_new.hpp"
#include "common/spray_scene.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <string>
#include "common/temp_dir.hpp"

using s2sim::test::allocations;

namespace s2sim {
namespace {

namespace fs = std::filesystem;

/// Allocations of 1000 ticks of `scene` loaded with `o`.
long allocations_per_1000_ticks(const fs::path& scene, const SimulationOptions& o) {
  auto sim = Simulation::load(scene, o);
  if (sim->find_signal("sensors/magnet/vin")) sim->set_input("sensors/magnet/vin", 1.0);
  sim->step(10);  // first steps may size caches
  const long before = allocations.load();
  sim->step(1000);
  return allocations.load() - before;
}

TEST(SensorAllocation, SensorsAddNoAllocationToTheStep) {
  // Each fixture with its sensors, against the same scene with them inert (every plugin of
  // the build but the sensors one): whatever the rest of the step allocates (Simbody's
  // temporaries, other plugins), sensors add nothing.
  SimulationOptions with, without;
  with.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  const fs::path others = s2sim::test::process_temp_dir() / "s2sim_plugins_but_sensors";
  fs::remove_all(others);
  fs::create_directories(others);
  for (const auto& entry : fs::directory_iterator(S2SIM_PLUGIN_DIR))
    if (entry.path().extension() == ".so" && entry.path().filename() != "libsensors.so")
      fs::create_symlink(entry.path(), others / entry.path().filename());
  without.plugin_path = {others};
  without.default_plugin_path = false;  // not the build's folder, which has the sensors
  for (const std::string fixture :
       {"ir_wall", "ranger", "floorline", "imu", "proximity", "jointforce", "lidar3d"}) {
    // Joint reactions come from Simbody's Acceleration stage, so reading them turns the
    // small-tree fast path off (docs/models/multibody.md): the inert run takes the same path.
    with.simbody_dynamics_only = without.simbody_dynamics_only = fixture == "jointforce";
    const fs::path scene = fs::path(S2SIM_SOURCE_DIR) / "tests/plugins/sensors/fixtures" / fixture;
    EXPECT_EQ(allocations_per_1000_ticks(scene, with), allocations_per_1000_ticks(scene, without))
        << fixture;
  }
  // A spray gun painting through its cone, its rays cast for occlusion, on a moving target.
  with.simbody_dynamics_only = without.simbody_dynamics_only = false;
  test::SprayScene spray;
  spray.cells = 20;
  spray.occlusion = spray.blocker = true;
  const fs::path scene =
      test::write_spray_scene(s2sim::test::process_temp_dir() / "spray_allocation", spray);
  EXPECT_EQ(allocations_per_1000_ticks(scene, with), allocations_per_1000_ticks(scene, without))
      << "spraygun";
}

}  // namespace
}  // namespace s2sim
