#include "outputs.hpp"

#include <s2sim/error.hpp>
#include <s2sim/math.hpp>
#include <signal_csv.hpp>

#include <cinttypes>
#include <cmath>

namespace s2sim::runner {
namespace {

std::string format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

/// JSON string escaping for IDs (quotes, backslashes, control characters).
std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

/// Shortest text that reads back to the same double; non-finite values become null.
std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  for (int precision = 15; precision <= 17; ++precision) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) return buf;
  }
  return format("%.17g", v);
}

struct PoseRow {
  std::string name;
  double x, y, z, yaw;
};

std::vector<PoseRow> robot_rows(const Simulation& sim) {
  std::vector<PoseRow> rows;
  for (const auto& r : sim.scene().robots) {
    if (r.main_body < 0) continue;
    const Pose& p = sim.body_pose(r.main_body + 1);
    rows.push_back({r.id, p.position.x, p.position.y, p.position.z, yaw_of(p.rotation)});
  }
  return rows;
}

std::vector<PoseRow> thing_rows(const Simulation& sim) {
  std::vector<PoseRow> rows;
  for (int b : sim.scene().things) {
    const Pose& p = sim.body_pose(b + 1);
    rows.push_back(
        {sim.scene().bodies[b].id, p.position.x, p.position.y, p.position.z, yaw_of(p.rotation)});
  }
  return rows;
}

std::string robot_name(const Simulation& sim, int robot) {
  return robot >= 0 ? sim.scene().robots[robot].id : std::string();
}

}  // namespace

CsvLog::CsvLog(const std::string& file, const Simulation& sim,
               const std::vector<std::string>& patterns)
    : path_(file), signals_(apps::select_signals(sim, patterns)), row_(signals_.size()) {
  out_ = std::fopen(file.c_str(), "w");
  if (out_ == nullptr) throw Error(ErrorKind::usage, "--log: cannot write '" + file + "'");
  apps::write_csv_header(out_, sim, signals_);
}

CsvLog::~CsvLog() {
  if (out_ != nullptr) std::fclose(out_);
}

void CsvLog::close() {
  if (out_ == nullptr) return;
  const bool failed = std::ferror(out_) != 0;
  const bool close_failed = std::fclose(out_) != 0;  // the final flush happens here
  out_ = nullptr;
  if (failed || close_failed) throw OutputError("--log: writing '" + path_ + "' failed");
}

void CsvLog::write_row(const Simulation& sim) {
  for (std::size_t k = 0; k < signals_.size(); ++k)
    row_[k] = sim.signal(signals_[k]);
  // A non-finite value is no measurement: the log keeps its rows up to the last finite one and
  // the run fails (exit 5) naming the signal, rather than writing inf/nan with exit 0.
  if (const auto bad = apps::first_non_finite(row_); bad >= 0) {
    std::fflush(out_);
    char value[32];
    std::snprintf(value, sizeof value, "%g", row_[static_cast<std::size_t>(bad)]);
    throw Error(ErrorKind::runtime,
                "signal '" + sim.signal_info(signals_[static_cast<std::size_t>(bad)]).name +
                    "' is " + value + " at t = " + std::to_string(sim.time_s()) +
                    " s; --log keeps the rows before it");
  }
  apps::write_csv_row(out_, sim.time_s(), row_);
  // One write per row: the rows stay whole in the file whatever happens to the process next.
  if (std::fflush(out_) != 0 || std::ferror(out_))
    throw OutputError("--log: writing '" + path_ + "' failed");
}

std::string summary_text(const Simulation& sim, const RunTiming& t) {
  std::string s;
  char line[256];
  std::snprintf(line, sizeof line,
                "simulated %.3f s in %.3f s wall: %.1fx real time, %" PRId64 " steps of %g ms\n",
                sim.time_s(), t.wall_s, t.wall_s > 0 ? sim.time_s() / t.wall_s : 0.0, t.steps,
                sim.tick_s() * 1e3);
  s += line;
  const Simulation::RunAheadCounts ahead = sim.run_ahead_counts();
  if (ahead.stretches + ahead.lost > 0) {  // --threads: how much of it the parts ran alone
    std::snprintf(line, sizeof line,
                  "ran ahead: %" PRId64 " stretches (%" PRId64 " steps), %" PRId64
                  " gone back where two parts came close\n",
                  ahead.stretches, ahead.ticks, ahead.lost);
    s += line;
  }
  // A value that prints as zero prints without a sign: a robot driving straight ends at
  // y = -1e-18 as readily as at +1e-18, and "-0.0000" would read as a drift.
  auto shown = [](double v, double last_digit) { return std::abs(v) < 0.5 * last_digit ? 0.0 : v; };
  auto rows = [&](const char* title, const std::vector<PoseRow>& r) {
    if (r.empty()) return;
    s += title;
    for (const auto& p : r) {
      std::snprintf(line, sizeof line, "  %-20s x %9.4f  y %9.4f  z %9.4f  yaw %8.2f deg\n",
                    p.name.c_str(), shown(p.x, 1e-4), shown(p.y, 1e-4), shown(p.z, 1e-4),
                    shown(p.yaw * 180.0 / kPi, 1e-2));
      s += line;
    }
  };
  rows("robots:\n", robot_rows(sim));
  rows("things:\n", thing_rows(sim));
  return s;
}

std::string dynamics_check_text(const Simulation& sim) {
  const Simulation::DynamicsCheck check = sim.dynamics_check();
  char line[512];
  if (sim.dynamics() == "loose") {
    std::snprintf(line, sizeof line,
                  "dynamics check: nothing compared, no body of this scene has a joint (each "
                  "is integrated on its own)\n");
  } else if (sim.dynamics() != "checked") {
    std::snprintf(line, sizeof line,
                  "dynamics check: nothing compared, the %s dynamics step this scene (the "
                  "small-tree dynamics cannot take it)\n",
                  sim.dynamics().c_str());
  } else {
    const int n = std::snprintf(
        line, sizeof line,
        "dynamics check: %" PRId64
        " accelerations compared with Simbody's, the largest difference %.3g of the largest "
        "acceleration (at t = %.4f s), within the agreement of %g\n",
        check.compared, check.worst_relative, check.worst_time_s, check.agreement);
    if (check.judged_on_loops > 0 && n > 0 && n < static_cast<int>(sizeof line))
      std::snprintf(line + n, sizeof line - static_cast<std::size_t>(n),
                    "dynamics check: %" PRId64
                    " substeps judged on the loop constraints, where the two constrained "
                    "solves parted (loop errors up to %.3g for the tree, %.3g for Simbody)\n",
                    check.judged_on_loops, check.worst_loop_error,
                    check.worst_reference_loop_error);
  }
  return line;
}

std::string summary_json(const Simulation& sim, const RunTiming& t, bool with_timing) {
  std::string s = "{\n";
  s += "  \"sim_time\": " + json_number(sim.time_s()) + ",\n";
  if (with_timing) {
    s += "  \"wall_time\": " + json_number(t.wall_s) + ",\n";
    s += "  \"rtf\": " + json_number(t.wall_s > 0 ? sim.time_s() / t.wall_s : 0.0) + ",\n";
  }
  s += "  \"steps\": " + std::to_string(t.steps) + ",\n";
  auto poses = [&](const char* key, const std::vector<PoseRow>& rows) {
    s += std::string("  \"") + key + "\": [";
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto& p = rows[i];
      s += (i ? ",\n    " : "\n    ");
      s += "{\"name\": " + json_string(p.name) + ", \"x\": " + json_number(p.x) +
           ", \"y\": " + json_number(p.y) + ", \"z\": " + json_number(p.z) +
           ", \"yaw\": " + json_number(p.yaw) + "}";
    }
    s += rows.empty() ? "],\n" : "\n  ],\n";
  };
  poses("robots", robot_rows(sim));
  poses("things", thing_rows(sim));
  s += "  \"axes\": [";
  for (std::size_t a = 0; a < sim.axis_count(); ++a) {
    const auto& ax = sim.axis(a);
    s += (a ? ",\n    " : "\n    ");
    s += "{\"robot\": " + json_string(robot_name(sim, ax.robot)) +
         ", \"name\": " + json_string(ax.name) + ", \"pos\": " + json_number(sim.axis_position(a)) +
         ", \"vel\": " + json_number(sim.axis_velocity(a)) + "}";
  }
  s += sim.axis_count() ? "\n  ]\n" : "]\n";
  s += "}\n";
  return s;
}

void ProgressBar::update(double sim_s, double total_s, double wall_s, bool force) {
  if (!enabled_ || (!force && wall_s - last_draw_wall_s_ < 0.1)) return;
  last_draw_wall_s_ = wall_s;
  const double fraction = total_s > 0 ? std::min(1.0, sim_s / total_s) : 1.0;
  constexpr int width = 40;
  const int filled = static_cast<int>(fraction * width);
  char bar[width + 1];
  for (int i = 0; i < width; ++i)
    bar[i] = i < filled ? '#' : '.';
  bar[width] = '\0';
  std::fprintf(stderr, "\r[%s] %5.1f%%  t = %8.3f s  %6.1fx real time", bar, fraction * 100, sim_s,
               wall_s > 0 ? sim_s / wall_s : 0.0);
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (enabled_ && last_draw_wall_s_ >= 0) std::fputc('\n', stderr);
}

}  // namespace s2sim::runner
