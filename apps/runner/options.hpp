#pragma once
/// \file
/// Command line of s2sim-run.

#include "exit_codes.hpp"

#include <s2sim/kernel/simulation.hpp>

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
  std::string record_file;             ///< --record: the state at every log period
  std::string save_images_dir;         ///< --save-images: every camera frame as a PNG
  std::string video_file;              ///< --video: a camera's colour frames as an MP4
  std::string video_image;             ///< --video-image: which camera image
  std::vector<std::string> signal_patterns;
  std::string summary_file;
  bool summary_timing = true;  ///< wall_time and rtf in the JSON summary
  std::uint64_t seed = 1;
  std::vector<std::pair<std::string, double>> inputs;     ///< --set
  std::vector<std::pair<std::string, double>> constants;  ///< --define
  std::optional<double> physics_step_s;
  std::optional<int> substeps;
  bool simbody_dynamics_only = false;  ///< --simbody-dynamics: no small-tree dynamics
  bool check_dynamics = false;         ///< --check-dynamics: Simbody's compared every substep
  int threads = 1;                     ///< --threads: parts of the multibody stepped at once
  /// --watchdog: the longest one call into a component may last (wall seconds; 0: unwatched).
  double watchdog_s = apps::kDefaultWatchdogS;
  std::vector<std::string> plugin_path;  ///< searched before the default folders
  bool default_plugin_path = true;       ///< false: --no-default-plugin-path
  std::vector<std::string> model_path;   ///< --model-path: package:// and model:// folders
  /// The project's SimTwo script: as its control block says (default), --run-script, --no-script.
  ScriptMode script_mode = ScriptMode::control_block;
  std::string script_file;  ///< --script FILE
  /// --press R,C[@SECONDS]: a click on sheet button (row, column) at a time (default 0).
  struct Press {
    int row = 0, col = 0;
    double time_s = 0;
  };
  std::vector<Press> presses;
  /// --sheet R,C=VALUE: a sheet cell's number before the first step.
  struct SheetValue {
    int row = 0, col = 0;
    double value = 0;
  };
  std::vector<SheetValue> sheet_values;
  bool quiet = false;
  bool list_signals = false;
  bool list_inputs = false;
  bool help = false;
  bool version = false;
};

/// SimTwo's sheet cell (row, column), 1-based, as the input's name: `B3` for (3, 2).
inline std::string cell_name(int row, int col) {
  std::string letters;
  for (int c = col; c > 0; c = (c - 1) / 26)
    letters.insert(letters.begin(), static_cast<char>('A' + (c - 1) % 26));
  return letters + std::to_string(row);
}

/// Parses argv. Throws s2sim::Error (kind usage) with a message naming the bad argument.
Options parse_options(int argc, char** argv);

/// The --help text.
const char* usage_text();

}  // namespace s2sim::runner
