#include "options.hpp"

#include <s2sim/error.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace s2sim::viewer {
namespace {

double parse_double(const std::string& option, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v))
    throw Error(ErrorKind::usage, option + ": '" + text + "' is not a number");
  return v;
}

int parse_int(const std::string& option, const std::string& text, int min) {
  const double v = parse_double(option, text);
  if (v != static_cast<int>(v) || v < min)
    throw Error(ErrorKind::usage,
                option + ": '" + text + "' is not a whole number >= " + std::to_string(min));
  return static_cast<int>(v);
}

std::pair<std::string, double> parse_assignment(const std::string& option,
                                                const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw Error(ErrorKind::usage, option + ": '" + text + "' is not NAME=VALUE");
  return {text.substr(0, eq), parse_double(option, text.substr(eq + 1))};
}

}  // namespace

const char* usage_text() {
  return R"(usage: s2sim-view SCENE [options]
  SCENE                    a scene folder or its scene.xml, or a URDF, SDF or MJCF robot;
                           a bare name (default) is also looked up in the install's scenes
  --replay FILE            play a recording of s2sim-run --record (SCENE: the recorded one
                           unless given); a timeline scrubs it (docs/recording.md)
  --video FILE.mp4         with --replay: write the replay as an MP4 video, then quit
  --video-fps N            frames per second of the video, 1 to 240 (30)
  --seed N                 seed of every random stream (1)
  --physics-step S         physics step, seconds    --substeps N
  --define NAME=VALUE      constant set before scene.xml is read
  --set INPUT=VALUE        hold an input at a value
  --plugin-path DIR        plugin folder searched first (repeatable)
  --model-path DIR         folder for package:// and model:// URIs (repeatable)
  --size WxH               window size in pixels (1280x720)
  --speed X                times real time, 0.1 to 1000; 0 = as fast as possible (1)
  --paused                 start paused
  --chart SIGNAL...        signals to chart (patterns, as s2sim-run --signals)
  --chart-span S           simulated seconds of history the chart keeps, 1 to 3600 (60)
  --script-file FILE       run this SimTwo script instead of the one the project names
  --run-script             run the project's SimTwo script even when its control block is not
                           "Script"
  --no-script              do not run the project's SimTwo script
  --sheet R,C=VALUE        set SimTwo's sheet cell (row R, column C, from 1) before the start
  --show-window NAME       open a window: run, configuration, chart, sheet, editor, script,
                           log, body, cameras
  --hide-ui                world view only
  --no-shadows             no shadows (faster on a machine without a GPU)
  --look fast|full         full: 4x anti-aliasing, shadows on bodies (shadow map); fast: none,
                           shadows on the floor only (default: full, but fast on a software
                           rasteriser such as llvmpipe outside screenshot runs)
  --msaa N                 samples per pixel of the 3-D view, 0 = no anti-aliasing
  --font-scale X           text and widgets X times their size, 0.5 to 4 (HiDPI screens)
  --screenshot FILE.png    write the last frame, then quit (with --frames N, default 3)
  --frames N               quit after N frames
  --watchdog S             with --frames, a UI script or --video: quit (exit 8) when one
                           call into a component lasts longer than S seconds of wall time,
                           naming it (default 120; 0: never). A window that is used by hand
                           shows such a call and offers to stop the simulation instead
  --do "COMMAND"           a UI script command (repeatable, see docs/viewer.md)
  --script FILE            UI script commands, one a line
  --no-frame-cap           draw as fast as possible (benchmark)
  --report-fps             print the frame rate at exit
  --print-projections      print where each robot and its shadow are on screen
)";
}

Options parse_options(int argc, char** argv) {
  Options o;
  auto value = [&](int& i, const std::string& option) -> std::string {
    if (i + 1 >= argc) throw Error(ErrorKind::usage, option + ": missing value");
    return argv[++i];
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--seed") {
      o.load_option = a;
      o.seed = static_cast<std::uint64_t>(parse_int(a, value(i, a), 0));
    } else if (a == "--physics-step") {
      o.load_option = a;
      o.physics_step_s = parse_double(a, value(i, a));
      if (*o.physics_step_s <= 0) throw Error(ErrorKind::usage, a + ": must be positive");
    } else if (a == "--substeps") {
      o.load_option = a;
      o.substeps = parse_int(a, value(i, a), 1);
    } else if (a == "--define") {
      o.load_option = a;
      o.constants.push_back(parse_assignment(a, value(i, a)));
    } else if (a == "--set") {
      o.load_option = a;
      o.inputs.push_back(parse_assignment(a, value(i, a)));
    } else if (a == "--plugin-path") {
      o.plugin_path.push_back(value(i, a));
    } else if (a == "--model-path") {
      o.model_path.push_back(value(i, a));
    } else if (a == "--size") {
      const std::string v = value(i, a);
      const auto x = v.find('x');
      if (x == std::string::npos) throw Error(ErrorKind::usage, a + ": '" + v + "' is not WxH");
      o.width_px = parse_int(a, v.substr(0, x), 64);
      o.height_px = parse_int(a, v.substr(x + 1), 64);
    } else if (a == "--speed") {
      o.speed = parse_double(a, value(i, a));
      if (o.speed != 0 && (o.speed < 0.1 || o.speed > 1000))
        throw Error(ErrorKind::usage, a + ": must be 0 (as fast as possible) or 0.1 to 1000");
    } else if (a == "--paused") {
      o.paused = true;
    } else if (a == "--chart") {
      while (i + 1 < argc && argv[i + 1][0] != '-')
        o.chart_signals.emplace_back(argv[++i]);
      if (o.chart_signals.empty()) throw Error(ErrorKind::usage, a + ": missing signal");
    } else if (a == "--chart-span") {
      o.chart_span_s = parse_double(a, value(i, a));
      if (!(o.chart_span_s >= 1 && o.chart_span_s <= 3600))
        throw Error(ErrorKind::usage, a + ": must be 1 to 3600 seconds");
    } else if (a == "--script-file") {
      o.load_option = a;
      o.script_file = value(i, a);
    } else if (a == "--sheet") {
      o.load_option = a;
      const std::string v = value(i, a);
      int row = 0, col = 0, used = 0;
      if (std::sscanf(v.c_str(), "%d,%d=%n", &row, &col, &used) != 2 || used == 0 || row < 1 ||
          col < 1)
        throw Error(ErrorKind::usage, a + ": expected ROW,COLUMN=VALUE (from 1), got '" + v + "'");
      char text[40];
      std::snprintf(text, sizeof text, "%.17g",
                    parse_double(a, v.substr(static_cast<std::size_t>(used))));
      o.sheet_cells.push_back({row, col, text});
    } else if (a == "--run-script") {
      o.load_option = a;
      o.script_mode = ScriptMode::always;
    } else if (a == "--no-script") {
      o.load_option = a;
      o.script_mode = ScriptMode::off;
    } else if (a == "--show-window") {
      o.show_windows.push_back(value(i, a));
    } else if (a == "--font-scale") {
      o.font_scale = parse_double(a, value(i, a));
      if (o.font_scale < 0.5 || o.font_scale > 4)
        throw Error(ErrorKind::usage, a + ": must be 0.5 to 4");
    } else if (a == "--no-shadows") {
      o.shadows = false;
    } else if (a == "--look") {
      const std::string v = value(i, a);
      if (v != "fast" && v != "full") throw Error(ErrorKind::usage, a + ": must be fast or full");
      o.look = v == "full" ? 1 : 0;
    } else if (a == "--msaa") {
      o.msaa_samples = parse_int(a, value(i, a), 0);
      if (o.msaa_samples > 16) throw Error(ErrorKind::usage, a + ": must be 0 to 16");
    } else if (a == "--hide-ui") {
      o.hide_ui = true;
    } else if (a == "--screenshot") {
      o.screenshot_file = value(i, a);
    } else if (a == "--frames") {
      o.frames = parse_int(a, value(i, a), 1);
    } else if (a == "--watchdog") {
      o.watchdog_s = parse_double(a, value(i, a));
      if (!(o.watchdog_s >= 0) || !std::isfinite(o.watchdog_s))
        throw Error(ErrorKind::usage, a + ": must be a finite number of seconds >= 0 (0: never)");
    } else if (a == "--do") {
      o.script.push_back(value(i, a));
    } else if (a == "--script") {
      const std::string file = value(i, a);
      std::ifstream in(file);
      if (!in) throw Error(ErrorKind::usage, a + ": cannot read '" + file + "'");
      for (std::string line; std::getline(in, line);)
        if (!line.empty() && line[0] != '#') o.script.push_back(line);
    } else if (a == "--replay") {
      o.replay_file = value(i, a);
    } else if (a == "--video") {
      o.video_file = value(i, a);
    } else if (a == "--video-fps") {
      o.video_fps = parse_int(a, value(i, a), 1);
      if (o.video_fps > 240) throw Error(ErrorKind::usage, a + ": must be 1 to 240");
    } else if (a == "--no-frame-cap") {
      o.no_frame_cap = true;
    } else if (a == "--report-fps") {
      o.report_fps = true;
    } else if (a == "--print-projections") {
      o.print_projections = true;
    } else if (!a.empty() && a[0] == '-') {
      throw Error(ErrorKind::usage, "unknown option '" + a + "' (see --help)");
    } else if (o.scene.empty()) {
      o.scene = a;
    } else {
      throw Error(ErrorKind::usage, "more than one scene: '" + o.scene + "' and '" + a + "'");
    }
  }
  if (!o.help && o.scene.empty() && o.replay_file.empty())
    throw Error(ErrorKind::usage, "no scene given (see --help)");
  if (!o.replay_file.empty() && !o.load_option.empty())
    throw Error(ErrorKind::usage,
                "--replay with " + o.load_option + ": the recording says how its scene is loaded");
  if (!o.video_file.empty() && o.replay_file.empty())
    throw Error(ErrorKind::usage, "--video writes a replay: it needs --replay FILE");
  if (!o.screenshot_file.empty() && o.frames < 0) o.frames = 3;
  if (o.script_mode == ScriptMode::off && !o.script_file.empty())
    throw Error(ErrorKind::usage, "--script-file and --no-script contradict each other");
  if (!o.script_file.empty() && o.script_mode == ScriptMode::control_block)
    o.script_mode = ScriptMode::always;
  return o;
}

}  // namespace s2sim::viewer
