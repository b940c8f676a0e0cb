#include "script_session.hpp"
#include "ui_script.hpp"

#include <s2sim/error.hpp>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

namespace s2sim::viewer {
namespace {

Error bad(const std::string& command, const std::string& why) {
  return Error(ErrorKind::usage, "script command '" + command + "': " + why);
}

/// Offset of the start of line `line` (1-based) in `text`, npos when it has fewer lines.
std::size_t line_start(const std::string& text, int line) {
  std::size_t pos = 0;
  for (int i = 1; i < line && pos != std::string::npos; ++i) {
    pos = text.find('\n', pos);
    if (pos != std::string::npos) ++pos;
  }
  return line < 1 ? std::string::npos : pos;
}

std::string line_text(const std::string& text, int line) {
  const std::size_t start = line_start(text, line);
  if (start == std::string::npos || start > text.size()) return {};
  const std::size_t end = text.find('\n', start);
  return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

std::string one_line(std::string text) {
  for (std::size_t at; (at = text.find('\n')) != std::string::npos;)
    text.replace(at, 1, " | ");
  return text;
}

}  // namespace

bool more_commands(ViewerState& state, const std::string& command, const std::string& rest) {
  ScriptEditorState& editor = state.script_editor;
  if (command == "script-goto-error") {
    const int n = std::stoi(rest);
    if (n < 1 || n > static_cast<int>(editor.errors.size()))
      throw bad(command + " " + rest, "no such compile error");
    editor.highlight_line = editor.errors[static_cast<std::size_t>(n - 1)].line;
    editor.scroll_to_line = editor.highlight_line;
    return true;
  }
  if (command == "script-set-line") {
    std::istringstream args(rest);
    int line = 0;
    args >> line;
    std::string text;
    std::getline(args >> std::ws, text);
    const std::size_t start = line_start(editor.text, line);
    if (editor.file.empty() || start == std::string::npos)
      throw bad(command + " " + rest, "no such line in the script");
    const std::size_t end = editor.text.find('\n', start);
    editor.text.replace(start, end == std::string::npos ? std::string::npos : end - start, text);
    return true;
  }
  if (command == "chart-xy") {
    std::istringstream args(rest);
    std::string x, y;
    if (!(args >> x >> y)) throw bad(command + " " + rest, "chart-xy X_SIGNAL Y_SIGNAL");
    auto series_of = [&](const std::string& name) {
      const std::size_t signal = state.sim->signal_index(name);
      state.chart.add_signal(signal);
      const auto& signals = state.chart.signals();
      for (std::size_t k = 0; k < signals.size(); ++k)
        if (signals[k] == signal) return static_cast<int>(k);
      return -1;
    };
    state.chart_view.x_series = series_of(x);
    state.chart_view.y_series = series_of(y);
    // Before the first step the t = 0 sample is taken again, with these signals.
    if (state.sim->tick() == 0) {
      state.chart.clear_samples();
      state.chart.record(*state.sim);
    }
    state.chart_view.xy = true;
    return true;
  }
  if (command == "sleep") {  // wall-clock seconds (tests that edit files meanwhile)
    std::this_thread::sleep_for(std::chrono::duration<double>(std::stod(rest)));
    return true;
  }
  if (command == "chart-time") {
    state.chart_view.xy = false;
    return true;
  }
  return false;
}

bool print_more(ViewerState& state, const std::string& what) {
  const ScriptEditorState& editor = state.script_editor;
  const Annotations& published = state.sim->annotations();
  if (what == "replay") {
    if (!state.replay) throw bad("print replay", "no replay (start with --replay FILE)");
    const Replay& r = *state.replay;
    std::printf("replay %.9f %.9f %zu %zu %d %.6g\n", r.time_s(), r.recording().times_s[r.frame()],
                r.frame(), r.recording().frame_count(), r.playing ? 1 : 0, r.speed);
  } else if (what == "script-errors") {
    for (const ScriptMessage& m : editor.errors)
      std::printf("script-error %s %d %d %s\n", m.file.c_str(), m.line, m.column, m.text.c_str());
    std::printf("script-errors %zu\n", editor.errors.size());
  } else if (what == "script-view") {
    std::printf("script-view %d %d %d\n", editor.first_visible_line, editor.last_visible_line,
                editor.highlight_line);
  } else if (what == "script-status") {
    std::printf("script-status %d %d %s\n", script_loaded(state) ? 1 : 0,
                script_running(state) ? 1 : 0, editor.status.c_str());
  } else if (what.rfind("script-line ", 0) == 0) {
    const int line = std::stoi(what.substr(12));
    std::printf("script-line %d %s\n", line, line_text(editor.text, line).c_str());
  } else if (what == "hud") {
    std::printf("hud %s\n", one_line(published.hud_text()).c_str());
  } else if (what.rfind("log-count ", 0) == 0) {
    const std::string needle = what.substr(10);
    int n = 0;
    for (const LogLine& line : state.log)
      n += line.text.find(needle) != std::string::npos ? 1 : 0;
    std::printf("log-count %d\n", n);
  } else if (what == "script-trails") {
    for (const auto& trail : published.trails)
      std::printf("script-trail %s %d %zu\n", trail.source.c_str(), trail.id,
                  trail.points_m.size());
  } else if (what == "xy-series") {
    for (const auto& series : published.series)
      std::printf("xy-series %s %d %zu\n", series.source.c_str(), series.id, series.points.size());
  } else if (what == "chart-samples") {
    const std::size_t n = state.chart.sample_count();
    std::printf("chart-samples %zu %.6f %.6f\n", n, n ? state.chart.time_s(0) : 0.0,
                n ? state.chart.time_s(n - 1) : 0.0);
  } else if (what == "memory") {
    std::ifstream status("/proc/self/status");
    long rss_kB = -1, hwm_kB = -1;
    for (std::string line; std::getline(status, line);) {
      if (line.rfind("VmRSS:", 0) == 0) rss_kB = std::stol(line.substr(6));
      if (line.rfind("VmHWM:", 0) == 0) hwm_kB = std::stol(line.substr(6));
    }
    std::printf("memory %ld %ld\n", rss_kB, hwm_kB);
  } else {
    return false;
  }
  return true;
}

bool replay_command(ViewerState& state, const std::string& command, const std::string& rest) {
  if (command.rfind("replay-", 0) != 0) return false;
  if (!state.replay) throw bad(command + " " + rest, "no replay (start with --replay FILE)");
  Replay& replay = *state.replay;
  if (command == "replay-seek") {
    replay.seek(std::stod(rest));
  } else if (command == "replay-speed") {
    replay.speed = std::stod(rest);
    if (replay.speed == 0) throw bad(command + " " + rest, "the speed must not be 0 (pause)");
    replay.playing = true;
  } else if (command == "replay-step") {
    replay.step_frames(std::stol(rest));
    replay.playing = false;
  } else {
    throw bad(command + " " + rest, "replay-seek T, replay-speed X or replay-step N");
  }
  return true;
}

}  // namespace s2sim::viewer
