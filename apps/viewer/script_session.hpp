#pragma once
/// \file
/// The SimTwo script of the viewer's scene (docs/scripting.md): which file, its compile
/// errors, and the editor's Compile, Run, Stop, Save and reload (windows/script_window.cpp).

#include "viewer_state.hpp"

#include <string>
#include <vector>

namespace s2sim::viewer {

/// Every `file:line:column: text` line of a compiler's output (fpc's form), in order.
std::vector<ScriptMessage> parse_script_messages(const std::string& output);

/// Points the editor at the scene's script (after a load): reads it when it is another file
/// than the one shown or when it changed on disk and the editor holds no unsaved edit.
void open_scene_script(ViewerState& state);
/// Reads the file again when another program changed it (its mtime) and the editor holds
/// no unsaved edit; an edit is kept and the status says the file changed. Once a frame.
void reload_script_if_changed(ViewerState& state);
/// Writes the editor's text to the script file. Returns false (status says why) on failure.
bool save_script(ViewerState& state);
/// Save, then load the scene anew with this script running (SimTwo's Compile then Run: the
/// simulation restarts at t = 0). A compile error lists its messages and keeps the running
/// simulation. Returns true when the script compiled.
bool compile_script(ViewerState& state);
/// SimTwo's Run: starts the compiled script afresh (fresh globals, Initialize first) through
/// the controller's `running` input; compiles first when the scene runs no script.
void run_script(ViewerState& state);
/// SimTwo's Stop: no more calls until Run.
void stop_script(ViewerState& state);
/// Whether the running simulation has a script controller, and whether it is running.
bool script_loaded(const ViewerState& state);
bool script_running(const ViewerState& state);

}  // namespace s2sim::viewer
