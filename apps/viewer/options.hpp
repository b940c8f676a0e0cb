#pragma once
/// \file
/// Command line of s2sim-view.

#include "exit_codes.hpp"

#include <s2sim/kernel/simulation.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace s2sim::viewer {

struct Options {
  std::string scene;
  std::uint64_t seed = 1;
  std::optional<double> physics_step_s;
  std::optional<int> substeps;
  std::vector<std::pair<std::string, double>> constants;  ///< --define
  std::vector<std::pair<std::string, double>> inputs;     ///< --set
  std::vector<std::string> plugin_path;
  std::vector<std::string> model_path;  ///< --model-path
  int width_px = 1280;
  int height_px = 720;
  std::string screenshot_file;  ///< write the last frame as PNG, then quit
  int frames = -1;              ///< stop after this many frames (-1 = until closed)
  /// --watchdog: in a run paced by frames (--frames, a UI script, --video), the longest one call
  /// into a component may last (wall seconds; 0: unwatched). An interactive window shows the
  /// call instead and offers to stop the simulation.
  double watchdog_s = apps::kDefaultWatchdogS;
  std::vector<std::string> show_windows;
  std::vector<std::string> chart_signals;  ///< patterns, as s2sim-run --signals
  std::vector<std::string> script;         ///< UI commands, see ui_script.hpp
  double speed = 1.0;                      ///< times real time; 0 = as fast as possible
  bool paused = false;
  bool shadows = true;  ///< --no-shadows turns them off
  /// --msaa N: samples per pixel of the 3-D view, 0 = off; -1 (default) = as --look says.
  int msaa_samples = -1;
  /// --look fast|full: 0 = fast (no multisampling, planar floor-only shadows), 1 = full
  /// (4x multisampling, shadow map with smooth edges); -1 (default) = full, except fast on a
  /// software rasteriser (llvmpipe) outside screenshot runs.
  int look = -1;
  bool hide_ui = false;            ///< world view only
  double font_scale = 1;           ///< --font-scale: text and widgets scaled (HiDPI)
  bool no_frame_cap = false;       ///< draw as fast as possible (benchmark)
  bool report_fps = false;         ///< print frames per second at exit
  bool print_projections = false;  ///< print where each robot projects on screen (tests)
  /// The SimTwo project's script (docs/scripting.md): as s2sim-run, it runs when the project's
  /// control block says so (--run-script: always, --no-script: never); `script_file` is another
  /// script (--script-file; the viewer's --script is its UI commands).
  ScriptMode script_mode = ScriptMode::control_block;
  std::string script_file;
  /// --sheet R,C=VALUE: SimTwo sheet cells set before the start, as s2sim-run's.
  std::vector<scene::SheetCell> sheet_cells;
  /// Simulated seconds of history the chart keeps (--chart-span), a ring per signal.
  double chart_span_s = 60;
  /// --replay FILE: play a recording (the scene and how it was loaded come from the file).
  std::string replay_file;
  std::string video_file;  ///< --video FILE.mp4: write the replay as a video, then quit
  int video_fps = 30;      ///< --video-fps
  /// The last option given that says how the scene is loaded (--seed, --define, ...):
  /// refused with --replay, whose recording says it.
  std::string load_option;
  bool help = false;
};

/// Parses argv. Throws s2sim::Error (kind usage) naming the bad argument.
Options parse_options(int argc, char** argv);
const char* usage_text();

}  // namespace s2sim::viewer
