#include "options.hpp"

#include <s2sim/error.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>
#include <string_view>
#include <thread>

namespace s2sim::runner {
namespace {

Error usage_error(const std::string& message) {
  return Error(ErrorKind::usage, message + " (see s2sim-run --help)");
}

double parse_number(std::string_view option, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v))
    throw usage_error(std::string(option) + ": '" + text + "' is not a number");
  return v;
}

std::pair<std::string, double> parse_assignment(std::string_view option, const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw usage_error(std::string(option) + ": expected NAME=VALUE, got '" + text + "'");
  return {text.substr(0, eq), parse_number(option, text.substr(eq + 1))};
}

/// "R,C" with 1-based integers (SimTwo's sheet rows and columns).
std::pair<int, int> parse_cell(std::string_view option, const std::string& text) {
  const auto comma = text.find(',');
  auto integer = [&](const std::string& part) {
    char* end = nullptr;
    const long v = std::strtol(part.c_str(), &end, 10);
    if (part.empty() || end != part.c_str() + part.size() || v < 1 || v > 100000)
      throw usage_error(std::string(option) + ": '" + text +
                        "' is not ROW,COLUMN with integers from 1 (SimTwo's sheet numbering)");
    return static_cast<int>(v);
  };
  if (comma == std::string::npos)
    throw usage_error(std::string(option) + ": expected ROW,COLUMN, got '" + text + "'");
  return {integer(text.substr(0, comma)), integer(text.substr(comma + 1))};
}

}  // namespace

const char* usage_text() {
  return R"(Usage: s2sim-run SCENE [options]
Runs a SimTwo/S2Sim scene headless. SCENE is a scene folder or its scene.xml, or a robot
file in URDF (.urdf), SDF (.sdf) or MJCF (.xml with a <mujoco> root), run on the floor.

Options:
  --duration S         simulated seconds to run (default 10)
  --realtime           pace the run to the wall clock
  --fast               run as fast as possible (default)
  --log FILE.csv       write signals to a CSV file (header: name [unit])
  --signals PATTERN... signals to log, glob patterns (* and ?); default: all (needs --log)
  --log-period S       seconds between CSV rows and recorded frames (default: every
                       physics step; needs --log or --record)
  --record FILE        record the whole state at every log period (docs/recording.md):
                       s2sim-view --replay FILE plays it, s2sim.recording reads it
  --save-images DIR    write every frame of every image (cameras, lidars) as
                       DIR/<image name>/<frame>.png (docs/models/sensors.md, "Cameras")
  --video FILE.mp4     write a camera's colour frames as a video, at the camera's rate
  --video-image NAME   the camera image --video writes (default: the scene's only one),
                       e.g. robots/r/sensors/front/rgb
  --summary FILE.json  write the final summary as JSON
  --no-timing          leave wall_time and rtf out of the JSON (byte-identical reruns)
  --seed N             seed of every random stream (default 1)
  --set INPUT=VALUE... hold an input for the whole run, e.g.
                       --set robots/arm/axes/J1/ref_torque=0.5
  --define NAME=VALUE  a constant defined before scene.xml is read
  --watchdog S         stop the run (exit 8) when one call into a component lasts longer
                       than S seconds of wall time, naming it (default 120; 0: never)
  --physics-step S     override the physics step (seconds)
  --substeps N         override the physics substeps per step
  --threads N          step the scene's islands (robots not jointed to each other) on N
                       threads, 1 to the machine's hardware threads (default 1); the
                       results are the same for every N (a note says when the components
                       cannot run on their islands' threads, and why)
  --simbody-dynamics   Simbody's realize chain for every system, not the small-tree
                       dynamics (the same dynamics to rounding, slower): the reference
  --check-dynamics     step on the small-tree dynamics and have Simbody compute the same
                       accelerations at every substep: a difference beyond the agreement
                       stops the run (exit 5); the largest and the agreement are printed
                       at the end (the results are the unchecked run's, bit for bit)
  --plugin-path DIR    search DIR for plugins before the default folders (repeatable;
                       the first library on the path that provides a kind wins)
  --no-default-plugin-path
                       search only the --plugin-path folders
  --model-path DIR     search DIR for package:// and model:// URIs before
                       S2SIM_MODEL_PATH, ROS_PACKAGE_PATH, GZ_SIM_RESOURCE_PATH (repeatable)
  --script FILE        run this SimTwo script instead of the one the project names
  --run-script         run the project's script even when its control block is not
                       "Script" (SimTwo's Run)
  --no-script          do not run the project's script
  --press R,C[@S]...   click the sheet button at row R, column C (1-based) at S seconds
                       (default 0), e.g. --press 11,3@0.5
  --sheet R,C=VALUE... set the number of sheet cell (R, C) before the first step
  --list-signals       print every signal with its unit and exit
  --list-inputs        print every input with its unit and exit
  --quiet              no progress bar, no summary on the terminal
  --version, --help

Exit codes: 0 ok, 1 internal error, 2 bad scene, 3 plugin error, 4 bad usage
(unknown signal or input, bad option), 5 the simulation failed (non-finite state),
6 --log, --record, --save-images, --video or --summary could not be written, 7 a fatal signal (the component is
named).
)";
}

Options parse_options(int argc, char** argv) {
  Options o;
  std::vector<std::string> args(argv + 1, argv + argc);
  auto is_option = [](const std::string& a) { return a.size() > 2 && a[0] == '-' && a[1] == '-'; };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size() || is_option(args[i + 1])) throw usage_error(a + " needs a value");
      return args[++i];
    };
    // Options that take several values read until the next option.
    auto values = [&](std::vector<std::string>& out) {
      if (i + 1 >= args.size() || is_option(args[i + 1]))
        throw usage_error(a + " needs at least one value");
      while (i + 1 < args.size() && !is_option(args[i + 1]))
        out.push_back(args[++i]);
    };
    if (a == "--duration") {
      o.duration_s = parse_number(a, value());
      if (o.duration_s < 0) throw usage_error("--duration must not be negative");
    } else if (a == "--realtime") {
      o.realtime = true;
    } else if (a == "--fast") {
      o.realtime = false;
    } else if (a == "--log") {
      o.log_file = value();
    } else if (a == "--record") {
      o.record_file = value();
    } else if (a == "--save-images") {
      o.save_images_dir = value();
    } else if (a == "--video") {
      o.video_file = value();
    } else if (a == "--video-image") {
      o.video_image = value();
    } else if (a == "--signals") {
      values(o.signal_patterns);
    } else if (a == "--log-period") {
      o.log_period_s = parse_number(a, value());
      if (!(*o.log_period_s > 0)) throw usage_error("--log-period must be positive");
    } else if (a == "--summary") {
      o.summary_file = value();
    } else if (a == "--no-timing") {
      o.summary_timing = false;
    } else if (a == "--seed") {
      const std::string& v = value();
      char* end = nullptr;
      errno = 0;
      o.seed = std::strtoull(v.c_str(), &end, 10);
      if (v.empty() || v[0] == '-' || end != v.c_str() + v.size() || errno == ERANGE)
        throw usage_error("--seed: '" + v + "' is not a non-negative integer");
    } else if (a == "--set") {
      std::vector<std::string> sets;
      values(sets);
      for (const auto& s : sets)
        o.inputs.push_back(parse_assignment(a, s));
    } else if (a == "--define") {
      o.constants.push_back(parse_assignment(a, value()));
    } else if (a == "--watchdog") {
      o.watchdog_s = parse_number(a, value());
      if (!(o.watchdog_s >= 0) || !std::isfinite(o.watchdog_s))
        throw usage_error("--watchdog must be a finite number of seconds >= 0 (0: never)");
    } else if (a == "--physics-step") {
      o.physics_step_s = parse_number(a, value());
      if (!(*o.physics_step_s > 0)) throw usage_error("--physics-step must be positive");
    } else if (a == "--substeps") {
      const double n = parse_number(a, value());
      if (n < 1 || n != std::floor(n) || n > 1000)
        throw usage_error("--substeps must be an integer from 1 to 1000");
      o.substeps = static_cast<int>(n);
    } else if (a == "--threads") {
      const std::string& v = value();
      const int hardware = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
      const double n = parse_number(a, v);
      if (n < 1 || n != std::floor(n) || n > hardware)
        throw usage_error("--threads must be an integer from 1 to " + std::to_string(hardware) +
                          " (this machine's hardware threads), got '" + v + "'");
      o.threads = static_cast<int>(n);
    } else if (a == "--simbody-dynamics") {
      o.simbody_dynamics_only = true;
    } else if (a == "--check-dynamics") {
      o.check_dynamics = true;
    } else if (a == "--plugin-path") {
      o.plugin_path.push_back(value());
    } else if (a == "--model-path") {
      o.model_path.push_back(value());
    } else if (a == "--no-default-plugin-path") {
      o.default_plugin_path = false;
    } else if (a == "--script") {
      o.script_file = value();
    } else if (a == "--run-script") {
      o.script_mode = ScriptMode::always;
    } else if (a == "--no-script") {
      o.script_mode = ScriptMode::off;
    } else if (a == "--press") {
      std::vector<std::string> presses;
      values(presses);
      for (const auto& p : presses) {
        const auto at = p.find('@');
        const auto [row, col] = parse_cell(a, p.substr(0, at));
        double t = 0;
        if (at != std::string::npos) {
          t = parse_number(a, p.substr(at + 1));
          if (t < 0) throw usage_error("--press: the time in '" + p + "' must not be negative");
        }
        o.presses.push_back({row, col, t});
      }
    } else if (a == "--sheet") {
      std::vector<std::string> cells;
      values(cells);
      for (const auto& c : cells) {
        const auto eq = c.find('=');
        if (eq == std::string::npos)
          throw usage_error("--sheet: expected ROW,COLUMN=VALUE, got '" + c + "'");
        const auto [row, col] = parse_cell(a, c.substr(0, eq));
        o.sheet_values.push_back({row, col, parse_number(a, c.substr(eq + 1))});
      }
    } else if (a == "--quiet") {
      o.quiet = true;
    } else if (a == "--list-signals") {
      o.list_signals = true;
    } else if (a == "--list-inputs") {
      o.list_inputs = true;
    } else if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--version") {
      o.version = true;
    } else if (is_option(a) || (a.size() > 1 && a[0] == '-')) {
      throw usage_error("unknown option '" + a + "'");
    } else if (o.scene.empty()) {
      o.scene = a;
    } else {
      throw usage_error("unexpected argument '" + a + "' (the scene is already '" + o.scene + "')");
    }
  }
  if (o.scene.empty() && !o.help && !o.version) throw usage_error("no scene given");
  if (o.script_mode == ScriptMode::off && !o.script_file.empty())
    throw usage_error("--script and --no-script contradict each other");
  if (!o.script_file.empty() && o.script_mode == ScriptMode::control_block)
    o.script_mode = ScriptMode::always;
  // Both only shape the CSV: without --log they would be silently ignored (and a misspelt
  // --signals pattern never reported).
  if (o.log_file.empty() && !o.help && !o.version) {
    if (!o.signal_patterns.empty()) throw usage_error("--signals selects the columns of --log");
    if (o.log_period_s && o.record_file.empty())
      throw usage_error("--log-period sets the rows of --log and the frames of --record");
  }
  if (!o.video_image.empty() && o.video_file.empty())
    throw usage_error("--video-image chooses the camera image of --video");
  return o;
}

}  // namespace s2sim::runner
