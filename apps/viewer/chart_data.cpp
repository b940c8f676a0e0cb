#include "chart_data.hpp"

#include <signal_csv.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace s2sim::viewer {
void ChartData::add_signal(std::size_t signal) {
  if (has_signal(signal)) return;
  signals_.push_back(signal);
  values_.emplace_back(times_s_.size(), std::numeric_limits<double>::quiet_NaN());
  values_.back().reserve(times_s_.capacity());
}

void ChartData::remove_signal(std::size_t signal) {
  const auto it = std::find(signals_.begin(), signals_.end(), signal);
  if (it == signals_.end()) return;
  values_.erase(values_.begin() + (it - signals_.begin()));
  signals_.erase(it);
}

bool ChartData::has_signal(std::size_t signal) const {
  return std::find(signals_.begin(), signals_.end(), signal) != signals_.end();
}

void ChartData::clear_samples() {
  begin_ = 0;
  times_s_.clear();
  for (auto& v : values_)
    v.clear();
}

void ChartData::clear() {
  signals_.clear();
  values_.clear();
  times_s_.clear();
  begin_ = 0;
}

std::size_t ChartData::stored_values() const {
  std::size_t n = times_s_.capacity();
  for (const auto& v : values_)
    n += v.capacity();
  return n;
}

void ChartData::drop_front(std::size_t count) {
  begin_ += count;
  // Compact once a quarter is dead: the buffers keep their capacity, so no allocation.
  if (begin_ >= 64 && begin_ * 4 >= times_s_.size()) {
    const auto dead = static_cast<long>(begin_);
    times_s_.erase(times_s_.begin(), times_s_.begin() + dead);
    for (auto& v : values_)
      v.erase(v.begin(), v.begin() + dead);
    begin_ = 0;
  }
}

void ChartData::record(const Simulation& sim) {
  append(sim.time_s(), sim.tick_s(), [&](std::size_t signal) { return sim.signal(signal); });
}

void ChartData::record(double time_s, double tick_s, std::span<const double> signal_values) {
  append(time_s, tick_s, [&](std::size_t signal) { return signal_values[signal]; });
}

template <class ReadSignal>
void ChartData::append(double now_s, double tick_s, const ReadSignal& read) {
  const std::size_t per_sample = signals_.size() + 1;
  const std::size_t max_samples = std::max<std::size_t>(2, kMaxStoredValues * 4 / 5 / per_sample);
  if (times_s_.size() == times_s_.capacity()) {
    // Grow as a vector does, but never past what compaction can leave: at most a third more
    // than the live samples, plus the 64 compaction waits for.
    const std::size_t limit = max_samples * 4 / 3 + 70;
    const std::size_t capacity =
        std::max(times_s_.size() + 1, std::min(2 * times_s_.capacity() + 64, limit));
    times_s_.reserve(capacity);
    for (auto& v : values_)
      v.reserve(capacity);
  }
  times_s_.push_back(now_s);
  for (std::size_t k = 0; k < signals_.size(); ++k)
    values_[k].push_back(read(signals_[k]));
  // The span (a tick's slack, so a span of T seconds keeps T / tick + 1 samples)...
  std::size_t old = 0;
  const double from_s = now_s - span_s_ - 0.5 * tick_s;
  while (old < size() && times_s_[begin_ + old] < from_s)
    ++old;
  // ...and the bound on the numbers kept (0.8 of it live, the rest slack before compaction).
  if (size() - old > max_samples) old = size() - max_samples;
  if (old > 0) drop_front(old);
}

std::string ChartData::export_csv(const std::string& file, const Simulation& sim) const {
  std::FILE* out = std::fopen(file.c_str(), "w");
  if (out == nullptr) return "cannot write '" + file + "': " + std::strerror(errno);
  apps::write_csv_header(out, sim, signals_);
  std::vector<double> row(signals_.size());
  for (std::size_t i = begin_; i < times_s_.size(); ++i) {
    for (std::size_t k = 0; k < signals_.size(); ++k)
      row[k] = values_[k][i];
    apps::write_csv_row(out, times_s_[i], row);
  }
  const bool failed = std::ferror(out) != 0;
  if (std::fclose(out) != 0 || failed) return "writing '" + file + "' failed";
  return {};
}

}  // namespace s2sim::viewer
