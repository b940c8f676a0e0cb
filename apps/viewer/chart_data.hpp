#pragma once
/// \file
/// The chart's recorded samples: the chosen signals read after every tick, so that an
/// exported CSV has exactly the rows of `s2sim-run --log` (same times, same formatting), over
/// a bounded history: the last `span_s()` simulated seconds (`--chart-span`, 60 s by default),
/// and never more than kMaxStoredValues numbers in all (the span shrinks when many signals are
/// charted). Each signal's samples are a sliding window over one buffer: recording appends,
/// samples older than the span are dropped from the front, and the buffer is compacted in
/// place once a quarter of it is dropped; the buffers never grow past what that can leave, so
/// they hold at most about 1.07 times kMaxStoredValues numbers, and a long run allocates
/// nothing once they have grown (docs/viewer.md, "Chart memory").

#include <s2sim/kernel/simulation.hpp>

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace s2sim::viewer {

class ChartData {
 public:
  /// Numbers kept at most, times included: 8 M doubles, 64 MB (0.8 of it live samples, the
  /// rest room for compaction; the buffers' capacity stays under 69 MB).
  static constexpr std::size_t kMaxStoredValues = 8'000'000;

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

  /// Simulated seconds of history kept (> 0).
  void set_span(double span_s) { span_s_ = span_s; }
  double span_s() const { return span_s_; }

  /// Appends one sample of every chosen signal at the simulation's current time, and drops
  /// what falls out of the span or over the bound.
  void record(const Simulation& sim);
  /// The same from recorded values (a replay): `signal_values` holds every signal of the
  /// simulation, by index, at `time_s`.
  void record(double time_s, double tick_s, std::span<const double> signal_values);

  /// The kept samples, oldest first.
  std::span<const double> times_s() const { return {times_s_.data() + begin_, size()}; }
  std::span<const double> values(std::size_t series) const {
    return {values_[series].data() + begin_, size()};
  }
  std::size_t sample_count() const { return size(); }
  double time_s(std::size_t i) const { return times_s_[begin_ + i]; }
  /// Numbers held in memory (capacity of the buffers), for the memory bound's test.
  std::size_t stored_values() const;

  /// Writes the samples as s2sim-run's CSV log. Returns an empty string or the error.
  std::string export_csv(const std::string& file, const Simulation& sim) const;

 private:
  std::size_t size() const { return times_s_.size() - begin_; }
  void drop_front(std::size_t count);
  template <class ReadSignal>
  void append(double now_s, double tick_s, const ReadSignal& read);

  double span_s_ = 60;
  std::vector<std::size_t> signals_;
  std::size_t begin_ = 0;  ///< the oldest kept sample in every buffer
  std::vector<double> times_s_;
  std::vector<std::vector<double>> values_;  ///< per signal, same length as times_s_
};

}  // namespace s2sim::viewer
