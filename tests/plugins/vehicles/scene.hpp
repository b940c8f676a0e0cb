#pragma once
// Loading a vehicle scene of scenes/ with constants of the test's choosing.
#include <s2sim/kernel/simulation.hpp>

#include <filesystem>
#include <map>
#include <memory>
#include <string>

namespace s2sim::vehicles_test {

inline std::unique_ptr<Simulation> load(const std::string& scene,
                                        std::map<std::string, double> constants = {}) {
  SimulationOptions o;
  o.plugin_path = {std::filesystem::path(S2SIM_PLUGIN_DIR)};
  for (const auto& [k, v] : constants)
    o.constants.push_back({k, v});
  return Simulation::load(std::filesystem::path(S2SIM_SOURCE_DIR) / "scenes" / scene, o);
}

}  // namespace s2sim::vehicles_test
