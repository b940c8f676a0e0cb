// Sensors in the step loop allocate nothing: every operator new of this binary is counted and
// a simulation with sensors must allocate exactly what the bare Simbody model does.
#include <s2sim/kernel/simulation.hpp>

#include "model/multibody.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <string>

namespace {
std::atomic<long> allocations{0};
}

void* operator new(std::size_t n) {
  ++allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace s2sim {
namespace {

namespace fs = std::filesystem;

TEST(SensorAllocation, SensorsAddNoAllocationToTheStep) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR), fs::path(S2SIM_TEST_PLUGIN_DIR) / "sensor-reader"};
  for (const char* fixture : {"ir_wall", "ranger", "floorline", "imu", "proximity", "controller"}) {
    auto sim = Simulation::load(
        fs::path(S2SIM_SOURCE_DIR) / "tests/plugins/sensors/fixtures" / fixture, o);
    if (std::string(fixture) == "proximity") sim->set_input("sensors/magnet/vin", 1.0);
    sim->step(10);
    long before = allocations.load();
    sim->step(1000);
    const long with_sensors = allocations.load() - before;
    model::Multibody bare(sim->scene(), sim->tick_s(), sim->scene().settings.substeps);
    for (int i = 0; i < 10; ++i)
      bare.step();
    before = allocations.load();
    for (int i = 0; i < 1000; ++i)
      bare.step();
    EXPECT_EQ(with_sensors, allocations.load() - before) << fixture;
  }
}

}  // namespace
}  // namespace s2sim
