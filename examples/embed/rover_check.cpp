// Embeds S2Sim (libs2sim.so, CMake target S2Sim::s2sim) to check the rover scene: loads it
// with the example plugin, runs it, and asserts that the heading controller turned the rover
// to its target and drove it; then that a snapshot restored repeats the run exactly.
//   rover_check SCENE_FOLDER PLUGIN_FOLDER     exit 0 when every check passes
#include <s2sim/kernel/simulation.hpp>

#include <cmath>
#include <cstdio>
#include <exception>

namespace {

int failures = 0;

void check(bool ok, const char* what, double value) {
  std::printf("%s %s (%.4f)\n", ok ? "ok  " : "FAIL", what, value);
  if (!ok) ++failures;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: rover_check SCENE_FOLDER PLUGIN_FOLDER\n");
    return 4;
  }
  try {
    s2sim::SimulationOptions options;
    options.plugin_path = {argv[2]};  // searched first, then the installed plugins
    options.seed = 7;
    auto sim = s2sim::Simulation::load(argv[1], options);
    for (const auto& w : sim->warnings())
      std::printf("warning: %s\n", w.c_str());

    const std::size_t x = sim->signal_index("robots/rover/x");
    const std::size_t y = sim->signal_index("robots/rover/y");
    const std::size_t yaw = sim->signal_index("robots/rover/yaw");
    const std::size_t heading = sim->signal_index("robots/rover/sensors/compass/heading");

    sim->run_until(4.0);
    const s2sim::Simulation::Snapshot at4 = sim->save();
    sim->run_until(8.0);
    const double x8 = sim->signal(x), y8 = sim->signal(y), yaw8 = sim->signal(yaw);

    check(std::abs(yaw8 - s2sim::kPi / 2) < 0.05, "turned to 90 degrees: yaw (rad)", yaw8);
    check(std::abs(sim->signal(heading) - yaw8) < 0.02, "the compass reads the yaw (rad)",
          sim->signal(heading));
    check(y8 > 1.0, "drove along +Y (m)", y8);
    check(std::abs(x8) < 0.5, "stayed near x = 0 (m)", x8);

    // The controller's input changes the target: 180 degrees from the snapshot at 4 s on.
    sim->restore(at4);
    sim->run_until(8.0);
    check(sim->signal(y) == y8 && sim->signal(yaw) == yaw8, "a restored run repeats (y, m)",
          sim->signal(y));
    sim->restore(at4);
    sim->set_input("robots/rover/controllers/pilot/heading", s2sim::kPi);
    sim->run_until(8.0);
    check(std::abs(std::abs(sim->signal(yaw)) - s2sim::kPi) < 0.05,
          "a new heading input turns it to 180 degrees: |yaw| (rad)", std::abs(sim->signal(yaw)));
  } catch (const s2sim::Error& e) {
    std::fprintf(stderr, "rover_check: %s\n", e.what());
    return s2sim::exit_code(e.kind());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rover_check: %s\n", e.what());
    return 1;
  }
  std::printf("%s\n", failures == 0 ? "all checks passed" : "some checks FAILED");
  return failures == 0 ? 0 : 1;
}
