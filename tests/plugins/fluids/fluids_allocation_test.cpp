// The fluid components allocate nothing in the step: 1000 ticks of a scene with drag and
// buoyancy (a box hull at a surface), and of one with a propeller, allocate what the bare
// hull does.
#include <s2sim/kernel/simulation.hpp>

#include "common/counting_new.hpp"

#include <gtest/gtest.h>

#include <filesystem>

using s2sim::test::allocations;

namespace s2sim {
namespace {

namespace fs = std::filesystem;

long allocations_per_1000_ticks(const char* fixture) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  auto sim =
      Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "tests/plugins/fluids/fixtures" / fixture, o);
  sim->step(10);
  const long before = allocations.load();
  sim->step(1000);
  return allocations.load() - before;
}

TEST(FluidsAllocation, FluidComponentsAddNoAllocationToTheStep) {
  // Against the same hull with no component at all: what the rest of the step allocates
  // (Simbody's temporaries) is the same, the fluid components add nothing.
  const long bare = allocations_per_1000_ticks("bare_box");
  EXPECT_EQ(allocations_per_1000_ticks("floating_box"), bare);
  EXPECT_EQ(allocations_per_1000_ticks("spin_sphere"), bare);
}

}  // namespace
}  // namespace s2sim
