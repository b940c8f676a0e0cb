/// \file
/// libFuzzer target for the scene loader and the simulation it builds (docs/reliability.md,
/// "Fuzzing"). The input is a scene.xml; after a NUL byte, a robot file `bot.xml` that the
/// scene may name (`<robot><body file='bot.xml'/></robot>`). A located s2sim::Error is the
/// right answer to bad input; any other exception, a crash or a sanitizer report is a finding.
///
///   cmake --preset fuzz && cmake --build build-fuzz --target s2sim_scene_fuzzer
///   build-fuzz/bin/s2sim_scene_fuzzer -max_total_time=3600 corpus/ tests/fuzz/seeds/

#include <s2sim/kernel/simulation.hpp>

#include <dlfcn.h>
#include <unistd.h>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace {

/// The plugins are built with coverage counters (-fsanitize=fuzzer-no-link) that libFuzzer
/// registers when a library is loaded and reads after every input. The kernel unloads a
/// plugin with its last simulation; its counters would be read unmapped. One reference held
/// here for the process's life keeps every plugin mapped.
bool pin_plugins() {
  for (const auto& entry : fs::directory_iterator(S2SIM_PLUGIN_DIR))
    if (entry.path().extension() == ".so")
      (void)::dlopen(entry.path().c_str(), RTLD_NOW | RTLD_NODELETE);
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool pinned = pin_plugins();
  (void)pinned;
  static const fs::path dir =
      fs::temp_directory_path() / ("s2sim-scene-fuzzer-" + std::to_string(::getpid()));
  static const bool made = fs::create_directories(dir) || true;
  (void)made;
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = input.find('\0');
  std::ofstream(dir / "scene.xml", std::ios::binary | std::ios::trunc) << input.substr(0, nul);
  std::ofstream(dir / "bot.xml", std::ios::binary | std::ios::trunc)
      << (nul == std::string::npos ? std::string() : input.substr(nul + 1));
  try {
    s2sim::SimulationOptions options;
    options.plugin_path = {S2SIM_PLUGIN_DIR};
    auto sim = s2sim::Simulation::load(dir, options);
    sim->step(20);  // a few ticks: sensors, controllers, contact and the integrator run
  } catch (const s2sim::Error&) {
    // A located refusal or divergence: correct.
  }
  // Any other exception escapes: libFuzzer reports it (a finding).
  return 0;
}
