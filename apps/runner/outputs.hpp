#pragma once
/// \file
/// What s2sim-run writes: the CSV log, the final summary (terminal and JSON), the progress bar.

#include "exit_codes.hpp"

#include <s2sim/kernel/simulation.hpp>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace s2sim::runner {

using apps::kExitComponentCrashed;  // a fatal signal (crash_report.hpp)
using apps::kExitComponentExited;   // a component called exit() (crash_report.hpp)
using apps::kExitOutputFailed;      // --log or --summary could not be written
using apps::kExitWatchdog;          // one call into a component outlasted --watchdog

/// An output file could not be written (a full disk, a lost mount): not the simulation's
/// failure, so not exit 5.
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A CSV file with a header `name [unit]` and one row per logged tick, in the format of
/// apps/common/signal_csv.hpp. Rows go through a reused buffer: no allocation per row. The first
/// column is always `time [s]`; every other signal appears at most once.
class CsvLog {
 public:
  /// Throws s2sim::Error (usage) when the file cannot be written or a pattern matches nothing.
  CsvLog(const std::string& file, const Simulation& sim, const std::vector<std::string>& patterns);
  ~CsvLog();
  CsvLog(const CsvLog&) = delete;
  CsvLog& operator=(const CsvLog&) = delete;
  /// Writes one row and hands it to the system: a crash later (crash_report.hpp) leaves every
  /// complete row in the file. Throws OutputError when it cannot be written.
  void write_row(const Simulation& sim);
  /// Closes the file. Throws OutputError when the last rows could not be written.
  void close();

 private:
  std::FILE* out_ = nullptr;
  std::string path_;
  std::vector<std::size_t> signals_;
  std::vector<double> row_;  ///< reused for every row
};

struct RunTiming {
  double wall_s = 0;
  std::int64_t steps = 0;
};

/// The summary as text for the terminal.
std::string summary_text(const Simulation& sim, const RunTiming& timing);
/// The dynamics check's one line (--check-dynamics), for stderr.
std::string dynamics_check_text(const Simulation& sim);
/// The summary as JSON: sim_time, wall_time, rtf, steps, robots, things, axes.
std::string summary_json(const Simulation& sim, const RunTiming& timing, bool with_timing);

/// A one-line progress bar on a terminal (stderr), redrawn at most ten times a second.
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled) {}
  /// Redraws when 0.1 s of wall time has passed since the last draw, or when `force`.
  void update(double sim_s, double total_s, double wall_s, bool force = false);
  void finish();

 private:
  bool enabled_;
  double last_draw_wall_s_ = -1;
};

}  // namespace s2sim::runner
