#include "signal_csv.hpp"

#include <s2sim/error.hpp>

#include <cmath>

namespace s2sim::apps {

std::vector<std::size_t> select_signals(const Simulation& sim,
                                        const std::vector<std::string>& patterns,
                                        const std::string& option) {
  // The kernel publishes `time` as a signal too; the log writes it first, so leaving it out
  // and skipping repeats (overlapping patterns) keeps column names unique.
  std::vector<std::size_t> selected;
  std::vector<bool> taken(sim.signal_count(), false);
  if (const auto time = sim.find_signal("time")) taken[*time] = true;
  auto take = [&](std::size_t i) {
    if (!taken[i]) selected.push_back(i);
    taken[i] = true;
  };
  if (patterns.empty()) {
    for (std::size_t i = 0; i < sim.signal_count(); ++i)
      take(i);
    return selected;
  }
  for (const auto& p : patterns) {
    const auto matched = sim.match_signals(p);
    if (matched.empty()) {
      // A plain name gets the "did you mean" of signal_index().
      if (p.find_first_of("*?") == std::string::npos) (void)sim.signal_index(p);
      throw Error(ErrorKind::usage, option + ": pattern '" + p + "' matches no signal");
    }
    for (std::size_t i : matched)
      take(i);
  }
  return selected;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';  // RFC 4180: a quote inside a quoted field is doubled
    quoted += c;
  }
  return quoted + '"';
}

void write_csv_header(std::FILE* out, const Simulation& sim, std::span<const std::size_t> signals) {
  std::fputs("time [s]", out);
  for (std::size_t i : signals) {
    const SignalInfo& info = sim.signal_info(i);
    std::fputc(',', out);
    std::fputs(csv_field(info.name + " [" + info.unit + "]").c_str(), out);
  }
  std::fputc('\n', out);
}

std::ptrdiff_t first_non_finite(std::span<const double> values) {
  for (std::size_t k = 0; k < values.size(); ++k)
    if (!std::isfinite(values[k])) return static_cast<std::ptrdiff_t>(k);
  return -1;
}

void write_csv_row(std::FILE* out, double time_s, std::span<const double> values) {
  std::fprintf(out, "%.6f", time_s);
  for (double v : values)
    std::fprintf(out, ",%.10g", v);
  std::fputc('\n', out);
}

}  // namespace s2sim::apps
