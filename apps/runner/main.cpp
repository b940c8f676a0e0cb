// s2sim-run: the headless runner. Loads a scene, holds the --set inputs, steps it for
// --duration seconds, logs and summarises.
#include "camera_video.hpp"
#include "crash_report.hpp"
#include "headless_camera_renderer.hpp"
#include "image_saver.hpp"
#include "options.hpp"
#include "outputs.hpp"
#include "recording.hpp"
#include "scene_search.hpp"
#include "simulation_options.hpp"
#include "watchdog.hpp"

#include <s2sim/kernel/simulation.hpp>
#include <s2sim/version.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <new>
#include <optional>
#include <system_error>
#include <thread>

namespace {

using Clock = std::chrono::steady_clock;

// 2^53: tick counts stay exact as doubles, and far beyond any real run.
constexpr double kMaxTicks = 9007199254740992.0;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

int run(const s2sim::runner::Options& o) {
  using namespace s2sim;
  SimulationOptions options = apps::simulation_options(o);
  for (const auto& c : o.sheet_values) {  // as if Global.S2Sheet had them
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", c.value);
    options.sheet_cells.push_back({c.row, c.col, text});
  }
  if (!o.sheet_values.empty() && options.script_mode == ScriptMode::off)
    throw Error(ErrorKind::usage,
                "--sheet sets cells of the SimTwo script's sheet: not with --no-script");
  // Watching from the load on: a component's configure may hang too.
  std::optional<runner::Watchdog> watchdog;
  if (o.watchdog_s > 0) watchdog.emplace(o.watchdog_s);
  auto sim = Simulation::load(apps::find_scene(o.scene), options);
  sim->set_camera_renderer(render::headless_camera_renderer_factory());
  if (!o.quiet)
    for (const auto& w : sim->warnings())
      std::fprintf(stderr, "warning: %s\n", w.c_str());
  // Not a warning (the results are the same), but why --threads gains less than it could.
  if (!o.quiet && options.threads > 1 && !sim->components_serial_reason().empty())
    std::fprintf(stderr, "note: --threads %d: the components run on the calling thread: %s\n",
                 options.threads, sim->components_serial_reason().c_str());

  if (o.list_signals || o.list_inputs) {
    if (o.list_signals)
      for (std::size_t i = 0; i < sim->signal_count(); ++i)
        std::printf("%s [%s]\n", sim->signal_info(i).name.c_str(),
                    sim->signal_info(i).unit.c_str());
    if (o.list_inputs)
      for (std::size_t i = 0; i < sim->input_count(); ++i)
        std::printf("%s [%s]\n", sim->input_info(i).name.c_str(), sim->input_info(i).unit.c_str());
    return 0;
  }
  for (const auto& [name, value] : o.inputs)
    sim->set_input(name, value);
  for (const auto& c : o.sheet_values) {
    bool found = false;
    const std::string name = "sheet/" + runner::cell_name(c.row, c.col);
    for (std::size_t i = 0; i < sim->input_count() && !found; ++i)
      found = sim->input_info(i).name == name;
    if (!found)
      throw Error(ErrorKind::usage,
                  "--sheet " + std::to_string(c.row) + "," + std::to_string(c.col) +
                      ": no SimTwo script runs, so there is no sheet (the project's control "
                      "block is not \"Script\": add --run-script, or --script FILE)");
  }
  // The SimTwo sheet: a cell's number is the input sheet/<cell>; a button's is its clicks.
  auto sheet_input = [&](int row, int col, const char* option) {
    const std::string name = "sheet/" + runner::cell_name(row, col);
    bool found = false;
    for (std::size_t i = 0; i < sim->input_count() && !found; ++i)
      found = sim->input_info(i).name == name;
    if (!found)
      throw Error(ErrorKind::usage, std::string(option) + " " + std::to_string(row) + "," +
                                        std::to_string(col) + ": the sheet has no cell " +
                                        runner::cell_name(row, col) +
                                        " (cells come from the project's Global.S2Sheet)");
    return sim->input_index(name);
  };
  std::vector<std::pair<std::int64_t, std::size_t>> presses;  // (tick, input), in time order
  for (const auto& p : o.presses)
    presses.emplace_back(std::llround(p.time_s / sim->tick_s()),
                         sheet_input(p.row, p.col, "--press"));
  std::stable_sort(presses.begin(), presses.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::size_t next_press = 0;
  auto apply_presses = [&] {
    for (; next_press < presses.size() && presses[next_press].first <= sim->tick(); ++next_press)
      sim->set_input(presses[next_press].second, sim->input(presses[next_press].second) + 1);
  };

  // llround() of a value beyond int64 is undefined (LLONG_MIN on x86): refuse an endless
  // duration and clamp the log period (a huge one legitimately means "the first row only").
  if (o.duration_s / sim->tick_s() > kMaxTicks) {
    char message[128];
    std::snprintf(message, sizeof message, "--duration: %g s is too many physics steps of %g s",
                  o.duration_s, sim->tick_s());
    throw Error(ErrorKind::usage, message);
  }

  std::optional<runner::CsvLog> log;
  if (!o.log_file.empty()) log.emplace(o.log_file, *sim, o.signal_patterns);
  const double period_ticks =
      o.log_period_s ? std::min(*o.log_period_s / sim->tick_s(), kMaxTicks) : 1.0;
  const std::int64_t log_every = std::max<std::int64_t>(1, std::llround(period_ticks));
  const auto total_ticks = static_cast<std::int64_t>(std::llround(o.duration_s / sim->tick_s()));
  std::optional<apps::RecordingWriter> recording;
  if (!o.record_file.empty())
    recording.emplace(o.record_file, apps::recording_header(*sim, options, log_every));
  auto record_frame = [&] {
    if (!recording) return;
    if (const std::string error = recording->write_frame(*sim); !error.empty())
      throw runner::OutputError(error);
  };
  std::optional<runner::ImageSaver> images;
  if (!o.save_images_dir.empty()) {
    images.emplace(o.save_images_dir, *sim);
    for (const std::string& name : images->skipped())
      std::fprintf(stderr, "s2sim-run: --save-images: '%s' is a point cloud, not saved\n",
                   name.c_str());
  }
  std::optional<runner::CameraVideo> video;
  if (!o.video_file.empty()) video.emplace(o.video_file, *sim, o.video_image);
  runner::ProgressBar progress(!o.quiet && isatty(STDERR_FILENO));
  if (log) log->write_row(*sim);
  record_frame();
  const auto start = Clock::now();
  // Stepping in chunks keeps the clock and the progress bar out of the per-step cost, and
  // lets the parts run ahead over a chunk with --threads (docs/scheduling.md): a hundredth of
  // the run, a thousandth when paced in real time.
  // A SimTwo script may end the run (CloseSimTwo): then the steps go one by one, so that the
  // run stops at the step of the request, its outputs written as at the end. Saved images
  // too, so that no frame is drawn over before it is written.
  const std::optional<std::size_t> close = sim->find_signal("controllers/script/close");
  const std::int64_t chunk =
      close || images || video ? 1
      : log || recording       ? log_every
                               : std::max<std::int64_t>(1, total_ticks / (o.realtime ? 1000 : 100));
  std::int64_t done = 0;
  while (done < total_ticks && !(close && sim->signal(*close) != 0)) {
    apply_presses();
    std::int64_t n = std::min(chunk, total_ticks - done);
    if (next_press < presses.size())
      n = std::max<std::int64_t>(1, std::min(n, presses[next_press].first - sim->tick()));
    sim->step(n);
    if (watchdog) watchdog->progressed(sim->time_s());
    done += n;
    if (log && done % log_every == 0) log->write_row(*sim);
    if (done % log_every == 0) record_frame();
    if (images) images->save_new_frames();
    if (video) video->add_new_frame();
    if (o.realtime) {
      const double ahead = sim->time_s() - seconds_since(start);
      if (ahead > 0) std::this_thread::sleep_for(std::chrono::duration<double>(ahead));
    }
    progress.update(sim->time_s(), o.duration_s, seconds_since(start));
  }
  runner::RunTiming timing{seconds_since(start), done};
  progress.update(sim->time_s(), o.duration_s, timing.wall_s, true);
  progress.finish();
  if (log) log->close();
  if (recording)
    if (const std::string error = recording->close(); !error.empty())
      throw runner::OutputError(error);
  if (video) video->finish();

  if (!o.quiet) std::fputs(runner::summary_text(*sim, timing).c_str(), stdout);
  if (o.check_dynamics) std::fputs(runner::dynamics_check_text(*sim).c_str(), stderr);
  if (!o.summary_file.empty()) {
    std::ofstream out(o.summary_file, std::ios::binary);
    out << runner::summary_json(*sim, timing, o.summary_timing);
    out.close();  // flushes: a write error (full disk) only shows after this
    if (!out) throw runner::OutputError("--summary: cannot write '" + o.summary_file + "'");
  }
  // close 2: the script ended the run with Halt and a non-zero code (its stderr line names
  // it): a failed run, its outputs written.
  if (close && sim->signal(*close) == 2) {
    std::fputs("s2sim-run: error: the script ended the run with a non-zero Halt code\n", stderr);
    return exit_code(ErrorKind::runtime);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  s2sim::runner::install_crash_report();
  try {
    const auto options = s2sim::runner::parse_options(argc, argv);
    if (options.help) {
      std::fputs(s2sim::runner::usage_text(), stdout);
      return 0;
    }
    if (options.version) {
      std::printf("s2sim-run %s (SDK %s, plugin ABI %d)\n", s2sim::kSdkVersionString,
                  s2sim::kSdkVersionString, S2SIM_PLUGIN_ABI_VERSION);
      return 0;
    }
    return run(options);
  } catch (const s2sim::Error& e) {
    std::fprintf(stderr, "s2sim-run: error: %s\n", e.what());
    return s2sim::exit_code(e.kind());
  } catch (const s2sim::runner::OutputError& e) {
    std::fprintf(stderr, "s2sim-run: error: %s\n", e.what());
    return s2sim::runner::kExitOutputFailed;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "s2sim-run: error: %s\n", s2sim::apps::kOutOfMemoryText);
    return s2sim::apps::kExitCannotGoOn;
  } catch (const std::system_error& e) {
    std::fprintf(stderr, "s2sim-run: error: %s: %s\n", s2sim::apps::kResourceRefusedText, e.what());
    return s2sim::apps::kExitCannotGoOn;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "s2sim-run: internal error: %s\n", e.what());
    return s2sim::apps::kExitCannotGoOn;
  }
}
