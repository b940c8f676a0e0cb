#pragma once
/// \file
/// The viewer's windows, each drawn by one function over the shared state.

#include "../viewer_state.hpp"

namespace s2sim::viewer {

/// Play, pause, step, reset, speed, time and real-time factor.
void draw_run_window(ViewerState& state);
/// The Run window's contents in a replay: play, pause, direction, speed, frame steps, timeline.
void draw_replay_controls(ViewerState& state);
/// Physics step, controller periods, speed, camera, shadows; each robot's pose and speed.
void draw_configuration_window(ViewerState& state);
/// Any signals against time, with legend, zoom, pause and CSV export.
void draw_chart_window(ViewerState& state);
/// SimTwo's sheet: the inputs `sheet/<cell>` that controllers read and write.
void draw_sheet_window(ViewerState& state);
/// The scene's XML files; apply reloads the scene and keeps the camera.
void draw_scene_editor_window(ViewerState& state);
/// SimTwo's script editor: the script with line numbers, Compile, Run, Stop, Save, the
/// compiler's located errors (a click shows the line).
void draw_script_window(ViewerState& state);
/// Loader warnings and viewer messages.
void draw_log_window(ViewerState& state);
/// The data of the body picked in the world view.
void draw_body_window(ViewerState& state);
/// The scene's camera and lidar images, each shown one chosen: colour, depth and range in
/// false colour with a legend, body ids in a colour per body (hovering names the body).
void draw_camera_window(ViewerState& state);

/// Reads the scene's XML files into the editor (after a load).
void load_editor_files(ViewerState& state);
/// Applies the editor's text: saves the changed files and reloads; on error restores the files
/// and keeps the running scene. Returns true when the new scene loaded.
bool apply_editor(ViewerState& state);

}  // namespace s2sim::viewer
