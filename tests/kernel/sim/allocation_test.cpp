// "No allocation in the step loop", checked: every operator new in this test binary is counted.
// Simbody's forward dynamics allocates small temporaries itself (and constraint projection
// more); what S2Sim controls -- scheduler, components, loads, reading back -- must add none.
#include <s2sim/kernel/simulation.hpp>

#include "kernel/model/model_runner.hpp"
#include "model/multibody.hpp"
#include "scene/element_params.hpp"
#include "sim/step.hpp"

#include "common/counting_new.hpp"
#include "common/edited_copy.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <string>
#include <thread>

using s2sim::test::allocations;

namespace s2sim {
namespace {

struct Counts {
  long simulation = 0;  // per 1000 ticks of Simulation::step
  long simbody = 0;     // per 1000 steps of the bare multibody model of the same scene
};

Counts count(const std::filesystem::path& scene, const SimulationOptions& o) {
  Counts c;
  auto sim = Simulation::load(scene, o);
  sim->step(1500);  // first steps size caches; contacts settle
  long before = allocations.load();
  sim->step(1000);
  c.simulation = allocations.load() - before;

  model::Multibody bare(sim->scene(), sim->tick_s(), sim->scene().settings.substeps);
  // The same Coulomb brakes and implicit drives as the drive train applies (Simbody's M^-1
  // products and velocity projections allocate).
  for (std::size_t a = 0; a < bare.axes().size(); ++a) {
    const auto& jt = sim->scene().joints[bare.axes()[a].joint];
    const scene::ElementParams drive(bare.axes()[a].which == 0 ? jt.drive1 : jt.drive2);
    bare.applied_axis_friction()[a] = drive.number("friction.fc", 1e-3);  // plugin defaults
    const double viscous = drive.number("friction.bv", 1e-5);
    if (viscous > 0)
      bare.axis_drives()[(*bare.axis_drive_count())++] =
          AxisDrive{static_cast<std::int32_t>(a), 0.0, viscous, -INFINITY, INFINITY};
  }
  for (int i = 0; i < 10; ++i)
    test::physics_tick(bare, nullptr);
  before = allocations.load();
  for (int i = 0; i < 1000; ++i)
    test::physics_tick(bare, nullptr);
  c.simbody = allocations.load() - before;
  return c;
}

TEST(Allocation, TheKernelAddsNoAllocationToSimbodysOwn) {
  SimulationOptions o;
  o.plugin_path = {std::filesystem::path(S2SIM_TEST_PLUGIN_DIR) / "scene",
                   std::filesystem::path(S2SIM_PLUGIN_DIR)};
  // Components of every category, a hinge, a free thing.
  const Counts a =
      count(std::filesystem::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/components", o);
  EXPECT_EQ(a.simulation, a.simbody);
  // The default scene without its loop: hinges, a slider with stops, a universal joint.
  const auto no_loop = test::edited_copy(std::filesystem::path(S2SIM_SOURCE_DIR) / "scenes/default",
                                         "scene.xml", "<body file='four_bar.xml'/>", "");
  const Counts b = count(no_loop, SimulationOptions{});
  EXPECT_EQ(b.simulation, b.simbody);
  EXPECT_EQ(b.simulation, 0) << "every tree on the fast path, the universal joint's too";
  // Loops on the fast path (every kind: the loops seed's hinge, ball and slider loops, a walker
  // on the floor; the peers' closed-loop arm; the default scene's four-bar beside its gimbal):
  // no Simbody projection, nothing allocated at all.
  for (const char* scene :
       {"tests/fuzz/seeds/loops/mechanisms", "bench/peers/scenes/arm_loop", "scenes/default"}) {
    const Counts f = count(std::filesystem::path(S2SIM_SOURCE_DIR) / scene, SimulationOptions{});
    EXPECT_EQ(f.simulation, 0) << scene;
    EXPECT_EQ(f.simbody, 0) << scene;
  }
  // Contact: a pile of boxes and spheres (box-box by FCL's boxBox2, sphere-box, planes), after
  // it has settled so that the contact count is steady.
  SimulationOptions settled;
  const Counts c = count(std::filesystem::path(S2SIM_SOURCE_DIR) / "scenes/pile", settled);
  EXPECT_EQ(c.simulation, c.simbody);
  const auto base = std::filesystem::path(S2SIM_SHARED_SCENES) / "base";
  if (std::filesystem::exists(base / "scene.xml")) {
    // With motors the drive train's brakes follow the motion: axes that slide get Coulomb's
    // law as a force and skip Simbody's allocating M^-1 products, so the simulation may
    // allocate less than the bare model braked on every axis, never more.
    const Counts d = count(base, SimulationOptions{});
    EXPECT_LE(d.simulation, d.simbody);
  }
  RecordProperty("simbody_allocations_per_step_components", std::to_string(a.simbody / 1000.0));
  RecordProperty("simbody_allocations_per_step_default", std::to_string(b.simbody / 1000.0));
}

}  // namespace
}  // namespace s2sim

namespace s2sim {
namespace {

/// Allocations in 1000 ticks of robots_16 after 500, every thread counted.
long robots16_allocations(int threads, bool simbody_dynamics_only) {
  SimulationOptions o;
  o.threads = threads;
  o.simbody_dynamics_only = simbody_dynamics_only;
  auto sim =
      Simulation::load(std::filesystem::path(S2SIM_SOURCE_DIR) / "bench/peers/scenes/robots_16", o);
  for (std::size_t i = 0; i < sim->input_count(); ++i)
    if (sim->input_info(i).name.find("/ref_voltage") != std::string::npos) sim->set_input(i, 5.0);
  sim->step(500);
  const long before = allocations.load();
  sim->step(1000);
  return allocations.load() - before;
}

TEST(Allocation, TheParallelStepAddsOnlySimbodysOwnPerSystem) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one hardware thread";
  // The pool, the parts' slices and the ticket allocate nothing. Through Simbody's realize
  // chain each system allocates its own temporaries per tick (2 on this scene, whatever its
  // size), and Simbody's operators allocate theirs for each contact friction point's column
  // (the same points whatever the parts), so two systems of 8 robots allocate exactly one
  // system's 2 a tick more than one of 16 does; through the small-tree fast path (the default
  // here) nothing allocates at all.
  const long serial = robots16_allocations(1, true);
  const long parallel = robots16_allocations(2, true);
  RecordProperty("allocations_per_tick_serial", std::to_string(serial / 1000.0));
  RecordProperty("allocations_per_tick_two_threads", std::to_string(parallel / 1000.0));
  EXPECT_GT(serial, 0);
  EXPECT_EQ(parallel - serial, 2 * 1000);
  EXPECT_EQ(robots16_allocations(1, false), 0);
  EXPECT_EQ(robots16_allocations(2, false), 0);
}

}  // namespace
}  // namespace s2sim
