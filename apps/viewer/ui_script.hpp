#pragma once
/// \file
/// Scripted UI input for tests and documentation: a list of commands run one after the other
/// between frames, pressing the same buttons a user would (docs/viewer.md lists them).
///
///   wait N               let N frames pass
///   click LABEL          press the button LABEL (e.g. Pause, Step, Reset, Apply, Export CSV)
///                        and let the next frame act on it
///   run-until T          play until the simulated time reaches T seconds, then pause
///   speed X              times real time; 0 = as fast as possible
///   print time           print "time <t>" on stdout
///   print stuck          print "stuck yes|no <seconds> <component>": a call into a component
///                        that has not returned (the only print while one runs)
///   print editor-error   print "editor-error <line> <message>" (line -1 when unknown)
///   print tick           print "tick <n>"
///   print body ID        print "body <ID> <x> <y> <z>" (its position, m)
///   print camera         print "camera <yaw> <pitch> <distance> <target x y z>"
///   print signal NAME    print "signal <NAME> <value>"
///   move BODY X Y Z      move a thing (or robot root body) there at rest, as a ctrl-drag does
///   sheet-set CELL VALUE set the sheet cell (input sheet/CELL), as typing in the Sheet does
///   chart-add PATTERN    chart the signals matching PATTERN
///   chart-csv FILE       set the chart's CSV file name (then `click Export CSV`)
///   show NAME / hide NAME   open or close a window (run, configuration, chart, sheet, script,
///                        editor, log, body, cameras)
///   select BODY          pick a body by ID (as a click in the world view does)
///   editor-open FILE     show the scene editor's file whose name is FILE
///   editor-insert LINE TEXT   insert TEXT and a line break before line LINE (1-based)
///   camera YAW PITCH DISTANCE  degrees, degrees, metres
///   follow ROBOT         the camera follows the robot
///   screenshot FILE      save this frame as PNG
///   quit
/// While a component's call has not returned, only wait, click, screenshot, sleep, quit and
/// `print stuck` run; the next other command waits until the simulation answers again.

#include "viewer_state.hpp"

#include <string>
#include <vector>

namespace s2sim::viewer {

class UiScript {
 public:
  explicit UiScript(std::vector<std::string> commands) : commands_(std::move(commands)) {}

  /// Runs commands until one needs frames to pass. Called once a frame, before the UI is
  /// drawn. Sets `screenshot_file` when the frame must be saved. Throws s2sim::Error (usage)
  /// for an unknown command or a bad argument.
  void frame(ViewerState& state, std::string& screenshot_file);
  bool finished() const { return next_ >= commands_.size() && wait_frames_ == 0 && !running_; }
  bool empty() const { return commands_.empty(); }

 private:
  void run_commands(ViewerState& state, std::string& screenshot_file);

  std::vector<std::string> commands_;
  std::size_t next_ = 0;
  int wait_frames_ = 0;
  bool running_ = false;  ///< inside run-until
};

/// The commands of ui_script_more.cpp (SimTwo script editor, XY chart, HUD, memory):
///   script-goto-error N  show the script's N-th compile error's line, as clicking it does
///   script-set-line N TEXT   replace line N (1-based) of the script editor's text
///   chart-xy X Y         chart signal Y against signal X (exact names); chart-time: back
///   sleep S              wait S seconds of wall time (tests that change files meanwhile)
///   print script-errors  "script-error FILE LINE COLUMN TEXT" for each compile error
///   print script-view    "script-view FIRST LAST HIGHLIGHT": the lines the editor shows
///   print script-status  "script-status LOADED RUNNING STATUS"
///   print script-line N  "script-line N TEXT" of the editor's text
///   print hud            "hud TEXT" (lines joined by " | ")
///   print log-count TEXT "log-count N": the log's lines that contain TEXT
///   print script-trails  "script-trail SOURCE ID POINTS" for each published trail
///   print xy-series      "xy-series SOURCE ID POINTS" for each published XY series
///   print chart-samples  "chart-samples N FIRST_S LAST_S"
///   print memory         "memory VmRSS_kB VmHWM_kB" (/proc/self/status)
/// Each returns false for a command (or print argument) it does not know.
bool more_commands(ViewerState& state, const std::string& command, const std::string& rest);
/// A replay's commands (--replay; an error without one):
///   replay-seek T        move the replay's clock to T seconds (as dragging the timeline)
///   replay-speed X       recorded seconds per wall second, negative: backwards; and play
///   replay-step N        N frames forwards (negative: back), paused
///   print replay         "replay <clock s> <frame time s> <frame> <frames> <playing> <speed>"
bool replay_command(ViewerState& state, const std::string& command, const std::string& rest);
bool print_more(ViewerState& state, const std::string& what);
/// The camera window's commands (ui_script_cameras.cpp):
///   camera-image NAME on|off   show or hide image NAME in the Cameras window
///   print cameras        "camera-image NAME SHOWN FRAME UPLOADS X Y W H NEAR FAR legend X Y W
///                        H" for each image (where it and its legend's bar were drawn last
///                        frame; NEAR FAR: a distance image's legend); a point cloud's
///                        "points N" instead of the rest
///   print image-pixel NAME X Y   "image-pixel NAME X Y VALUES": the image's own pixel (r g b,
///                        metres, or id and body path)
///   print image-blocks NAME NX NY   "image-blocks NAME NX NY R G B...": the mean colour, as
///                        the window shows it, of each block of an NX x NY grid, row by row
///   print image-ids NAME "image-id NAME ID PIXELS PATH" for each body id of an ids image
bool camera_command(ViewerState& state, const std::string& command, const std::string& rest);
bool print_camera(ViewerState& state, const std::string& what);

/// Opens or closes a window by name; false for an unknown name.
bool set_window(WindowFlags& windows, const std::string& name, bool open);

}  // namespace s2sim::viewer
