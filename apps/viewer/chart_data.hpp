#pragma once
/// \file
/// The chart's recorded samples: the chosen signals read after every tick, so that an
/// exported CSV has exactly the rows of `s2sim-run --log` (same times, same formatting).

#include <s2sim/kernel/simulation.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace s2sim::viewer {

class ChartData {
 public:
  /// Signals in chart order (never `time`, each once).
  const std::vector<std::size_t>& signals() const { return signals_; }
  /// Adds a signal; its earlier samples are NaN (it was not recorded then).
  void add_signal(std::size_t signal);
  void remove_signal(std::size_t signal);
  bool has_signal(std::size_t signal) const;
  /// Forgets every sample (the signals stay).
  void clear_samples();
  /// Forgets everything.
  void clear();

  /// Appends one sample of every chosen signal at the simulation's current time.
  void record(const Simulation& sim);

  const std::vector<double>& times_s() const { return times_s_; }
  const std::vector<double>& values(std::size_t series) const { return values_[series]; }

  /// Writes the samples as s2sim-run's CSV log. Returns an empty string or the error.
  std::string export_csv(const std::string& file, const Simulation& sim) const;

 private:
  std::vector<std::size_t> signals_;
  std::vector<double> times_s_;
  std::vector<std::vector<double>> values_;  ///< per signal, same length as times_s_
};

}  // namespace s2sim::viewer
