#pragma once
// Loading scenes/motor_bench (and edited copies of it) for the drive-train tests.
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <utility>
#include <vector>
#include "common/temp_dir.hpp"

namespace s2sim::test {

namespace fs = std::filesystem;

inline const fs::path kBench = fs::path(S2SIM_SOURCE_DIR) / "scenes/motor_bench";
inline constexpr double kPi = s2sim::kPi;

// Table 2 of the paper (SI).
inline constexpr double kKs = 0.4908, kTc = 3.558e-4, kB = 1.92e-3, kRa = 7.6, kLa = 4.88e-3;

inline SimulationOptions bench_options(std::vector<std::pair<std::string, double>> defines = {},
                                       std::optional<double> step_s = std::nullopt) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  o.constants = std::move(defines);
  o.physics_step_s = step_s;
  return o;
}

inline std::unique_ptr<Simulation> load_bench(
    std::vector<std::pair<std::string, double>> defines = {},
    std::optional<double> step_s = std::nullopt) {
  return Simulation::load(kBench, bench_options(std::move(defines), step_s));
}

/// A copy of the bench with text replacements in its robot file.
inline fs::path bench_with(const std::vector<std::pair<std::string, std::string>>& edits) {
  std::string tag;
  for (const auto& [from, to] : edits)
    tag += from + "->" + to + ";";
  const fs::path dir = s2sim::test::process_temp_dir() /
                       ("s2sim_bench_" + std::to_string(std::hash<std::string>{}(tag)));
  fs::remove_all(dir);
  fs::copy(kBench, dir, fs::copy_options::recursive);
  std::ifstream in(dir / "nxt_motor.xml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const auto& [from, to] : edits) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  std::ofstream(dir / "nxt_motor.xml") << text;
  return dir;
}

inline std::string axis(const char* name) {
  return std::string("robots/bench/axes/motor/") + name;
}

}  // namespace s2sim::test
