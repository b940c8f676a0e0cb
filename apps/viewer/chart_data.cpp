#include "chart_data.hpp"

#include <signal_csv.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace s2sim::viewer {
namespace {
// About 100 MB of doubles at most: beyond it the oldest half of the history is dropped.
constexpr std::size_t kMaxStoredValues = 12'000'000;
}  // namespace

void ChartData::add_signal(std::size_t signal) {
  if (has_signal(signal)) return;
  signals_.push_back(signal);
  values_.emplace_back(times_s_.size(), std::numeric_limits<double>::quiet_NaN());
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
  times_s_.clear();
  for (auto& v : values_)
    v.clear();
}

void ChartData::clear() {
  signals_.clear();
  values_.clear();
  times_s_.clear();
}

void ChartData::record(const Simulation& sim) {
  if ((times_s_.size() + 1) * (values_.size() + 1) > kMaxStoredValues) {
    const auto half = static_cast<long>(times_s_.size() / 2);
    times_s_.erase(times_s_.begin(), times_s_.begin() + half);
    for (auto& v : values_)
      v.erase(v.begin(), v.begin() + half);
  }
  times_s_.push_back(sim.time_s());
  for (std::size_t k = 0; k < signals_.size(); ++k)
    values_[k].push_back(sim.signal(signals_[k]));
}

std::string ChartData::export_csv(const std::string& file, const Simulation& sim) const {
  std::FILE* out = std::fopen(file.c_str(), "w");
  if (out == nullptr) return "cannot write '" + file + "': " + std::strerror(errno);
  apps::write_csv_header(out, sim, signals_);
  std::vector<double> row(signals_.size());
  for (std::size_t i = 0; i < times_s_.size(); ++i) {
    for (std::size_t k = 0; k < signals_.size(); ++k)
      row[k] = values_[k][i];
    apps::write_csv_row(out, times_s_[i], row);
  }
  const bool failed = std::ferror(out) != 0;
  if (std::fclose(out) != 0 || failed) return "writing '" + file + "' failed";
  return {};
}

}  // namespace s2sim::viewer
