// s2sim-bench: wall-clock cost of stepping scenes through the façade, no logging. For each
// scene: load, warm up, then time `--duration` simulated seconds; repeat and keep the best
// run (the least disturbed by the rest of the machine).

#include <s2sim/error.hpp>
#include <s2sim/kernel/simulation.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <thread>
#include <vector>

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int kUsageExit = 4;

const char* const kUsage = R"(Usage: s2sim-bench [SCENE...] [options]
Times stepping each scene (a folder or its scene.xml) without logging and prints the
real-time factor. Default scenes: every folder of <repo>/scenes with a scene.xml, then those
of <repo>/../shared/simtwo-scenes when it exists.

Options:
  --duration S   simulated seconds timed per repeat (default 10)
  --warmup S     simulated seconds stepped before timing (default 0.5)
  --repeats N    timed repeats; the best is reported (default 3)
  --set I=V      hold input I at V (e.g. a motor voltage, to time a robot that drives);
                 repeatable; every scene must have the input
  --json FILE    also write the results as JSON
  --threads N    step each scene's islands on N threads (SimulationOptions::threads)
  --script       run each scene's SimTwo script when its project starts it, as s2sim-run
                 does (the script's compile is not timed; default: physics only)
  --profile      after the timed repeats, one more run with per-stage timing: wall time per
                 tick pipeline stage (sense ... read out, docs/architecture.md) in us/step
  --help
)";

struct Options {
  std::vector<fs::path> scenes;
  double duration_s = 10;
  double warmup_s = 0.5;
  int repeats = 3;
  std::string json_file;
  std::vector<std::pair<std::string, double>> inputs;  ///< --set
  bool profile = false;
  int threads = 1;      ///< --threads
  bool script = false;  ///< --script
};

struct Result {
  std::string scene;
  fs::path path;
  int bodies = 0;
  std::size_t axes = 0;
  double step_s = 0;
  std::int64_t steps = 0;
  double wall_s = 0;                                 ///< best of the repeats
  std::vector<s2sim::Simulation::StageTime> stages;  ///< --profile
  std::string components_serial;  ///< --threads > 1: why the components run serially
};

[[noreturn]] void usage_error(const std::string& message) {
  std::fprintf(stderr, "s2sim-bench: error: %s (see s2sim-bench --help)\n", message.c_str());
  std::exit(kUsageExit);
}

double parse_number(const std::string& option, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
    usage_error(option + ": '" + text + "' is not a number");
  return v;
}

/// Scene folders (those with a scene.xml) directly under `root`, sorted by name.
std::vector<fs::path> scene_folders(const fs::path& root) {
  std::vector<fs::path> found;
  std::error_code ec;
  if (!fs::is_directory(root, ec)) return found;
  for (const auto& entry : fs::directory_iterator(root, ec))
    if (entry.is_directory() && fs::exists(entry.path() / "scene.xml"))
      found.push_back(entry.path());
  std::sort(found.begin(), found.end());
  return found;
}

Options parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--duration") {
      o.duration_s = parse_number(a, value());
      if (!(o.duration_s > 0)) usage_error("--duration must be positive");
    } else if (a == "--warmup") {
      o.warmup_s = parse_number(a, value());
      if (o.warmup_s < 0) usage_error("--warmup must not be negative");
    } else if (a == "--repeats") {
      const double n = parse_number(a, value());
      if (n < 1 || n > 1000 || n != std::floor(n)) usage_error("--repeats must be 1 to 1000");
      o.repeats = static_cast<int>(n);
    } else if (a == "--json") {
      o.json_file = value();
    } else if (a == "--set") {
      const std::string v = value();
      const auto eq = v.find('=');
      if (eq == std::string::npos || eq == 0)
        usage_error("--set needs INPUT=VALUE, got '" + v + "'");
      o.inputs.emplace_back(v.substr(0, eq),
                            parse_number("--set " + v.substr(0, eq), v.substr(eq + 1)));
    } else if (a == "--threads") {
      const double n = parse_number(a, value());
      if (n < 1 || n > 64 || n != std::floor(n)) usage_error("--threads must be 1 to 64");
      o.threads = static_cast<int>(n);
    } else if (a == "--profile") {
      o.profile = true;
    } else if (a == "--script") {
      o.script = true;
    } else if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (a.size() > 1 && a[0] == '-') {
      usage_error("unknown option '" + a + "'");
    } else {
      o.scenes.emplace_back(a);
    }
  }
  if (o.scenes.empty()) {
    const fs::path repo = S2SIM_SOURCE_DIR;
    for (const auto& s : scene_folders(repo / "scenes"))
      o.scenes.push_back(s);
    for (const auto& s :
         scene_folders((repo / ".." / "shared" / "simtwo-scenes").lexically_normal()))
      o.scenes.push_back(s);
    if (o.scenes.empty()) usage_error("no scene given and none found under " + repo.string());
  }
  return o;
}

/// "parent/folder": the repo and the shared scenes both have a `default`.
std::string scene_name(const fs::path& p) {
  fs::path folder = fs::absolute(p).lexically_normal();
  if (!folder.has_filename()) folder = folder.parent_path();  // a trailing slash
  if (folder.filename() == "scene.xml") folder = folder.parent_path();
  return (folder.parent_path().filename() / folder.filename()).string();
}

Result measure(const fs::path& path, const Options& o) {
  s2sim::SimulationOptions options;
  options.threads = o.threads;
  if (o.script) options.script_mode = s2sim::ScriptMode::control_block;
  auto sim = s2sim::Simulation::load(path, options);
  Result r;
  r.scene = scene_name(path);
  r.path = path;
  r.bodies = sim->body_count() - 1;  // body 0 is the world
  r.axes = sim->axis_count();
  r.step_s = sim->tick_s();
  if (o.threads > 1) r.components_serial = sim->components_serial_reason();
  // llround() beyond int64 is undefined; 2^53 steps is far beyond any benchmark anyway.
  if ((o.duration_s + o.warmup_s) / r.step_s > 9007199254740992.0)
    throw s2sim::Error(s2sim::ErrorKind::usage, "--duration/--warmup: too many physics steps");
  r.steps = std::max<std::int64_t>(1, std::llround(o.duration_s / r.step_s));
  const auto warmup = std::llround(o.warmup_s / r.step_s);
  r.wall_s = std::numeric_limits<double>::infinity();
  for (int i = 0; i < o.repeats; ++i) {
    // reset() repeats a run bit for bit, so every repeat times the same work.
    if (i > 0) sim->reset();
    for (const auto& [name, value] : o.inputs)  // reset() restores the inputs too
      sim->set_input(name, value);
    sim->step(warmup);
    const auto start = Clock::now();
    sim->step(r.steps);
    r.wall_s = std::min(r.wall_s, std::chrono::duration<double>(Clock::now() - start).count());
  }
  if (o.profile) {  // a separate run: the clock reads must not weigh on the timed ones
    sim->reset();
    for (const auto& [name, value] : o.inputs)
      sim->set_input(name, value);
    sim->step(warmup);
    sim->set_profiling(true);
    sim->step(r.steps);
    r.stages = sim->stage_times();
    sim->set_profiling(false);
  }
  return r;
}

double us_per_step(const Result& r) {
  return r.wall_s * 1e6 / static_cast<double>(r.steps);
}
double rtf(const Result& r) {
  return static_cast<double>(r.steps) * r.step_s / r.wall_s;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char esc[8];
      std::snprintf(esc, sizeof esc, "\\u%04x", c);
      out += esc;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string number(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

void write_json(const std::string& file, const Options& o, const std::vector<Result>& results) {
  // Strings are appended, not formatted into a fixed buffer: a long path must not truncate.
  std::string s = "{\n  \"duration_s\": " + number("%g", o.duration_s) +
                  ",\n  \"warmup_s\": " + number("%g", o.warmup_s) +
                  ",\n  \"repeats\": " + std::to_string(o.repeats) + ",\n  \"hardware_threads\": " +
                  std::to_string(std::thread::hardware_concurrency()) + ",\n  \"results\": [";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const Result& r = results[i];
    s += i ? ",\n    " : "\n    ";
    s += "{\"scene\": " + json_string(r.scene) + ", \"path\": " + json_string(r.path.string()) +
         ", \"bodies\": " + std::to_string(r.bodies) + ", \"axes\": " + std::to_string(r.axes) +
         ", \"physics_step_s\": " + number("%g", r.step_s) +
         ", \"steps\": " + std::to_string(r.steps) +
         ", \"wall_ms\": " + number("%.3f", r.wall_s * 1e3) +
         ", \"us_per_step\": " + number("%.3f", us_per_step(r)) +
         ", \"rtf\": " + number("%.2f", rtf(r)) + "}";
  }
  s += results.empty() ? "]\n}\n" : "\n  ]\n}\n";
  std::ofstream out(file, std::ios::binary);
  out << s;
  out.close();
  if (!out) {
    std::fprintf(stderr, "s2sim-bench: error: --json: cannot write '%s'\n", file.c_str());
    std::exit(kUsageExit);
  }
}

void print_profile(const Result& r) {
  double total = 0;
  for (const auto& s : r.stages)
    total += s.seconds;
  const auto steps = static_cast<double>(r.steps);
  std::printf("  %-16s %10s %9s %7s\n", "stage", "calls/step", "us/step", "share");
  for (const auto& s : r.stages)
    std::printf("  %-16s %10.2f %9.3f %6.1f%%\n", s.stage.c_str(),
                static_cast<double>(s.calls) / steps, s.seconds * 1e6 / steps,
                total > 0 ? 100 * s.seconds / total : 0.0);
  std::printf("  %-16s %10s %9.3f  (with the profiler's own clock reads)\n", "total", "",
              total * 1e6 / steps);
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse_options(argc, argv);
  std::printf("%g s simulated per run after %g s warm-up, best of %d, %u hardware threads\n\n",
              o.duration_s, o.warmup_s, o.repeats, std::thread::hardware_concurrency());
  std::printf("%-32s %7s %5s %9s %10s %9s %9s\n", "scene", "bodies", "axes", "step[ms]", "wall[ms]",
              "us/step", "RTF");
  std::vector<Result> results;
  int status = 0;
  for (const auto& path : o.scenes) {
    try {
      const Result r = measure(path, o);
      std::printf("%-32s %7d %5zu %9g %10.1f %9.2f %9.1f\n", r.scene.c_str(), r.bodies, r.axes,
                  r.step_s * 1e3, r.wall_s * 1e3, us_per_step(r), rtf(r));
      if (o.threads > 1)
        std::printf("  components: %s\n",
                    r.components_serial.empty()
                        ? "in the parts, on their threads"
                        : ("on the calling thread: " + r.components_serial).c_str());
      if (o.profile) print_profile(r);
      std::fflush(stdout);
      results.push_back(r);
    } catch (const s2sim::Error& e) {
      // One bad scene should not hide the numbers of the others; the exit code still tells.
      std::fprintf(stderr, "s2sim-bench: error: %s\n", e.what());
      if (status == 0) status = s2sim::exit_code(e.kind());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "s2sim-bench: internal error: %s\n", e.what());
      if (status == 0) status = 1;
    }
  }
  if (!o.json_file.empty()) write_json(o.json_file, o, results);
  return status;
}
