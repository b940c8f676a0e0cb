// s2sim-view as a user (or the docs) drive it: the real binary under xvfb-run renders
// screenshots, runs scripted UI commands (the same buttons a mouse presses) and exports its
// chart; the tests check the pixels, the simulated time, the CSV against s2sim-run's and the
// scene editor's error handling. Each run is a few seconds of Mesa llvmpipe.

#include "viewer_test_support.hpp"

#include "viewer_png.hpp"

namespace {

using namespace viewer_test;

/// Whether some pixel within `radius` of (x, y) shows `colour` lit: the shading scales a
/// colour by 0.35 (ambient) to 1 and adds at most 0.2 of specular, so the pixel must have the
/// colour's chromaticity (each channel over their sum) and each channel in that range. A grey
/// body is then told from the light grey floor by its brightness.
bool colour_near(const Image& image, double x, double y, const double colour[3], int radius) {
  const double sum = colour[0] + colour[1] + colour[2];
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const int px = static_cast<int>(std::lround(x)) + dx;
      const int py = static_cast<int>(std::lround(y)) + dy;
      if (px < 0 || py < 0 || px >= image.width || py >= image.height) continue;
      const unsigned char* p = image.at(px, py);
      const double s = p[0] + p[1] + p[2] + 1e-9;
      bool close = true;
      for (int c = 0; c < 3; ++c)
        close = close && std::abs(p[c] / s - colour[c] / sum) < 0.06 &&
                p[c] >= 0.3 * colour[c] * 255 - 2 && p[c] <= (colour[c] + 0.25) * 255 + 2;
      if (close && s > 30) return true;
    }
  return false;
}

struct Projection {
  double x = 0, y = 0;
  double colour[3] = {0, 0, 0};
};

TEST_F(Viewer, ScreenshotShowsTheFloorTheRobotsInTheirColoursAndTheirShadows) {
  const fs::path png = dir_ / "world.png";
  // Seen low from the side the light casts the shadow to, around the framed scene's centre
  // (the framed start view has a wheel in front of the spot under the body's centre).
  const std::string camera = "camera -145 20 0.6";
  const Result r =
      view(robot_scene().string(), {"--screenshot", png.string(), "--frames", "3", "--hide-ui",
                                    "--print-projections", "--do", "wait 1", "--do", camera});
  ASSERT_EQ(r.status, 0) << r.err;
  const Image image = read_png(png);
  ASSERT_EQ(image.width, 1280) << "no PNG written";
  ASSERT_EQ(image.height, 720);

  // Not uniform: the luminance varies widely over the image.
  double lo = 255, hi = 0;
  for (int y = 0; y < image.height; y += 4)
    for (int x = 0; x < image.width; x += 4) {
      lo = std::min(lo, luminance(image.at(x, y)));
      hi = std::max(hi, luminance(image.at(x, y)));
    }
  EXPECT_GT(hi - lo, 100);

  // The floor: the lower middle of the view is light grey (with darker grid lines).
  int grey = 0;
  for (int x = 0; x < image.width; x += 8) {
    const unsigned char* p = image.at(x, image.height - 40);
    if (std::abs(p[0] - p[1]) < 12 && std::abs(p[1] - p[2]) < 12 && p[0] > 120) ++grey;
  }
  EXPECT_GT(grey, image.width / 8 / 2) << "the floor is not visible at the bottom of the view";

  // Each robot's main body carries its colour where it projects; its shadow darkens the floor.
  std::map<std::string, Projection> robots, shadows;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream in(line);
    std::string what, id;
    Projection p;
    in >> what >> id >> p.x >> p.y;
    if (what == "robot") {
      in >> p.colour[0] >> p.colour[1] >> p.colour[2];
      robots[id] = p;
    } else if (what == "shadow") {
      shadows[id] = p;
    }
  }
  ASSERT_FALSE(robots.empty()) << r.out;
  // The same frame without shadows, for comparison.
  const fs::path plain_png = dir_ / "no-shadows.png";
  const Result plain =
      view(robot_scene().string(), {"--screenshot", plain_png.string(), "--frames", "3",
                                    "--hide-ui", "--no-shadows", "--do", "wait 1", "--do", camera});
  ASSERT_EQ(plain.status, 0) << plain.err;
  const Image unshadowed = read_png(plain_png);
  ASSERT_EQ(unshadowed.width, image.width);
  int coloured = 0, shadowed = 0, on_screen = 0;
  for (const auto& [id, p] : robots) {
    if (colour_near(image, p.x, p.y, p.colour, 3))
      ++coloured;
    else
      ADD_FAILURE() << id << ": no pixel of colour " << p.colour[0] << " " << p.colour[1] << " "
                    << p.colour[2] << " near (" << p.x << ", " << p.y << ")";
    // The shadow: the floor where the body's centre projects along the light is darker than
    // the same pixels rendered without shadows.
    const Projection& s = shadows[id];
    const int sx = static_cast<int>(std::lround(s.x)), sy = static_cast<int>(std::lround(s.y));
    if (sx < 1 || sy < 1 || sx >= image.width - 1 || sy >= image.height - 1) continue;
    ++on_screen;
    double darkest_ratio = 1;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        darkest_ratio =
            std::min(darkest_ratio, luminance(image.at(sx + dx, sy + dy)) /
                                        (luminance(unshadowed.at(sx + dx, sy + dy)) + 1));
    if (darkest_ratio < 0.8)
      ++shadowed;
    else  // another body may stand between the camera and the shadow
      std::printf("%s: no shadow seen at (%.0f, %.0f)\n", id.c_str(), s.x, s.y);
  }
  EXPECT_EQ(coloured, static_cast<int>(robots.size()));
  EXPECT_GT(shadowed, 0) << "no robot's shadow on the floor";
  EXPECT_GE(2 * shadowed, on_screen) << "most robots' shadows are missing";
}

std::vector<double> printed_times(const std::string& out) {
  std::vector<double> times;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("time ", 0) == 0) times.push_back(std::stod(line.substr(5)));
  return times;
}

TEST_F(Viewer, PauseStepAndResetButtonsDriveTheSimulatedTime) {
  const Result r =
      view((kSource / "scenes/default").string(),
           {"--do", "wait 5",     "--do", "click Pause", "--do", "print time", "--do", "wait 3",
            "--do", "print time", "--do", "click Step",  "--do", "print time", "--do", "click Step",
            "--do", "print time", "--do", "click Reset", "--do", "print time", "--do", "click Play",
            "--do", "wait 2",     "--do", "print time"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto t = printed_times(r.out);
  ASSERT_EQ(t.size(), 6u) << r.out;
  const double tick_s = 0.001;  // the default scene's physics step
  EXPECT_GT(t[0], 0.05) << "the scene did not play before Pause";
  EXPECT_DOUBLE_EQ(t[1], t[0]) << "time moved while paused";
  EXPECT_NEAR(t[2], t[0] + tick_s, 1e-9) << "Step did not advance exactly one tick";
  EXPECT_NEAR(t[3], t[0] + 2 * tick_s, 1e-9);
  EXPECT_EQ(t[4], 0.0) << "Reset did not go back to t = 0";
  EXPECT_GT(t[5], 0.0) << "Play did not restart the run";
}

// The Run window's real-time factor is the simulated time over the wall
// time. The run is paced by the wall clock as an interactive one is (`pace wall`); the test
// reads the simulated time and the viewer's steady clock 60 frames apart and the factor the
// Run window shows at the end.
TEST_F(Viewer, RunWindowRealTimeFactorIsSimulatedOverWallTime) {
  for (const char* speed : {"1", "0.5"}) {
    const Result r =
        view((kSource / "scenes/default").string(),
             {"--do", "pace wall", "--do", std::string("speed ") + speed, "--do", "wait 30", "--do",
              "print clock", "--do", "wait 60", "--do", "print clock", "--do", "print rtf"});
    ASSERT_EQ(r.status, 0) << r.err;
    std::istringstream out(r.out);
    std::vector<std::pair<double, double>> clocks;  // (simulated, wall)
    double shown = -1;
    for (std::string line; std::getline(out, line);) {
      double sim_s = 0, wall_s = 0;
      if (std::sscanf(line.c_str(), "clock %lf %lf", &sim_s, &wall_s) == 2)
        clocks.emplace_back(sim_s, wall_s);
      std::sscanf(line.c_str(), "rtf real-time factor %lfx", &shown);
    }
    ASSERT_EQ(clocks.size(), 2u) << r.out;
    ASSERT_GT(shown, 0) << "the Run window shows no real-time factor:\n" << r.out;
    const double measured =
        (clocks[1].first - clocks[0].first) / (clocks[1].second - clocks[0].second);
    EXPECT_NEAR(shown, measured, 0.1 * measured) << "speed " << speed << "\n" << r.out;
    EXPECT_NEAR(shown, std::stod(speed), 0.1 * std::stod(speed)) << r.out;
  }
}

TEST_F(Viewer, ChartExportEqualsTheRunnersCsvForTheSameSeed) {
  // The NXT's motor speeds and currents while it drives at 6 V; on a scene without motors any
  // other signals work the same way (the code is shared, apps/common/signal_csv.hpp).
  const fs::path scene = robot_scene();
  const bool nxt = scene.filename() == "nxt";
  const std::vector<std::string> signals =
      nxt ? std::vector<std::string>{"robots/nxt/axes/*/speed", "robots/nxt/axes/*/current"}
          : std::vector<std::string>{"robots/*/axes/*/pos", "robots/*/axes/*/speed"};
  const std::vector<std::string> inputs =
      nxt ? std::vector<std::string>{"robots/nxt/axes/right/ref_voltage=6",
                                     "robots/nxt/axes/left/ref_voltage=-6"}
          : std::vector<std::string>{};
  const fs::path runner_csv = dir_ / "runner.csv", chart_csv = dir_ / "chart.csv";
  std::string command = quote(kRunner.string()) + " " + quote(scene.string()) +
                        " --duration 1 --seed 7 --quiet --log " + quote(runner_csv.string());
  for (const auto& i : inputs) {
    command += " --set ";
    command += quote(i);
  }
  command += " --signals";
  for (const auto& s : signals) {
    command += ' ';
    command += quote(s);
  }
  const Result runner = run(command, dir_);
  ASSERT_EQ(runner.status, 0) << runner.err;

  std::vector<std::string> args = {"--seed", "7", "--hide-ui"};
  for (const auto& i : inputs)
    args.insert(args.end(), {"--set", i});
  args.push_back("--chart");
  args.insert(args.end(), signals.begin(), signals.end());
  for (const char* c : {"speed 0", "run-until 1", "show chart"})
    args.insert(args.end(), {"--do", c});
  args.insert(args.end(), {"--do", "chart-csv " + chart_csv.string(), "--do", "click Export CSV",
                           "--do", "print time"});
  const Result viewer = view(scene.string(), args);
  ASSERT_EQ(viewer.status, 0) << viewer.err;
  EXPECT_EQ(printed_times(viewer.out), std::vector<double>{1.0});
  const std::string expected = read_file(runner_csv), got = read_file(chart_csv);
  ASSERT_FALSE(got.empty()) << "the chart wrote no CSV";
  EXPECT_GT(std::count(expected.begin(), expected.end(), '\n'), 1000);
  if (nxt) {
    EXPECT_NE(expected.find("/current [A]"), std::string::npos) << expected.substr(0, 300);
  }
  EXPECT_TRUE(expected == got) << "the chart's CSV differs from s2sim-run's (first 300 bytes)\n"
                               << expected.substr(0, 300) << "\n---\n"
                               << got.substr(0, 300);
}

TEST_F(Viewer, ApplyingAnEditReloadsTheSceneAndKeepsTheCamera) {
  const fs::path scene = dir_ / "scene";
  fs::copy(kSource / "scenes/default", scene, fs::copy_options::recursive);
  const Result r =
      view(scene.string(), {"--do",
                            "camera 30 20 4",
                            "--do",
                            "wait 20",
                            "--do",
                            "print camera",
                            "--do",
                            "editor-open scene.xml",
                            "--do",
                            "editor-insert 5 <robot><ID name='extra'/><pos x='3' y='3' z='0'/>"
                            "<body file='pendulum.xml'/></robot>",
                            "--do",
                            "click Apply",
                            "--do",
                            "print editor-error",
                            "--do",
                            "print camera",
                            "--do",
                            "print time",
                            "--do",
                            "print signal robots/extra/y"});
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<std::string> cameras;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("camera ", 0) == 0) cameras.push_back(line);
  ASSERT_EQ(cameras.size(), 2u) << r.out;
  EXPECT_EQ(cameras[0], cameras[1]) << "the camera moved on reload";
  EXPECT_NE(r.out.find("editor-error -1 \n"), std::string::npos) << r.out;
  // The new scene runs from the start and has the new robot.
  const auto t = printed_times(r.out);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_LT(t[0], 0.05);
  EXPECT_NE(r.out.find("signal robots/extra/y 3\n"), std::string::npos) << r.out;
  EXPECT_NE(read_file(scene / "scene.xml").find("name='extra'"), std::string::npos);
}

TEST_F(Viewer, SyntaxErrorInTheSceneEditorIsReportedWithItsLineAndKeepsTheScene) {
  // A copy: applying writes the scene's files.
  const fs::path scene = dir_ / "scene";
  fs::copy(kSource / "scenes/default", scene, fs::copy_options::recursive);
  const std::string original = read_file(scene / "scene.xml");
  const Result r = view(scene.string(), {"--do", "wait 3", "--do", "editor-open scene.xml", "--do",
                                         "editor-insert 12 <oops a=>", "--do", "click Apply",
                                         "--do", "print editor-error", "--do", "print time", "--do",
                                         "wait 5", "--do", "print time"});
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream lines(r.out);
  int error_line = 0;
  std::string message;
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("editor-error ", 0) == 0) {
      std::istringstream in(line.substr(13));
      in >> error_line;
      std::getline(in, message);
    }
  EXPECT_EQ(error_line, 12) << r.out;
  EXPECT_NE(message.find("scene.xml:12"), std::string::npos) << message;
  // The running scene is kept (time goes on) and the file on disk is the one it came from.
  const auto t = printed_times(r.out);
  ASSERT_EQ(t.size(), 2u) << r.out;
  EXPECT_GT(t[1], t[0]);
  EXPECT_EQ(read_file(scene / "scene.xml"), original);
}

/// The kernel's component fixture (a thing `box`, test plugins) with extra `<plugin>` lines.
fs::path fixture_with_plugins(const fs::path& dir, const std::string& plugins) {
  const fs::path scene = dir / "fixture";
  fs::copy(kSource / "tests/kernel/sim/fixtures/components", scene, fs::copy_options::recursive);
  std::string text = read_file(scene / "scene.xml");
  const auto end = text.rfind("</scene>");
  text.insert(end, plugins);
  std::ofstream(scene / "scene.xml", std::ios::binary) << text;
  return scene;
}

// The test plugins, then the first-party ones (the fixture's axes need the drive train).
const std::string kTestPlugins = (fs::path(S2SIM_TEST_PLUGIN_DIR) / "scene").string();
const std::string kFirstPartyPlugins = S2SIM_PLUGIN_DIR;

TEST_F(Viewer, MovingAThingPlacesItAtRestWhereItIsDropped) {
  const fs::path scene = fixture_with_plugins(dir_, "");
  const Result r =
      view(scene.string(), {"--plugin-path", kTestPlugins, "--plugin-path", kFirstPartyPlugins,
                            "--do", "wait 3", "--do", "move box -1 0.5 2", "--do", "print body box",
                            "--do", "move bob 0 0 1", "--do", "print body box"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("body box -1.000000000 0.500000000 2.000000000"), std::string::npos)
      << r.out;
  // A jointed body is refused with a message, not a crash; the script goes on.
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 2) << r.out;
}

TEST_F(Viewer, SheetCellsAreInputsThatControllersReadAndWrite) {
  // A controller writes A1; two components read B2 (a number) and C1 (a button). The cells
  // are set the way the Sheet window sets them.
  const fs::path scene = fixture_with_plugins(
      dir_,
      "  <plugin kind='test_reference_controller' id='writer' input='sheet/A1' value='2.5' "
      "period_ms='40'/>\n"
      "  <plugin kind='test_echo_sensor' id='number' input='sheet/B2'/>\n"
      "  <plugin kind='test_echo_sensor' id='button' input='sheet/C1' unit='button'/>\n");
  const Result r = view(scene.string(), {"--plugin-path", kTestPlugins,
                                         "--plugin-path", kFirstPartyPlugins,
                                         "--show-window", "sheet",
                                         "--do",          "wait 3",
                                         "--do",          "sheet-set B2 4",
                                         "--do",          "click C1",
                                         "--do",          "wait 2",
                                         "--do",          "print signal sheet/A1",
                                         "--do",          "print signal sensors/number/seen",
                                         "--do",          "print signal sensors/button/seen"});
  ASSERT_EQ(r.status, 0) << r.err;
  // The controller writes value x its update count: 2.5 at its first update, then 5, 7.5...
  const auto a1 = r.out.find("signal sheet/A1 ");
  ASSERT_NE(a1, std::string::npos) << r.out;
  const double written = std::stod(r.out.substr(a1 + 16));
  EXPECT_GT(written, 0);
  EXPECT_DOUBLE_EQ(std::fmod(written, 2.5), 0.0) << written;
  EXPECT_NE(r.out.find("signal sensors/number/seen 4\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("signal sensors/button/seen 1\n"), std::string::npos) << r.out;
}

// The NXT driving a curve leaves a trail as long as the path its body travelled,
// drawn over the view (the screenshot is kept in the test's folder for a look).
TEST_F(Viewer, TrailFollowsTheRobotsPath) {
  const Result r = view(robot_scene().string(),
                        {"--set", "robots/nxt/axes/right/ref_voltage=6", "--set",
                         "robots/nxt/axes/left/ref_voltage=3", "--do", "overlay trails on", "--do",
                         "overlay labels on", "--do", "run-until 3", "--do", "print trail nxt",
                         "--do", "screenshot " + (dir_ / "trail.png").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  unsigned points = 0;
  double length_m = 0;
  const auto at = r.out.find("trail nxt ");
  ASSERT_NE(at, std::string::npos) << r.out;
  ASSERT_EQ(std::sscanf(r.out.c_str() + at, "trail nxt %u %lf", &points, &length_m), 2);
  EXPECT_GT(points, 20u) << r.out;
  // Driving a curve at these voltages the body moves some decimetres in 3 s.
  EXPECT_GT(length_m, 0.1) << r.out;
  EXPECT_LT(length_m, 10.0) << r.out;
}

/// Every shipped scene: scenes/* and the shared SimTwo projects next to the checkout.
std::vector<fs::path> shipped_scenes() {
  std::vector<fs::path> scenes;
  for (const fs::path& root : {kSource / "scenes", kSource / "../shared/simtwo-scenes"}) {
    if (!fs::is_directory(root)) continue;
    for (const auto& entry : fs::directory_iterator(root))
      if (fs::exists(entry.path() / "scene.xml")) scenes.push_back(entry.path());
  }
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

struct Box {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// The view framed: at start, and again after the camera was moved away and
// F (`frame`) was pressed, the scene's bounding box (its solids, shells and obstacles) projects
// inside the 3-D view (the window minus the Run window's column), and fills a good part of it
// (scenes/nxt used to fill 10 % of the width).
TEST_F(Viewer, EveryShippedSceneStartsFramedAndFReframes) {
  const auto scenes = shipped_scenes();
  ASSERT_GE(scenes.size(), 5u);
  for (const fs::path& scene : scenes) {
    // `print scene-box` prints at the end of the frame, after the camera command of the same
    // frame: hence the `wait 1` after it.
    std::vector<std::string> args{
        "--do", "wait 2", "--do", "print scene-box", "--do", "wait 1", "--do", "camera 10 5 300",
        "--do", "wait 1", "--do", "frame",           "--do", "wait 1", "--do", "print scene-box"};
    // A free port for a remote link (cartpole_remote, firefighting_omni): another program may
    // hold its default; and no client comes, so its lock-step link need not wait for one.
    if (scene.filename() == "cartpole_remote" || scene.filename() == "firefighting_omni") {
      for (const char* define : {"remote_port=0", "remote_wait_s=0.01"}) {
        args.push_back("--define");
        args.push_back(define);
      }
    }
    const Result r = view(scene.string(), args);
    ASSERT_EQ(r.status, 0) << scene << "\n" << r.err;
    std::istringstream out(r.out);
    int seen = 0;
    for (std::string line; std::getline(out, line);) {
      Box box, view;
      if (std::sscanf(line.c_str(), "scene-box %lf %lf %lf %lf view %lf %lf %lf %lf", &box.x0,
                      &box.y0, &box.x1, &box.y1, &view.x0, &view.y0, &view.x1, &view.y1) != 8)
        continue;
      ++seen;
      view.x1 += view.x0;  // printed as x, y, width, height
      view.y1 += view.y0;
      EXPECT_GE(box.x0, view.x0) << scene << ": " << line;
      EXPECT_GE(box.y0, view.y0) << scene << ": " << line;
      EXPECT_LE(box.x1, view.x1) << scene << ": " << line;
      EXPECT_LE(box.y1, view.y1) << scene << ": " << line;
      // A SimTwo project starts with its author's camera (moved back if the scene does not
      // fit): only the framing by F must fill the view.
      const double fill = std::max((box.x1 - box.x0) / (view.x1 - view.x0),
                                   (box.y1 - box.y0) / (view.y1 - view.y0));
      if (seen == 2 || !fs::exists(scene / "SimTwo.ini")) {
        EXPECT_GT(fill, 0.6) << scene << ": the scene is lost in the distance: " << line;
      }
    }
    EXPECT_EQ(seen, 2) << scene << "\n" << r.out;
  }
}

// The panels tiled: with every panel open, what ImGui placed does not
// overlap, stays in the window, and the 3-D view keeps at least half of it. The screenshot is
// kept in the test's folder for a look.
TEST_F(Viewer, WithAllPanelsOpenNoPanelOverlapsAndTheViewKeepsHalfTheWindow) {
  for (const char* font_scale : {"1", "2"}) {  // 2: a HiDPI screen's text
    std::vector<std::string> args{"--font-scale", font_scale};
    for (const char* w : {"configuration", "body", "log", "chart", "sheet", "editor"})
      args.insert(args.end(), {"--show-window", w});
    args.insert(
        args.end(),
        {"--do", "wait 3", "--do", "print layout", "--do",
         "screenshot " + (dir_ / ("all-panels-" + std::string(font_scale) + ".png")).string()});
    const Result r = view((kSource / "scenes/default").string(), args);
    ASSERT_EQ(r.status, 0) << r.err;
    std::map<std::string, Box> rects;
    std::istringstream out(r.out);
    for (std::string line; std::getline(out, line);) {
      char name[64] = {};
      Box b;
      if (std::sscanf(line.c_str(), "layout %63s %lf %lf %lf %lf", name, &b.x0, &b.y0, &b.x1,
                      &b.y1) == 5) {
        b.x1 += b.x0;
        b.y1 += b.y0;
        rects[name] = b;
      }
    }
    for (const char* expected : {"run", "left", "bottom", "menu", "world", "window"})
      ASSERT_TRUE(rects.count(expected)) << expected << " not placed:\n" << r.out;
    const Box window = rects.at("window");
    rects.erase("window");
    const double eps = 0.5;  // ImGui rounds positions to whole pixels
    for (const auto& [a, ra] : rects) {
      EXPECT_GE(ra.x0, -eps) << a;
      EXPECT_GE(ra.y0, -eps) << a;
      EXPECT_LE(ra.x1, window.x1 + eps) << a;
      EXPECT_LE(ra.y1, window.y1 + eps) << a;
      for (const auto& [b, rb] : rects)
        if (a < b) {
          const double w = std::min(ra.x1, rb.x1) - std::max(ra.x0, rb.x0);
          const double h = std::min(ra.y1, rb.y1) - std::max(ra.y0, rb.y0);
          EXPECT_FALSE(w > eps && h > eps) << a << " overlaps " << b << "\n" << r.out;
        }
    }
    const Box& world = rects.at("world");
    EXPECT_GE((world.x1 - world.x0) * (world.y1 - world.y0), 0.5 * window.x1 * window.y1) << r.out;
    EXPECT_TRUE(fs::exists(dir_ / ("all-panels-" + std::string(font_scale) + ".png")));
    // The menu bar grows with the font.
    EXPECT_GT(rects.at("menu").y1, std::string(font_scale) == "2" ? 30 : 10) << r.out;
  }
}

TEST_F(Viewer, BadOptionsAndScenesAreClearErrorsNotCrashes) {
  const Result missing = view((dir_ / "nowhere").string(), {"--frames", "1"});
  EXPECT_EQ(missing.status, 2) << missing.err;
  EXPECT_NE(missing.err.find("nowhere"), std::string::npos) << missing.err;
  const Result option = view((kSource / "scenes/default").string(), {"--frobnicate"});
  EXPECT_EQ(option.status, 4);
  EXPECT_NE(option.err.find("--frobnicate"), std::string::npos) << option.err;
  const Result script = view((kSource / "scenes/default").string(), {"--do", "wait many"});
  EXPECT_EQ(script.status, 4);
  EXPECT_NE(script.err.find("wait many"), std::string::npos) << script.err;
  const Result signal =
      view((kSource / "scenes/default").string(), {"--frames", "1", "--chart", "no/such"});
  EXPECT_EQ(signal.status, 4);
  EXPECT_NE(signal.err.find("no/such"), std::string::npos) << signal.err;
}

// A component whose update never returns froze the viewer: no frame was drawn and the window
// could not be closed. Now the window draws on, names the call and how long it has run, and
// "Stop the simulation" gives the run up, loading the scene again, paused. A run paced by
// frames stops at --watchdog (exit 8), and closing the window on a stuck call is exit 8 too.
TEST_F(Viewer, AComponentThatNeverReturnsLeavesTheWindowDrawingAndCanBeStopped) {
  const fs::path scene = dir_ / "hang";
  fs::create_directories(scene);
  std::ofstream(scene / "scene.xml") << "<scene>\n"
                                        "  <plugin kind='test_hostile' id='villain' "
                                        "mode='update_hang'/>\n"
                                        "</scene>\n";
  const std::string plugins = (fs::path(S2SIM_TEST_PLUGIN_DIR) / "hostile").string();
  const std::string villain = "component 'controllers/villain' (kind 'test_hostile')";

  const Result stopped =
      view(scene.string(), {"--plugin-path", plugins,
                            "--do",          "pace wall",
                            "--do",          "wait 60",
                            "--do",          "print stuck",
                            "--do",          "click Stop the simulation",
                            "--do",          "wait 2",
                            "--do",          "print stuck",
                            "--do",          "print time",
                            "--do",          "print log-count stopped: " + villain,
                            "--do",          "click Play",
                            "--do",          "wait 20",
                            "--do",          "print stuck",
                            "--do",          "quit"});
  // Quit while the second call hangs: the viewer does not wait for it, and says so (exit 8).
  EXPECT_EQ(stopped.status, 8) << stopped.err;
  EXPECT_NE(stopped.err.find("the window closed while " + villain), std::string::npos)
      << stopped.err;
  const std::vector<std::string> stuck = lines_with(stopped.out, "stuck ");
  ASSERT_EQ(stuck.size(), 3u) << stopped.out;
  EXPECT_EQ(stuck[0].rfind("yes ", 0), 0u) << stuck[0];
  EXPECT_NE(stuck[0].find(villain), std::string::npos) << stuck[0];
  EXPECT_GT(number_after(stopped.out, "stuck yes ", 0), 1.0) << "frames went on past the wait";
  EXPECT_EQ(stuck[1].rfind("no ", 0), 0u) << stuck[1];
  EXPECT_EQ(number_after(stopped.out, "time ", 0), 0) << "the scene is loaded again, paused";
  EXPECT_EQ(number_after(stopped.out, "log-count ", 0), 1) << stopped.out;
  // Played again, the reloaded scene's own call hangs: the notice names it with its own time,
  // not the given-up call's (which still runs on its thread).
  EXPECT_EQ(stuck[2].rfind("yes ", 0), 0u) << stuck[2];
  EXPECT_LT(number_after(stopped.out, "stuck yes ", 1), number_after(stopped.out, "stuck yes ", 0))
      << stopped.out;

  const Result paced =
      view(scene.string(), {"--plugin-path", plugins, "--frames", "100", "--watchdog", "0.5"});
  EXPECT_EQ(paced.status, 8) << paced.err;
  EXPECT_NE(paced.err.find("watchdog: " + villain), std::string::npos) << paced.err;
  EXPECT_NE(paced.err.find("has not returned for"), std::string::npos) << paced.err;
  const Result bad = view(scene.string(), {"--watchdog", "-1"});
  EXPECT_EQ(bad.status, 4);
  EXPECT_NE(bad.err.find("--watchdog"), std::string::npos) << bad.err;
}

// The quadrotor left the frame after 2 s: the camera framed the scene once. Now a robot that
// touches nothing is followed as it would leave the view. The boat floated over a grey floor:
// its water is drawn now, a translucent blue plane at the buoyancy's surface.
TEST_F(Viewer, AFlyingRobotIsKeptInViewAndABoatIsDrawnOnItsWater) {
  const Result quad =
      view((kSource / "scenes/quadrotor").string(),
           {"--do", "run-until 8", "--do", "print log-count camera: follows quad, which touches",
            "--do", "print body frame", "--do", "print camera"});
  ASSERT_EQ(quad.status, 0) << quad.err;
  EXPECT_EQ(number_after(quad.out, "log-count ", 0), 1) << quad.out;
  double body[3] = {0, 0, 0}, target[3] = {0, 0, 0}, yaw, pitch, distance;
  ASSERT_EQ(std::sscanf(lines_with(quad.out, "body frame ").at(0).c_str(), "%lf %lf %lf", &body[0],
                        &body[1], &body[2]),
            3);
  ASSERT_EQ(std::sscanf(lines_with(quad.out, "camera ").at(0).c_str(), "%lf %lf %lf %lf %lf %lf",
                        &yaw, &pitch, &distance, &target[0], &target[1], &target[2]),
            6);
  EXPECT_GT(body[2], 0.5) << "flying";
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(target[k], body[k], 0.05) << "the camera looks at the quadrotor, axis " << k;

  const fs::path png = dir_ / "boat.png";
  const Result boat =
      view((kSource / "scenes/boat").string(),
           {"--hide-ui", "--look", "fast", "--do", "run-until 1", "--do", "camera -120 25 5",
            "--do", "wait 1", "--do", "screenshot " + png.string()});
  ASSERT_EQ(boat.status, 0) << boat.err;
  const Image image = read_png(png);
  ASSERT_EQ(image.width, 1280) << "no PNG written";
  int blue = 0, samples = 0;  // the lower half of the view looks at the water over the floor
  for (int y = image.height / 2; y < image.height; y += 16)
    for (int x = 0; x < image.width; x += 16, ++samples) {
      const unsigned char* p = image.at(x, y);
      if (p[2] > p[0] + 25) ++blue;
    }
  EXPECT_GT(blue, samples * 3 / 4) << blue << " of " << samples << " samples are blue";
}

}  // namespace
