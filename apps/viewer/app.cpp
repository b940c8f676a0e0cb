#include "app.hpp"

#include "frame_stepping.hpp"
#include "gl.hpp"
#include "keep_in_view.hpp"
#include "renderer.hpp"
#include "scene_drawables.hpp"
#include "scene_look.hpp"
#include "screenshot.hpp"
#include "script_session.hpp"
#include "simtwo_camera.hpp"
#include "ui_script.hpp"
#include "video_writer.hpp"
#include "viewer_state.hpp"
#include "windows/panels.hpp"
#include "windows/point_cloud_overlay.hpp"
#include "windows/published_overlay.hpp"
#include "windows/stuck_window.hpp"
#include "windows/windows.hpp"
#include "windows/world_overlay.hpp"
#include "world_input.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <exit_codes.hpp>
#include <recording.hpp>
#include <s2sim/error.hpp>
#include <scene_search.hpp>
#include <signal_csv.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <thread>

namespace s2sim::viewer {
namespace {

using Clock = std::chrono::steady_clock;

/// GLFW and its window, released in the right order whatever happens.
struct Window {
  GLFWwindow* handle = nullptr;
  Window(int width, int height, bool visible) {
    glfwSetErrorCallback([](int code, const char* text) {
      std::fprintf(stderr, "s2sim-view: GLFW error %d: %s\n", code, text);
    });
    if (!glfwInit())
      throw Error(ErrorKind::runtime,
                  "cannot open a display (no desktop? run under xvfb-run, see docs/viewer.md)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_SAMPLES, 0);
    handle = glfwCreateWindow(width, height, "S2Sim", nullptr, nullptr);
    if (handle == nullptr) {
      glfwTerminate();
      throw Error(ErrorKind::runtime, "cannot create an OpenGL 3.3 core window");
    }
    glfwMakeContextCurrent(handle);
  }
  ~Window() {
    glfwDestroyWindow(handle);
    glfwTerminate();
  }
};

/// The user's layout file: $XDG_CONFIG_HOME/s2sim/s2sim-view.ini (~/.config/... by default),
/// or the working directory's s2sim-view.ini when neither variable is set.
std::string user_ini_file() {
  namespace fs = std::filesystem;
  fs::path dir;
  if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg)
    dir = fs::path(xdg) / "s2sim";
  else if (const char* home = std::getenv("HOME"); home && *home)
    dir = fs::path(home) / ".config" / "s2sim";
  std::error_code ignored;  // without the folder the layout is simply not saved
  if (!dir.empty()) fs::create_directories(dir, ignored);
  return (dir / "s2sim-view.ini").string();
}

struct ImGuiContextGuard {
  explicit ImGuiContextGuard(GLFWwindow* window, bool save_layout) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    // Scripted runs must not depend on (or leave) a saved window layout.
    static const std::string ini_file = user_ini_file();
    ImGui::GetIO().IniFilename = save_layout ? ini_file.c_str() : nullptr;
    ImGui::StyleColorsDark();
    ImGui::GetStyle().Alpha = 0.95f;
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
  }
  ~ImGuiContextGuard() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
};

class App {
 public:
  App(const Options& options, GLFWwindow* window) : window_(window), script_(options.script) {
    state_.options = options;
    state_.run.playing = !options.paused;
    state_.run.speed = options.speed > 0 ? options.speed : 1.0;
    state_.run.as_fast_as_possible = options.speed == 0;
    for (const auto& name : options.show_windows)
      if (!set_window(state_.windows, name, true))
        throw Error(ErrorKind::usage,
                    "--show-window: unknown window '" + name +
                        "' (run, configuration, chart, sheet, editor, script, log, "
                        "body, cameras)");
    if (options.hide_ui) state_.windows = WindowFlags{false};
    state_.render.shadows = options.shadows;
    renderer_.init();
    choose_look(options);
    register_layout_settings(state_);
    // One scale for the font and the widgets' paddings, so a HiDPI screen gets the same
    // layout, only larger (the columns' rows are measured from the font).
    ImGui::GetIO().FontGlobalScale = static_cast<float>(options.font_scale);
    ImGui::GetStyle().ScaleAllSizes(static_cast<float>(options.font_scale));
    state_.chart.set_span(options.chart_span_s);
    if (options.replay_file.empty()) {
      install(load_simulation_keeping_script_errors(state_, options));
    } else {
      // The recorded scene, loaded as it was recorded; the run stands still, the replay's
      // clock says which frame it shows.
      apps::Recording recording = apps::read_recording(options.replay_file);
      auto sim = apps::load_recorded_simulation(
          recording,
          options.scene.empty() ? std::string() : apps::find_scene(options.scene).string());
      state_.replay = std::make_unique<Replay>(std::move(recording));
      state_.replay->playing = !options.paused;
      state_.replay->speed = options.speed > 0 ? options.speed : 1.0;
      state_.run.playing = false;
      install(std::move(sim));
      state_.log_message("replay of " + options.replay_file + ": " +
                         std::to_string(state_.replay->recording().frame_count()) + " frames");
    }
    state_.run.held_inputs = options.inputs;
    // The runner's selection, so an exported chart has s2sim-run's columns in its order.
    if (!options.chart_signals.empty()) {
      for (std::size_t i : apps::select_signals(*state_.sim, options.chart_signals, "--chart"))
        state_.chart.add_signal(i);
      state_.chart.clear_samples();  // the t = 0 sample again, now with these signals
      state_.chart.record(*state_.sim);
      state_.windows.chart = state_.windows.chart || !options.hide_ui;
    }
    if (state_.replay) state_.replay->show(*state_.sim, state_.chart);
    // Framed in the first frame, once the layout (which needs the font) gives the view's shape;
    // a SimTwo project opens with its author's saved camera instead.
    state_.frame_request = true;
    start_camera_ = read_simtwo_camera(state_.sim->scene().folder);
  }

  int run() {
    const Options& o = state_.options;
    // Scripted and screenshot runs advance a fixed 1/60 s of wall time per frame, so that
    // what they show does not depend on the machine.
    const bool scripted = o.frames > 0 || !script_.empty() || !o.video_file.empty();
    const double fixed_frame_s = 1.0 / 60;
    int frames = 0;
    auto last = Clock::now();
    std::vector<double> frame_times_s;  // for --report-fps
    if (o.report_fps) frame_times_s.reserve(o.frames > 0 ? o.frames : 100000);
    // --video: the replay at its speed, one video frame every 1/fps of wall time, from its
    // start to its end.
    std::optional<apps::VideoWriter> video;
    std::vector<unsigned char> video_pixels;
    const double video_step_s = state_.replay ? state_.replay->speed / o.video_fps : 0;
    if (!o.video_file.empty()) {
      int width = 0, height = 0;
      glfwGetFramebufferSize(window_, &width, &height);
      video.emplace(o.video_file, width, height, o.video_fps);
      video_pixels.resize(static_cast<std::size_t>(width) * height * 3);
      state_.replay->playing = false;
    }
    while (!glfwWindowShouldClose(window_) && !state_.quit) {
      glfwPollEvents();
      const auto now = Clock::now();
      const double wall_dt_s = std::chrono::duration<double>(now - last).count();
      last = now;
      if (o.report_fps && frames > 0) frame_times_s.push_back(wall_dt_s);
      state_.frame_time_s = state_.frame_time_s * 0.9 + wall_dt_s * 0.1;

      // A call into a component that has not come back since an earlier frame: this frame
      // touches nothing of the simulation's (stepper.hpp).
      bool stuck = !stepping_.idle() && !stepping_.wait(state_, false, 0.02);
      if (!stuck) {
        if (state_.pending_simulation && state_.replay) {
          state_.pending_simulation.reset();
          state_.log_message("a replay shows the recorded scene: the edit is saved, not shown",
                             true);
        }
        if (state_.pending_simulation) install(std::move(state_.pending_simulation));
      }
      std::string screenshot_file;
      script_.frame(state_, screenshot_file);

      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      int width = 0, height = 0;
      glfwGetFramebufferSize(window_, &width, &height);
      const ImVec2 display = ImGui::GetIO().DisplaySize;
      update_layout(state_, display.x, display.y);
      const bool fixed_pacing = scripted && !state_.scripted_wall_pacing;
      if (!stuck) {
        input_.update(state_, drawables_);
        if (video) {
          state_.replay->seek(state_.replay->start_s() + video->frames() * video_step_s);
          state_.replay->show(*state_.sim, state_.chart);
        } else if (state_.replay) {
          state_.replay->advance(fixed_pacing ? fixed_frame_s : wall_dt_s);
          state_.replay->show(*state_.sim, state_.chart);
        } else {
          stepping_.start(state_, fixed_pacing ? fixed_frame_s : wall_dt_s, fixed_pacing);
          stuck = !stepping_.wait(state_, fixed_pacing, FrameStepping::kStuckAfterS);
        }
      }
      if (!stuck) {
        std::vector<std::string> mesh_warnings;
        drawables_.take_meshes(*state_.sim, renderer_, mesh_warnings);
        drawables_.take_canvases(*state_.sim, renderer_);
        for (const auto& w : mesh_warnings)
          state_.log_message("warning: " + w);
        drawables_.update(*state_.sim, state_.render.floor_half_size_m);
        record_trails(state_);
        collect_published_lines(state_);
        reload_script_if_changed(state_);
        frame_camera();
      }

      // The 3-D view in framebuffer pixels (they differ from ImGui's on a HiDPI screen); while
      // stuck, the bodies where they were last drawn.
      const float scale = display.x > 0 ? static_cast<float>(width) / display.x : 1;
      const Rect& world = state_.layout_rects.world;
      renderer_.draw(drawables_.items(state_.show_beams, state_.show_joints, state_.selected_body),
                     state_.camera.render_view({world.x * scale, world.y * scale,
                                                world.width * scale, world.height * scale},
                                               height),
                     state_.render);
      if (!stuck) {
        draw_world_overlay(state_);
        draw_published_overlay(state_);
        draw_point_cloud_overlay(state_);
        draw_windows();
      } else {
        if (draw_stuck_window(state_)) stepping_.give_up(state_);
        check_scripted_clicks();
      }
      ImGui::Render();
      for (const std::string& what : state_.end_of_frame_prints)
        what == "layout" ? print_layout(state_) : print_scene_box();
      state_.end_of_frame_prints.clear();
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

      bool video_done = false;
      if (video) {
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadBuffer(GL_BACK);
        glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, video_pixels.data());
        video->add_frame(video_pixels.data());
        // Done once the next frame would lie past the end (half a frame of slack for rounding).
        video_done = state_.replay->start_s() + (video->frames() - 0.5) * video_step_s >=
                     state_.replay->end_s();
        if (video_done) {
          video->finish();
          std::printf("video %s: %d frames of %dx%d at %d fps (%s)\n", o.video_file.c_str(),
                      video->frames(), width & ~1, height & ~1, o.video_fps,
                      video->codec().c_str());
          std::fflush(stdout);
        }
      }
      ++frames;
      const bool last_frame = (o.frames > 0 && frames >= o.frames) || video_done ||
                              (!script_.empty() && script_.finished() && o.frames < 0);
      if (last_frame && !o.screenshot_file.empty()) screenshot_file = o.screenshot_file;
      if (!screenshot_file.empty()) {
        const std::string error = save_screenshot(screenshot_file, width, height);
        if (!error.empty()) throw Error(ErrorKind::usage, "--screenshot: " + error);
      }
      if (last_frame && o.print_projections && !stuck) print_projections();
      glfwSwapBuffers(window_);
      if (last_frame) break;
      if (!o.no_frame_cap && !scripted) cap_frame_rate(now);
    }
    if (o.report_fps) report_frame_rate(frame_times_s);
    if (!stepping_.idle()) {
      // Closed while a call had not returned: it keeps what it uses, and the viewer says so.
      std::fprintf(stderr,
                   "s2sim-view: the window closed while %s had not returned for %.1f s; "
                   "the viewer quits without waiting for it\n",
                   FrameStepping::what_runs(state_.stuck).c_str(), state_.stuck.running_s);
      stepping_.give_up(state_, false);
      return apps::kExitWatchdog;
    }
    return 0;
  }

  /// A stepping thread was given up: the process must end without the destructors it may need.
  bool abandoned_stepping() const { return stepping_.abandoned_any(); }
  /// Gives up a frame's stepping still running (an error left the frame loop meanwhile); true
  /// when one was ever given up.
  bool give_up_stepping() {
    if (!stepping_.idle()) stepping_.give_up(state_, false);
    return stepping_.abandoned_any();
  }

 private:
  void install(std::unique_ptr<Simulation> sim) {
    // Keep the chart's signals by name across a reload (their indices may change).
    std::vector<std::string> charted;
    if (state_.sim)
      for (std::size_t i : state_.chart.signals())
        charted.push_back(state_.sim->signal_info(i).name);
    state_.sim = std::move(sim);
    state_.chart.clear();
    for (const auto& name : charted)
      if (const auto i = state_.sim->find_signal(name)) state_.chart.add_signal(*i);
    state_.chart.record(*state_.sim);
    std::vector<std::string> warnings = state_.sim->warnings();
    drawables_.build(state_.sim->scene(), renderer_, warnings);
    apply_look_of(state_.sim->scene().folder, warnings);
    for (const auto& w : warnings)
      state_.log_message("warning: " + w);
    state_.log_message("loaded " + state_.sim->scene().file.string());
    state_.selected_body = -1;
    declined_.clear();
    auto_followed_ = -1;
    if (state_.camera.follow_robot >= static_cast<int>(state_.sim->scene().robots.size()))
      state_.camera.follow_robot = -1;
    load_editor_files(state_);
    open_scene_script(state_);
    state_.next_published_line = 0;
  }

  static bool takes_screenshots(const Options& options) {
    return !options.screenshot_file.empty() ||
           std::any_of(options.script.begin(), options.script.end(),
                       [](const std::string& c) { return c.rfind("screenshot ", 0) == 0; });
  }

  /// The full look (4x multisampling, a shadow map with smooth edges) unless --look fast; on
  /// a software rasteriser (llvmpipe) it costs more than the rest of the frame, so there
  /// only screenshots get it by default (docs/viewer.md). --msaa overrides the samples.
  void choose_look(const Options& options) {
    const bool fast = options.look == 0 || (options.look < 0 && renderer_.software_rasteriser() &&
                                            !takes_screenshots(options));
    state_.render.shadow_map = !fast;
    state_.render.smooth_shadows = !fast;
    state_.render.msaa_samples = options.msaa_samples >= 0 ? options.msaa_samples : fast ? 0 : 4;
    if (fast && options.look < 0)
      state_.log_message(
          "software rasteriser: the fast look by default (no multisampling, "
          "shadows on the floor only); --look full for the full one");
  }

  /// The floor and sky of the scene folder's settings, once per folder (a reload of the same
  /// scene keeps what the user changed). Its warnings go to stderr as well as to the Log.
  void apply_look_of(const std::filesystem::path& folder, std::vector<std::string>& warnings) {
    if (folder == look_folder_) return;
    look_folder_ = folder;
    std::vector<std::string> look_warnings, notes;
    apply_scene_look(folder, state_.options.shadows, renderer_, state_.render, look_warnings,
                     notes);
    for (const auto& w : look_warnings)
      std::fprintf(stderr, "s2sim-view: warning: %s\n", w.c_str());
    warnings.insert(warnings.end(), look_warnings.begin(), look_warnings.end());
    for (const auto& n : notes)
      state_.log_message(n);
  }

  /// The view's width over its height.
  float view_aspect() const {
    const Rect& view = state_.layout_rects.world;
    return view.width / std::max(1.0f, view.height);
  }

  /// Frames the whole scene when asked (start, F, `frame`); when a robot is followed, keeps
  /// the camera on it, framing the robot when the following starts.
  void frame_camera() {
    Vec3f lo, hi;
    const auto& scene = state_.sim->scene();
    if (state_.frame_request) {
      state_.frame_request = false;
      state_.camera.follow_robot = -1;
      followed_robot_ = -1;
      if (start_camera_) {
        // The author's view, moved back along its line of sight if the scene does not fit.
        state_.camera.look_from(start_camera_->eye_m, start_camera_->target_m);
        const float saved_distance_m = state_.camera.distance_m;
        if (drawables_.bounds(scene, -1, lo, hi))
          state_.camera.back_off_to_fit(lo, hi, view_aspect());
        char moved[64] = "";
        if (state_.camera.distance_m > saved_distance_m)
          std::snprintf(moved, sizeof moved, ", moved back from %.2f to %.2f m to show it all",
                        saved_distance_m, state_.camera.distance_m);
        state_.log_message("camera: the project's saved camera (" + start_camera_->source + ")" +
                           moved + "; F frames the whole scene");
        start_camera_.reset();
      } else if (drawables_.bounds(scene, -1, lo, hi)) {
        state_.camera.frame_box(lo, hi, view_aspect());
      }
    }
    keep_flying_robots_in_view();
    const int r = state_.camera.follow_robot;
    // A robot followed by hand is framed; one kept in view keeps the distance it was seen at.
    if (r != followed_robot_ && r >= 0 && r != auto_followed_ && !state_.camera_set_by_script &&
        drawables_.bounds(scene, r, lo, hi))
      state_.camera.frame_box(lo, hi, view_aspect(), 0.5f);  // room to see where it goes
    followed_robot_ = r;
    state_.camera_set_by_script = false;
    if (r < 0) return;
    const int body = scene.robots[r].main_body;
    if (body >= 0) state_.camera.target_m = to_f(state_.sim->body_pose(body + 1).position);
  }

  /// A robot that flies or floats and would leave the view is followed, once: one the user
  /// then stops following (another choice, F) is left alone.
  void keep_flying_robots_in_view() {
    const std::size_t robots = state_.sim->scene().robots.size();
    if (declined_.size() != robots) declined_.assign(robots, false), auto_followed_ = -1;
    if (auto_followed_ >= 0 && state_.camera.follow_robot != auto_followed_) {
      declined_[static_cast<std::size_t>(auto_followed_)] = true;
      auto_followed_ = -1;
    }
    if (!state_.camera.keep_in_view || state_.camera.follow_robot >= 0) return;
    const Mat4 vp = state_.camera.projection(view_aspect()) * state_.camera.view();
    const int r = robot_leaving_view(*state_.sim, vp, declined_);
    if (r < 0) return;
    state_.camera.follow_robot = auto_followed_ = r;
    state_.log_message("camera: follows " + state_.sim->scene().robots[r].id +
                       ", which touches nothing and was leaving the view (Configuration: keep "
                       "in view)");
  }

  /// Where the scene's bounding box (the one F frames) lands in the window, in pixels, and the
  /// 3-D view's rectangle (`print scene-box`, tests).
  void print_scene_box() {
    Vec3f lo, hi;
    if (!drawables_.bounds(state_.sim->scene(), -1, lo, hi)) {
      std::printf("scene-box none\n");
      return;
    }
    const Rect& view = state_.layout_rects.world;
    const Mat4 vp = state_.camera.projection(view_aspect()) * state_.camera.view();
    float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec4f h = vp * Vec4f{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y,
                                 corner & 4 ? hi.z : lo.z, 1};
      const float w = h.w > 0 ? h.w : 1e-6f;  // behind the eye: far outside
      const float px = view.x + (h.x / w * 0.5f + 0.5f) * view.width;
      const float py = view.y + (0.5f - h.y / w * 0.5f) * view.height;
      x0 = std::min(x0, px), x1 = std::max(x1, px), y0 = std::min(y0, py), y1 = std::max(y1, py);
    }
    std::printf("scene-box %.1f %.1f %.1f %.1f view %.1f %.1f %.1f %.1f size %.3f %.3f %.3f\n", x0,
                y0, x1, y1, view.x, view.y, view.width, view.height, hi.x - lo.x, hi.y - lo.y,
                hi.z - lo.z);
    std::fflush(stdout);
  }

  void draw_windows() {
    draw_panels(state_);
    check_scripted_clicks();
  }

  /// A scripted click on a button that was not drawn this frame is an error in the script.
  void check_scripted_clicks() {
    if (!state_.scripted_clicks.empty()) {
      const std::string label = state_.scripted_clicks.front();
      state_.scripted_clicks.clear();
      throw Error(ErrorKind::usage, "script: no button '" + label + "' on screen");
    }
  }

  /// Prints where each robot's main body and its shadow land on screen, with its colour
  /// (tests check the screenshot's pixels there).
  void print_projections() {
    const auto& scene = state_.sim->scene();
    const Rect& view = state_.layout_rects.world;
    const Mat4 vp = state_.camera.projection(view_aspect()) * state_.camera.view();
    const Vec3f light = renderer_.light_direction();
    auto project = [&](const Vec3f& p, const char* what, const std::string& id,
                       const scene::Color* c) {
      const Vec4f h = vp * Vec4f{p.x, p.y, p.z, 1};
      const double px = view.x + (h.x / h.w * 0.5 + 0.5) * view.width;
      const double py = view.y + (0.5 - h.y / h.w * 0.5) * view.height;
      if (c)
        std::printf("%s %s %.1f %.1f %.3f %.3f %.3f\n", what, id.c_str(), px, py, c->r, c->g, c->b);
      else
        std::printf("%s %s %.1f %.1f\n", what, id.c_str(), px, py);
    };
    for (const auto& r : scene.robots) {
      if (r.main_body < 0) continue;
      const Pose& pose = state_.sim->body_pose(r.main_body + 1);
      const scene::Body& body = scene.bodies[r.main_body];
      if (body.geoms.empty()) continue;  // an imported link may have no collision geometry
      const Vec3f centre = to_f(pose * body.geoms.front().pose.position);
      project(centre, "robot", r.id, &body.geoms.front().visual.color);
      // Along the light onto the floor: where the centre's shadow falls.
      project(centre - light * (centre.z / light.z), "shadow", r.id, nullptr);
    }
    std::fflush(stdout);
  }

  /// Frames per second in the steady state: the first 10 frames (shader compilation, first
  /// uploads) are left out; the median and 95th percentile show the spread.
  static void report_frame_rate(std::vector<double> times_s) {
    const std::size_t skip = std::min<std::size_t>(10, times_s.size() / 2);
    times_s.erase(times_s.begin(), times_s.begin() + static_cast<long>(skip));
    if (times_s.empty()) {
      std::printf("frames: too few to measure\n");
      return;
    }
    double total_s = 0;
    for (double t : times_s)
      total_s += t;
    std::sort(times_s.begin(), times_s.end());
    std::printf(
        "frames %zu in %.3f s: %.1f frames per second (median frame %.2f ms, 95th "
        "percentile %.2f ms)\n",
        times_s.size(), total_s, times_s.size() / total_s, times_s[times_s.size() / 2] * 1e3,
        times_s[times_s.size() * 95 / 100] * 1e3);
  }

  /// Without vsync (Xvfb), sleep so the loop does not spin faster than 60 frames a second.
  static void cap_frame_rate(Clock::time_point frame_start) {
    const auto target = frame_start + std::chrono::microseconds(16'666);
    if (Clock::now() < target) std::this_thread::sleep_until(target);
  }

  GLFWwindow* window_;
  ViewerState state_;
  Renderer renderer_;
  SceneDrawables drawables_;
  UiScript script_;
  WorldInput input_;
  int followed_robot_ = -1;                  ///< the robot followed last frame, -1 = none
  int auto_followed_ = -1;                   ///< the robot kept in view now, -1 = none
  std::vector<bool> declined_;               ///< robots the user stopped following
  std::filesystem::path look_folder_;        ///< the folder whose floor and sky are applied
  std::optional<SavedCamera> start_camera_;  ///< a SimTwo project's camera, until first used
  FrameStepping stepping_;
};

}  // namespace

int run_viewer(const Options& options) {
  const bool headless =
      !options.screenshot_file.empty() || options.frames > 0 || !options.video_file.empty();
  Window window(options.width_px, options.height_px, !headless);
  glfwSwapInterval(options.no_frame_cap || headless ? 0 : 1);
  ImGuiContextGuard imgui(window.handle, !headless && options.script.empty());
  App app(options, window.handle);
  // A stepping thread given up may still run a component's code, which static destructors
  // and unloaded libraries would pull from under it: then the process ends at once.
  auto end_now = [](int code) {
    std::fflush(nullptr);
    std::_Exit(code);
  };
  try {
    const int code = app.run();
    if (app.abandoned_stepping()) end_now(code);
    return code;
  } catch (const Error& e) {
    if (!app.give_up_stepping()) throw;
    std::fprintf(stderr, "s2sim-view: error: %s\n", e.what());
    end_now(exit_code(e.kind()));
  }
  return 0;
}

}  // namespace s2sim::viewer
