// s2sim-run: the headless runner. Loads a scene, holds the --set inputs, steps it for
// --duration seconds, logs and summarises.
#include "crash_report.hpp"
#include "options.hpp"
#include "outputs.hpp"
#include "simulation_options.hpp"

#include <s2sim/kernel/simulation.hpp>
#include <s2sim/version.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
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
  auto sim = Simulation::load(o.scene, apps::simulation_options(o));
  if (!o.quiet)
    for (const auto& w : sim->warnings())
      std::fprintf(stderr, "warning: %s\n", w.c_str());

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
  runner::ProgressBar progress(!o.quiet && isatty(STDERR_FILENO));
  if (log) log->write_row(*sim);
  const auto start = Clock::now();
  // Stepping in chunks keeps the clock and the progress bar out of the per-step cost.
  const std::int64_t chunk = log ? log_every : std::max<std::int64_t>(1, total_ticks / 1000);
  std::int64_t done = 0;
  while (done < total_ticks) {
    const std::int64_t n = std::min(chunk, total_ticks - done);
    sim->step(n);
    done += n;
    if (log && done % log_every == 0) log->write_row(*sim);
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

  if (!o.quiet) std::fputs(runner::summary_text(*sim, timing).c_str(), stdout);
  if (!o.summary_file.empty()) {
    std::ofstream out(o.summary_file, std::ios::binary);
    out << runner::summary_json(*sim, timing, o.summary_timing);
    out.close();  // flushes: a write error (full disk) only shows after this
    if (!out) throw runner::OutputError("--summary: cannot write '" + o.summary_file + "'");
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
  } catch (const std::exception& e) {
    std::fprintf(stderr, "s2sim-run: internal error: %s\n", e.what());
    return 1;
  }
}
