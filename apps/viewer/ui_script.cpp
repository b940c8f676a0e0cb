#include "ui_script.hpp"

#include "windows/panels.hpp"
#include "windows/windows.hpp"

#include <s2sim/error.hpp>
#include <s2sim/math.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace s2sim::viewer {

bool set_window(WindowFlags& w, const std::string& name, bool open) {
  bool* flag = name == "run"             ? &w.run
               : name == "configuration" ? &w.configuration
               : name == "chart"         ? &w.chart
               : name == "sheet"         ? &w.sheet
               : name == "editor"        ? &w.editor
               : name == "script"        ? &w.script
               : name == "log"           ? &w.log
               : name == "body"          ? &w.body
               : name == "cameras"       ? &w.cameras
                                         : nullptr;
  if (flag == nullptr) return false;
  *flag = open;
  return true;
}

namespace {
/// Simulation index of the body with this ID (robot bodies and things), -1 if none.
int find_body(const ViewerState& state, const std::string& id) {
  const auto& bodies = state.sim->scene().bodies;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (bodies[b].id == id) return static_cast<int>(b) + 1;
  return -1;
}
}  // namespace

namespace {
/// The commands that touch nothing of the simulation's: all a script may run while the
/// stepping thread is in a call that has not come back.
bool runs_while_stuck(const std::string& command, const std::string& rest) {
  return command == "wait" || command == "click" || command == "screenshot" || command == "quit" ||
         command == "sleep" || (command == "print" && rest == "stuck");
}
}  // namespace

void UiScript::run_commands(ViewerState& state, std::string& screenshot_file) {
  if (running_) {
    if (state.stuck.now || state.run.playing) return;
    running_ = false;
  }
  if (wait_frames_ > 0) {
    --wait_frames_;
    return;
  }
  while (next_ < commands_.size()) {
    const std::string line = commands_[next_++];
    std::istringstream in(line);
    std::string command;
    in >> command;
    std::string rest;
    std::getline(in >> std::ws, rest);
    auto bad = [&](const std::string& why) {
      return Error(ErrorKind::usage, "script command '" + line + "': " + why);
    };
    if (command.empty() || command[0] == '#') continue;
    if (state.stuck.now && !runs_while_stuck(command, rest)) {
      --next_;  // once the simulation answers again
      return;
    }
    if (command == "wait") {
      wait_frames_ = std::stoi(rest.empty() ? "1" : rest) - 1;
      return;
    } else if (command == "click") {
      // The click happens while this frame's UI is drawn and takes effect in the next frame's
      // stepping: wait for that, so a following `print` sees its result.
      state.scripted_clicks.push_back(rest);
      wait_frames_ = 1;
      return;
    } else if (command == "run-until") {
      state.run.pause_at_s = std::stod(rest);
      state.run.playing = true;
      running_ = true;
      return;
    } else if (command == "speed") {
      const double x = std::stod(rest);
      state.run.as_fast_as_possible = x == 0;
      if (x > 0) state.run.speed = x;
    } else if (command == "print") {
      if (rest == "stuck")
        std::printf("stuck %s %.1f %s\n", state.stuck.now ? "yes" : "no", state.stuck.running_s,
                    state.stuck.component.c_str());
      else if (rest == "time")
        std::printf("time %.9f\n", state.sim->time_s());
      else if (rest == "tick")
        std::printf("tick %lld\n", static_cast<long long>(state.sim->tick()));
      else if (rest.rfind("body ", 0) == 0) {
        const int b = find_body(state, rest.substr(5));
        if (b < 0) throw bad("no body with that ID");
        const Vec3& p = state.sim->body_pose(b).position;
        std::printf("body %s %.9f %.9f %.9f\n", rest.substr(5).c_str(), p.x, p.y, p.z);
      } else if (rest.rfind("signal ", 0) == 0)
        std::printf("signal %s %.10g\n", rest.substr(7).c_str(), state.sim->signal(rest.substr(7)));
      else if (rest == "camera")
        std::printf("camera %.4f %.4f %.4f %.4f %.4f %.4f\n", state.camera.yaw_rad,
                    state.camera.pitch_rad, state.camera.distance_m, state.camera.target_m.x,
                    state.camera.target_m.y, state.camera.target_m.z);
      else if (rest == "layout" || rest == "scene-box")
        state.end_of_frame_prints.push_back(rest);
      else if (rest.rfind("trail ", 0) == 0) {
        const auto& robots = state.sim->scene().robots;
        std::size_t r = 0;
        while (r < robots.size() && robots[r].id != rest.substr(6))
          ++r;
        if (r == robots.size()) throw bad("no robot with that ID");
        const std::size_t n = state.trails.count(r, state.overlay.trail_length_s);
        double length_m = 0;
        for (std::size_t i = 1; i < n; ++i) {
          const Vec3f d = state.trails.point(r, n, i) - state.trails.point(r, n, i - 1);
          length_m += std::sqrt(dot(d, d));
        }
        std::printf("trail %s %zu %.4f\n", rest.substr(6).c_str(), n, length_m);
      } else if (rest == "rtf")
        std::printf("rtf %s\n", state.run_status_text.c_str());
      else if (rest == "clock")
        std::printf(
            "clock %.9f %.9f\n", state.sim->time_s(),
            std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
                .count());
      else if (rest == "editor-error")
        std::printf("editor-error %d %s\n", state.editor.error_line, state.editor.error.c_str());
      else if (!print_more(state, rest) && !print_camera(state, rest))
        throw bad(
            "print time, tick, clock, stuck, rtf, camera, layout, scene-box, body ID, signal NAME, "
            "editor-error, script-errors, script-view, script-status, script-line N, hud, "
            "log-count TEXT, script-trails, xy-series, chart-samples, memory, replay, "
            "cameras or image-pixel NAME X Y");
      std::fflush(stdout);
    } else if (command == "overlay") {
      std::istringstream args(rest);
      std::string what, on_off;
      if (!(args >> what >> on_off) || (on_off != "on" && on_off != "off"))
        throw bad("overlay trails|labels|axes|scale-bar on|off");
      bool* flag = what == "trails"      ? &state.overlay.trails
                   : what == "labels"    ? &state.overlay.labels
                   : what == "axes"      ? &state.overlay.axes
                   : what == "scale-bar" ? &state.overlay.scale_bar
                                         : nullptr;
      if (flag == nullptr) throw bad("overlay trails|labels|axes|scale-bar on|off");
      *flag = on_off == "on";
    } else if (command == "frame") {
      state.frame_request = true;
    } else if (command == "reset-layout") {
      reset_layout(state);
    } else if (command == "pace") {
      if (rest != "wall" && rest != "fixed") throw bad("pace wall or pace fixed");
      state.scripted_wall_pacing = rest == "wall";
    } else if (command == "chart-add") {
      for (std::size_t i : state.sim->match_signals(rest))
        if (state.sim->signal_info(i).name != "time") state.chart.add_signal(i);
    } else if (command == "chart-csv") {
      state.chart_view.csv_file = rest;
    } else if (command == "show" || command == "hide") {
      if (!set_window(state.windows, rest, command == "show")) throw bad("unknown window");
      if (command == "show") bring_to_front(state, rest);
    } else if (command == "select") {
      state.selected_body = find_body(state, rest);
      if (state.selected_body < 0) throw bad("no body with that ID");
      state.windows.body = true;
    } else if (command == "move") {
      std::istringstream args(rest);
      std::string id;
      Vec3 p;
      if (!(args >> id >> p.x >> p.y >> p.z)) throw bad("move BODY X Y Z");
      const int b = find_body(state, id);
      if (b < 0) throw bad("no body with that ID");
      move_body(state, b, p);
    } else if (command == "sheet-set") {
      std::istringstream args(rest);
      std::string cell;
      double value = 0;
      if (!(args >> cell >> value)) throw bad("sheet-set CELL VALUE");
      state.sim->set_input("sheet/" + cell, value);
    } else if (command == "editor-open") {
      if (state.editor.files.empty()) load_editor_files(state);
      bool found = false;
      for (std::size_t i = 0; i < state.editor.files.size(); ++i)
        if (state.editor.files[i].path.filename() == rest) {
          state.editor.current = static_cast<int>(i);
          found = true;
        }
      if (!found) throw bad("no such file in the scene editor");
      state.windows.editor = true;
    } else if (command == "editor-insert") {
      std::istringstream args(rest);
      int line_number = 0;
      args >> line_number;
      std::string text;
      std::getline(args >> std::ws, text);
      if (state.editor.files.empty()) load_editor_files(state);
      std::string& buffer = state.editor.files[state.editor.current].text;
      std::size_t pos = 0;
      for (int l = 1; l < line_number && pos != std::string::npos; ++l) {
        pos = buffer.find('\n', pos);
        if (pos != std::string::npos) ++pos;
      }
      if (line_number < 1 || pos == std::string::npos) throw bad("no such line");
      buffer.insert(pos, text + "\n");
    } else if (command == "camera") {
      std::istringstream args(rest);
      float yaw_deg = 0, pitch_deg = 0, distance_m = 0;
      if (!(args >> yaw_deg >> pitch_deg >> distance_m)) throw bad("camera YAW PITCH DISTANCE");
      state.camera.yaw_rad = yaw_deg * static_cast<float>(kPi) / 180;
      state.camera.pitch_rad = pitch_deg * static_cast<float>(kPi) / 180;
      state.camera.distance_m = distance_m;
      state.frame_request = false;  // a camera set by the script wins over the start framing
      state.camera_set_by_script = true;
    } else if (command == "follow") {
      const auto& robots = state.sim->scene().robots;
      state.camera.follow_robot = -1;
      for (std::size_t r = 0; r < robots.size(); ++r)
        if (robots[r].id == rest) state.camera.follow_robot = static_cast<int>(r);
      if (state.camera.follow_robot < 0) throw bad("no robot with that ID");
      state.frame_request = false;  // following frames the robot, not the whole scene
    } else if (replay_command(state, command, rest)) {
      // replay-seek, replay-speed, replay-step: ui_script_more.cpp
    } else if (camera_command(state, command, rest)) {
      // camera-image: ui_script_cameras.cpp
    } else if (more_commands(state, command, rest)) {
      // script-*, chart-xy, chart-time: ui_script_more.cpp
    } else if (command == "screenshot") {
      screenshot_file = rest;
      return;
    } else if (command == "quit") {
      state.quit = true;
      return;
    } else {
      throw bad("unknown command (see docs/viewer.md)");
    }
  }
}

void UiScript::frame(ViewerState& state, std::string& screenshot_file) {
  try {
    run_commands(state, screenshot_file);
  } catch (const Error&) {
    throw;
  } catch (const std::exception&) {
    // std::stoi / std::stod on a word that is not a number.
    throw Error(ErrorKind::usage,
                "script command '" + commands_[next_ - 1] + "': expected a number");
  }
}

}  // namespace s2sim::viewer
