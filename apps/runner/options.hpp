#pragma once
/// \file
/// Command line of s2sim-run.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace s2sim::runner {

struct Options {
  std::string scene;
  double duration_s = 10.0;
  bool realtime = false;
  std::string log_file;
  std::optional<double> log_period_s;  ///< default: every tick
  std::vector<std::string> signal_patterns;
  std::string summary_file;
  bool summary_timing = true;  ///< wall_time and rtf in the JSON summary
  std::uint64_t seed = 1;
  std::vector<std::pair<std::string, double>> inputs;     ///< --set
  std::vector<std::pair<std::string, double>> constants;  ///< --define
  std::optional<double> physics_step_s;
  std::optional<int> substeps;
  std::vector<std::string> plugin_path;  ///< searched before the default folders
  bool default_plugin_path = true;       ///< false: --no-default-plugin-path
  bool quiet = false;
  bool list_signals = false;
  bool list_inputs = false;
  bool help = false;
  bool version = false;
};

/// Parses argv. Throws s2sim::Error (kind usage) with a message naming the bad argument.
Options parse_options(int argc, char** argv);

/// The --help text.
const char* usage_text();

}  // namespace s2sim::runner
