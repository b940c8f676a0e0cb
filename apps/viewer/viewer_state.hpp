#pragma once
/// \file
/// Everything the viewer's windows share: the simulation, the camera, run control, the chart
/// data, the log and which windows are open. The windows are free functions over this state
/// (windows/*.hpp), so each stays one small file.

#include "camera.hpp"
#include "camera_window_state.hpp"
#include "chart_data.hpp"
#include "layout.hpp"
#include "options.hpp"
#include "renderer.hpp"
#include "replay.hpp"
#include "run_control.hpp"
#include "scene_drawables.hpp"
#include "trails.hpp"

#include <s2sim/kernel/simulation.hpp>

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace s2sim::viewer {

using render::Drawable;
using render::DrawItem;
using render::Renderer;
using render::RenderSettings;
using render::SceneDrawables;

struct LogLine {
  double time_s;
  std::string text;
  bool error = false;
};

/// The scene editor's buffers: one per XML file of the scene.
struct EditorFile {
  std::filesystem::path path;
  std::string text;     ///< what the editor shows (maybe edited)
  std::string on_disk;  ///< what the running scene was loaded from
};
struct EditorState {
  std::vector<EditorFile> files;
  int current = 0;
  std::string error;          ///< the last apply's error (full message), empty when it succeeded
  std::string error_message;  ///< the same without its location
  int error_line = -1;        ///< 1-based line in `error_file`, -1 when unknown
  std::string error_file;
  std::string status;
};

/// A located message of the script compiler: `file:line:column: text`.
struct ScriptMessage {
  std::string file;
  int line = 0, column = 0;
  std::string text;
};

/// The Script window (windows/script_window.cpp, script_session.cpp): SimTwo's script editor.
struct ScriptEditorState {
  std::filesystem::path file;               ///< the project's script; empty when it has none
  std::string text;                         ///< what the editor shows (maybe edited)
  std::string on_disk;                      ///< the file as last read or saved
  std::filesystem::file_time_type mtime{};  ///< of the file when read or saved
  std::vector<ScriptMessage> errors;        ///< of the last compile
  std::string status;
  int highlight_line = -1;                            ///< 1-based: the error line shown, -1 = none
  int scroll_to_line = -1;                            ///< scroll there in the next frame
  int first_visible_line = 0, last_visible_line = 0;  ///< as last drawn (tests)
};

/// What the chart window shows (the samples are in ChartData).
struct ChartView {
  /// XY mode: series `y_series` against series `x_series` (positions in ChartData::signals(),
  /// -1 = unset), and the XY series a SimTwo script publishes (Simulation::annotations()).
  bool xy = false;
  int x_series = -1, y_series = -1;
  double window_s = 10;  ///< visible time span
  bool frozen = false;   ///< "pause": the view stops following new samples
  double frozen_end_s = 0;
  std::string filter;
  std::string csv_file = "chart.csv";
  std::string status;
};

/// The world view's overlay (windows/world_overlay.cpp).
struct OverlaySettings {
  bool trails = false;
  float trail_length_s = 20;  ///< simulated seconds of trail shown
  bool axes = true;
  bool labels = false;
  bool scale_bar = true;
};

struct WindowFlags {
  bool run = true;
  bool configuration = false;
  bool chart = false;
  bool sheet = false;
  bool editor = false;
  bool script = false;
  bool log = false;
  bool body = false;
  bool cameras = false;
};

struct ViewerState {
  Options options;
  std::unique_ptr<Simulation> sim;
  Camera camera;
  RunControl run;
  /// Set when the viewer plays a recording (--replay) instead of running the simulation.
  std::unique_ptr<Replay> replay;
  ChartData chart;
  ChartView chart_view;
  std::vector<LogLine> log;
  EditorState editor;
  ScriptEditorState script_editor;
  /// The next annotation log line to copy into the log (Simulation::annotations()).
  std::uint64_t next_published_line = 0;
  WindowFlags windows;
  LayoutFractions layout;    ///< column sizes the user set (saved in the ImGui ini file)
  TiledLayout layout_rects;  ///< this frame's rectangles, the 3-D view's included
  std::array<bool, 16> panels_open_last_frame{};  ///< a panel opened since brings its tab up
  RenderSettings render;
  OverlaySettings overlay;
  CameraWindowState cameras;
  Trails trails;
  bool show_beams = true;
  bool show_joints = true;
  int selected_body = -1;          ///< simulation body index, -1 = none
  float physics_step_ms_edit = 0;  ///< the configuration window's field, 0 = not edited yet
  double frame_time_s = 0;         ///< smoothed wall time per frame
  std::string run_status_text;     ///< the Run window's real-time factor line as last shown
  /// Scripted runs advance a fixed 1/60 s per frame unless a script asks for the wall clock
  /// (`pace wall`), as an interactive run does.
  bool scripted_wall_pacing = false;
  bool quit = false;
  /// Frame the whole scene at the start of the next frame (start, the F key, `frame`).
  bool frame_request = true;
  /// Set when a script placed the camera this frame: it wins over the framing that starts
  /// with following a robot.
  bool camera_set_by_script = false;
  /// `print layout` / `print scene-box`: printed at the end of the frame, once the windows
  /// are placed and the camera has moved.
  std::vector<std::string> end_of_frame_prints;
  /// A freshly loaded simulation (scene editor, configuration) that the app swaps in at the
  /// start of the next frame, keeping the camera, the chart's signals and the windows.
  std::unique_ptr<Simulation> pending_simulation;

  /// While the stepping thread is in a call that has not come back (stepper.hpp), nothing may
  /// read or write `sim`, `run` or `chart`: the frame shows what runs and for how long.
  struct Stuck {
    bool now = false;
    std::string component;  ///< running_component()'s text, or empty for the kernel's own code
    double running_s = 0;   ///< wall seconds the call (or the step) has been running
  } stuck;

  /// Buttons pressed by a UI script this frame, consumed by `button()`.
  std::vector<std::string> scripted_clicks;

  void log_message(const std::string& text, bool error = false) {
    log.push_back({sim ? sim->time_s() : 0.0, text, error});
  }
};

/// ImGui::Button that a UI script can also press (same label): the tests drive the same code
/// path a mouse click does.
bool button(ViewerState& state, const char* label);

/// Moves a body (a thing or a robot's root body) to `position_m` at rest, keeping its
/// orientation (Simulation::place_body). A body that cannot move is reported in the log;
/// returns false then.
bool move_body(ViewerState& state, int body, const Vec3& position_m);

/// Loads options.scene with the options' seed, step, constants and script settings; throws
/// s2sim::Error.
std::unique_ptr<Simulation> load_simulation(const Options& options);
/// load_simulation, but a SimTwo script that does not compile does not refuse the scene: its
/// located messages go to `state.script_editor.errors` (and the log), and the scene loads
/// without its script. Other errors throw as load_simulation's.
std::unique_ptr<Simulation> load_simulation_keeping_script_errors(ViewerState& state,
                                                                  const Options& options);

}  // namespace s2sim::viewer
