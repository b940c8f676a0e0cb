// The viewer's SimTwo side, through the real binary under xvfb-run: a
// project's script runs with its sheet, the Script window lists located compile errors and
// shows their line, Compile/Run/Stop/Save and reloading after an external edit; the HUD,
// WriteLn lines in the Log, script trails and the XY chart; the chart's bounded memory;
// Reset after --set replays the run; the scene editor validates an edit before writing it.
// Some runs save the pictures of docs/ (S2SIM_DOC_IMAGES names the folder; the test's own
// folder otherwise).

#include "viewer_png.hpp"
#include "viewer_test_support.hpp"

#include <chrono>
#include <tuple>

namespace {

using namespace viewer_test;

const fs::path kShared = S2SIM_SHARED_SCENES;
const fs::path kFixtures = S2SIM_VIEWER_FIXTURES;

class ViewerScript : public Viewer {
 protected:
  void SetUp() override {
    Viewer::SetUp();
    if (IsSkipped()) return;
    // One compile cache for every test (the pascal_script tests share it).
    ::setenv("S2SIM_PASCAL_CACHE", S2SIM_PASCAL_TEST_CACHE, 1);
    if (std::system("command -v fpc >/dev/null 2>&1") != 0)
      GTEST_SKIP() << "fpc is missing: scripts/install-deps.sh installs it";
  }
  /// A copy of a shared SimTwo project (scripts and the editor write files).
  fs::path project(const std::string& name) {
    const fs::path copy = dir_ / name;
    fs::copy(kShared / name, copy, fs::copy_options::recursive);
    return copy;
  }
  /// MotorModel_V3AGM's control.pas reads its gains and reference from cells its sheet lacks
  /// (as in tests/plugins/pascal_script): the options that set them.
  static std::vector<std::string> motor_model_sheet() {
    return {"--sheet", "1,4=1000", "--sheet",  "2,10=0.1", "--sheet",
            "3,10=0",  "--sheet",  "2,7=0.05", "--sheet",  "3,7=1"};
  }
  static std::vector<std::string> joined(std::vector<std::string> a,
                                         const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
  }
  /// The cart-pole under `script` at `until_s`, screenshot without the UI to `name`.png; no
  /// warning on the way.
  Image cartpole_at(const std::string& script, double until_s, const std::string& name) {
    const fs::path png = dir_ / (name + ".png");
    const Result r =
        view((kSource / "scenes/cartpole").string(),
             {"--script-file", script, "--do", "speed 0", "--do",
              "run-until " + std::to_string(until_s), "--hide-ui", "--screenshot", png.string()});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
    const Image image = read_png(png);
    EXPECT_GT(image.width, 0) << name;
    return image;
  }
  /// Where a picture for docs/ goes.
  fs::path picture(const std::string& file) {
    const char* docs = std::getenv("S2SIM_DOC_IMAGES");
    return (docs && *docs ? fs::path(docs) : dir_) / file;
  }
};

// MotorModel_V3AGM names control_PosCascata.pas, which
// does not compile in SimTwo either. Its control block is None, so the project opens without
// running it; Compile lists fpc's located error, the simulation goes on, and choosing the
// error shows its line.
TEST_F(ViewerScript, CompileErrorIsListedWithItsLocationAndShowsItsLine) {
  const fs::path scene = project("MotorModel_V3AGM");
  const Result r =
      view(scene.string(),
           {"--show-window", "script",
            "--show-window", "log",
            "--do",          "wait 3",
            "--do",          "click Compile",
            "--do",          "wait 1",
            "--do",          "print script-errors",
            "--do",          "script-goto-error 1",
            "--do",          "wait 3",
            "--do",          "print script-view",
            "--do",          "print script-status",
            "--do",          "print time",
            "--do",          "screenshot " + picture("viewer-script-error.png").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto errors = lines_with(r.out, "script-error ");
  ASSERT_FALSE(errors.empty()) << r.out;
  EXPECT_NE(errors[0].find("control_PosCascata.pas 38 3 Fatal: Syntax error"), std::string::npos)
      << errors[0];
  int first = 0, last = 0, highlight = 0;
  ASSERT_EQ(std::sscanf(lines_with(r.out, "script-view ").at(0).c_str(), "%d %d %d", &first, &last,
                        &highlight),
            3);
  EXPECT_EQ(highlight, 38);
  EXPECT_LE(first, 38);
  EXPECT_GE(last, 38);
  EXPECT_EQ(lines_with(r.out, "script-status ").at(0).substr(0, 3), "0 0") << r.out;
  EXPECT_GT(number_after(r.out, "time "), 0.0) << "the scene runs without its script";
}

// The Run/Stop buttons: MotorModel's control.pas
// runs (WriteLn, HUDStrings), Stop holds its calls, Run starts it afresh (Initialize again).
TEST_F(ViewerScript, ProjectRunsUnderItsScriptAndStopAndRunControlIt) {
  const fs::path scene = project("MotorModel_V3AGM");
  const Result r =
      view(scene.string(),
           joined(motor_model_sheet(), {"--script-file", (scene / "control.pas").string(),
                                        "--show-window", "sheet",
                                        "--show-window", "log",
                                        "--do",          "speed 0",
                                        "--do",          "run-until 1",
                                        "--do",          "print signal controllers/script/calls",
                                        "--do",          "print hud",
                                        "--do",          "print log-count 123 Init",
                                        "--do",          "show script",
                                        "--do",          "wait 1",
                                        "--do",          "click Stop",
                                        "--do",          "wait 2",
                                        "--do",          "run-until 2",
                                        "--do",          "print signal controllers/script/calls",
                                        "--do",          "print script-status",
                                        "--do",          "click Run",
                                        "--do",          "wait 2",
                                        "--do",          "run-until 3",
                                        "--do",          "print signal controllers/script/calls",
                                        "--do",          "print log-count 123 Init",
                                        "--do",          "print script-status"}));
  ASSERT_EQ(r.status, 0) << r.err;
  const double calls_1 = number_after(r.out, "signal controllers/script/calls ", 0);
  const double calls_2 = number_after(r.out, "signal controllers/script/calls ", 1);
  const double calls_3 = number_after(r.out, "signal controllers/script/calls ", 2);
  EXPECT_NEAR(calls_1, 25, 1) << "one call per 40 ms";
  EXPECT_NEAR(calls_2, calls_1, 1) << "Stop holds the calls";
  EXPECT_GT(calls_3, calls_2 + 20) << "Run resumes them";
  EXPECT_EQ(lines_with(r.out, "hud ").at(0), "Test");
  EXPECT_EQ(number_after(r.out, "log-count ", 0), 1) << "WriteLn reaches the Log";
  EXPECT_EQ(number_after(r.out, "log-count ", 1), 2) << "Run calls Initialize again";
  EXPECT_EQ(lines_with(r.out, "script-status ").at(0).substr(0, 3), "1 0");
  EXPECT_EQ(lines_with(r.out, "script-status ").at(1).substr(0, 3), "1 1");
}

// The picture of a SimTwo project under its script with its sheet: RobotFactoryLite, its
// [Set] button pressed (row 11, column 3) so the script places the AGV.
TEST_F(ViewerScript, RobotFactorySheetButtonReachesTheScript) {
  const fs::path scene = project("RobotFactoryLite");
  const Result r =
      view(scene.string(), {"--run-script",
                            "--show-window",
                            "sheet",
                            "--show-window",
                            "log",
                            "--do",
                            "speed 0",
                            "--do",
                            "run-until 0.5",
                            "--do",
                            "print signal sheet/C11",
                            "--do",
                            "click Set##C11",
                            "--do",
                            "wait 1",
                            "--do",
                            "print signal sheet/C11",
                            "--do",
                            "run-until 1.5",
                            "--do",
                            "print signal sheet/C11",
                            "--do",
                            "print signal controllers/script/error",
                            "--do",
                            "screenshot " + picture("viewer-script-sheet.png").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(number_after(r.out, "signal sheet/C11 ", 0), 0);
  EXPECT_EQ(number_after(r.out, "signal sheet/C11 ", 1), 1) << "the click latched";
  EXPECT_EQ(number_after(r.out, "signal sheet/C11 ", 2), 0) << "the script consumed it";
  EXPECT_EQ(number_after(r.out, "signal controllers/script/error "), 0);
}

// The editor: a broken line saved by Compile is a located error and the running simulation is
// kept; another program writing the file makes the editor read it again.
TEST_F(ViewerScript, CompileKeepsTheRunningScriptOnErrorAndExternalEditsAreReloaded) {
  const fs::path scene = project("MotorModel_V3AGM");
  const fs::path script = scene / "control.pas";
  const std::string original = read_file(script);
  const std::string line_10 = lines_with(original, "").at(9);
  // Another program restores the file once the viewer has saved the broken line.
  const std::string writer = "sh -c 'while ! grep -q \"this is not pascal\" " +
                             quote(script.string()) + "; do sleep 0.1; done; sleep 0.5; cp " +
                             quote((kShared / "MotorModel_V3AGM/control.pas").string()) + " " +
                             quote(script.string()) + "' &";
  ASSERT_EQ(std::system(writer.c_str()), 0);
  const Result r =
      view(scene.string(),
           joined(motor_model_sheet(), {"--script-file", script.string(),
                                        "--show-window", "script",
                                        "--do",          "run-until 0.5",
                                        "--do",          "script-set-line 10 this is not pascal",
                                        "--do",          "click Compile",
                                        "--do",          "print script-errors",
                                        "--do",          "print script-status",
                                        "--do",          "print time",
                                        "--do",          "sleep 3",
                                        "--do",          "wait 3",
                                        "--do",          "print script-line 10",
                                        "--do",          "print log-count changed on disk"}));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto errors = lines_with(r.out, "script-error ");
  ASSERT_FALSE(errors.empty()) << r.out;
  EXPECT_NE(errors[0].find("/control.pas 10 "), std::string::npos) << errors[0];
  EXPECT_EQ(lines_with(r.out, "script-status ").at(0).substr(0, 3), "1 1")
      << "the previous script keeps running";
  EXPECT_NEAR(number_after(r.out, "time "), 0.5, 0.01);
  EXPECT_EQ(lines_with(r.out, "script-line 10 ").at(0), line_10);
  EXPECT_EQ(number_after(r.out, "log-count "), 1);
  EXPECT_EQ(read_file(script), original);
}

// A script's trail (AddTrailNode), its XY series (ChartSeriesAddXY),
// its HUD lines, and the chart's XY mode plotting the robot's y against its x, whose CSV is
// s2sim-run's for the same signals.
TEST_F(ViewerScript, ScriptTrailHudAndXyChart) {
  const fs::path scene = project("base");
  const fs::path script = kFixtures / "trail_xy.pas";
  const fs::path chart_csv = dir_ / "chart.csv", runner_csv = dir_ / "runner.csv";
  const Result r =
      view(scene.string(),
           {"--script-file", script.string(),
            "--show-window", "chart",
            "--show-window", "log",
            "--do",          "chart-xy robots/Classic/x robots/Classic/y",
            "--do",          "speed 0",
            "--do",          "run-until 4",
            "--do",          "print script-trails",
            "--do",          "print xy-series",
            "--do",          "print hud",
            "--do",          "print log-count ten calls",
            "--do",          "chart-csv " + chart_csv.string(),
            "--do",          "click Export CSV",
            "--do",          "wait 2",
            "--do",          "screenshot " + picture("viewer-script-trail-xy.png").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto trails = lines_with(r.out, "script-trail ");
  ASSERT_EQ(trails.size(), 1u) << r.out;
  EXPECT_EQ(trails[0], "controllers/script 0 100");  // one node per 40 ms call
  EXPECT_EQ(lines_with(r.out, "xy-series ").at(0), "controllers/script 0 100");
  EXPECT_EQ(lines_with(r.out, "hud ").at(0).rfind("calls 100 | x ", 0), 0u) << r.out;
  EXPECT_EQ(number_after(r.out, "log-count "), 1);

  const Result runner = run(quote(kRunner.string()) + " " + quote(scene.string()) + " --script " +
                                quote(script.string()) +
                                " --duration 4 --quiet --signals robots/Classic/x "
                                "robots/Classic/y --log " +
                                quote(runner_csv.string()),
                            dir_);
  ASSERT_EQ(runner.status, 0) << runner.err;
  const std::string expected = read_file(runner_csv);
  EXPECT_GT(std::count(expected.begin(), expected.end(), '\n'), 1000);
  EXPECT_TRUE(expected == read_file(chart_csv)) << "the XY chart's CSV differs from s2sim-run's";
}

// Every signal of the largest shared SimTwo project (`default`, 881
// signals at 1 kHz) charted and drawn for 3 minutes simulated stays under the documented bound
// (docs/viewer.md, "Chart memory"): the chart holds at most ChartData::kMaxStoredValues numbers
// (64 MB; here the last 7.2 s) and draws at most kMaxChartSegments segments a frame, so the
// process's peak memory exceeds that of a run without the chart by less than 128 MB. The
// baseline runs 5 s: a longer run without the chart holds no more, which only makes the
// comparison stricter. (Before the draw budget, drawing the chart took 650 MB more.)
TEST_F(ViewerScript, ChartingEverySignalFor3MinutesStaysUnderTheMemoryBound) {
  const fs::path scene = kShared / "default";
  auto run_for = [&](const char* until, std::vector<std::string> args) {
    for (const char* c : {"speed 0", until, "print chart-samples", "print memory"})
      args.insert(args.end(), {"--do", c});
    const Result r = view(scene.string(), args);
    EXPECT_EQ(r.status, 0) << r.err;
    std::printf("%s", r.out.c_str());
    long rss_kB = 0, peak_kB = 0;
    std::sscanf(lines_with(r.out, "memory ").at(0).c_str(), "%ld %ld", &rss_kB, &peak_kB);
    std::size_t samples = 0;
    double first_s = 0, last_s = 0;
    std::sscanf(lines_with(r.out, "chart-samples ").at(0).c_str(), "%zu %lf %lf", &samples,
                &first_s, &last_s);
    return std::tuple(peak_kB, samples, first_s, last_s);
  };
  const long without_kB = std::get<0>(run_for("run-until 5", {"--no-script"}));
  const auto [with_kB, samples, first_s, last_s] =
      run_for("run-until 180", {"--no-script", "--chart", "*"});
  EXPECT_LT(with_kB - without_kB, 128 * 1024)
      << "peak " << with_kB << " kB against " << without_kB << " kB without the chart";
  EXPECT_NEAR(last_s, 180, 1e-6);
  EXPECT_GT(first_s, 170) << "the oldest samples were dropped";
  EXPECT_GT(samples, 5000u) << "but seconds of them are kept";
}

// --chart-span keeps the last SECONDS of simulated time.
TEST_F(Viewer, ChartSpanKeepsTheLastSeconds) {
  const Result r = view(robot_scene().string(),
                        {"--hide-ui", "--chart", "robots/*/x", "--chart-span", "2", "--do",
                         "speed 0", "--do", "run-until 5", "--do", "print chart-samples"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(lines_with(r.out, "chart-samples ").at(0), "2001 3.000000 5.000000");
}

// Reset replays the run exactly, --set inputs included.
TEST_F(Viewer, ResetAfterSetReplaysTheFirstRunsCsvExactly) {
  const fs::path scene = robot_scene();
  const fs::path first = dir_ / "first.csv", second = dir_ / "second.csv";
  const Result r = view(scene.string(), {"--seed",  "3",
                                         "--set",   "robots/nxt/axes/right/ref_voltage=5",
                                         "--set",   "robots/nxt/axes/left/ref_voltage=-3",
                                         "--chart", "robots/nxt/*",
                                         "--do",    "speed 0",
                                         "--do",    "run-until 1",
                                         "--do",    "chart-csv " + first.string(),
                                         "--do",    "show chart",
                                         "--do",    "click Export CSV",
                                         "--do",    "click Reset",
                                         "--do",    "wait 1",
                                         "--do",    "run-until 1",
                                         "--do",    "chart-csv " + second.string(),
                                         "--do",    "click Export CSV",
                                         "--do",    "wait 1"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string a = read_file(first), b = read_file(second);
  EXPECT_GT(std::count(a.begin(), a.end(), '\n'), 1000);
  EXPECT_NE(a.find("ref_voltage"), std::string::npos) << a.substr(0, 300);
  EXPECT_TRUE(a == b) << "the run after Reset differs from the first";
}

// An edit that does not load is refused before anything is written (the file keeps
// its bytes and its time stamp); one that loads is written and the previous version is kept.
TEST_F(Viewer, SceneEditorValidatesAnEditBeforeWritingAndKeepsThePreviousVersion) {
  const fs::path scene = dir_ / "scene";
  fs::copy(kSource / "scenes/default", scene, fs::copy_options::recursive);
  const std::string original = read_file(scene / "scene.xml");
  const auto stamp = fs::last_write_time(scene / "scene.xml");
  std::string deep;  // the nesting that used to overflow the stack after the write
  for (int i = 0; i < 20000; ++i)
    deep += "<a>";
  const Result refused =
      view(scene.string(),
           {"--do", "wait 3", "--do", "editor-open scene.xml", "--do",
            "editor-insert 5 <robot><ID name='bad'/><pos x='zz' y='0' z='0'/></robot>", "--do",
            "click Apply", "--do", "print editor-error", "--do", "editor-insert 5 " + deep, "--do",
            "click Apply", "--do", "print editor-error"});
  ASSERT_EQ(refused.status, 0) << refused.err;
  const auto errors = lines_with(refused.out, "editor-error ");
  ASSERT_EQ(errors.size(), 2u) << refused.out;
  EXPECT_NE(errors[0].find("scene.xml"), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find("zz"), std::string::npos) << errors[0];
  EXPECT_EQ(errors[0].find("s2sim-view-edit"), std::string::npos) << "names the scratch copy";
  EXPECT_EQ(read_file(scene / "scene.xml"), original);
  EXPECT_EQ(fs::last_write_time(scene / "scene.xml"), stamp) << "a refused edit wrote the file";
  EXPECT_FALSE(fs::exists(scene / "scene.xml~"));

  const Result applied =
      view(scene.string(), {"--do", "wait 3", "--do", "editor-open scene.xml", "--do",
                            "editor-insert 5 <!-- an applied edit -->", "--do", "click Apply",
                            "--do", "wait 2", "--do", "print editor-error"});
  ASSERT_EQ(applied.status, 0) << applied.err;
  EXPECT_EQ(lines_with(applied.out, "editor-error ").at(0), "-1 ");
  EXPECT_NE(read_file(scene / "scene.xml").find("an applied edit"), std::string::npos);
  EXPECT_EQ(read_file(scene / "scene.xml~"), original);
}

// SetSolidColor through StepContext::set_body_color: CartPole's reset script paints
// its pole (255, 0, 51) at its 25th call; before, the pole shows its scene colour (200, 60, 60),
// whose shades keep green at 0.3 of red; after, green is gone.
TEST_F(ViewerScript, SetSolidColorPaintsTheSolidInTheWorldView) {
  const std::string script =
      (kSource / "tests/plugins/pascal_script/fixtures/teleport.pas").string();
  auto count = [&](double until_s, const std::string& name) {
    const Image image = cartpole_at(script, until_s, name);
    int painted = 0, scene_colour = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const unsigned char* p = image.at(x, y);
        if (p[0] < 40) continue;
        if (p[1] < 8 && p[0] > 3 * p[1]) ++painted;
        if (std::abs(p[1] - 0.3 * p[0]) < 0.05 * p[0] && std::abs(p[2] - 0.3 * p[0]) < 0.05 * p[0])
          ++scene_colour;
      }
    return std::pair{painted, scene_colour};
  };
  const auto [painted_before, scene_before] = count(0.45, "before");
  const auto [painted_after, scene_after] = count(0.505, "after");
  EXPECT_LT(painted_before, 50);
  EXPECT_GT(scene_before, 1000);
  EXPECT_GT(painted_after, 1000);
  EXPECT_LT(scene_after, 50);
}

// MeshThing: the viewer draws the thing as the mesh file from the call on, in its colour.
TEST_F(ViewerScript, MeshThingDrawsTheThingAsItsMeshFile) {
  const std::string script = (kFixtures / "mesh_thing.pas").string();
  auto green = [&](double until_s, const std::string& name) {
    const Image image = cartpole_at(script, until_s, name);
    int count = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const unsigned char* p = image.at(x, y);
        if (p[1] > 60 && p[1] > 2 * p[0] && p[1] > 2 * p[2]) ++count;
      }
    return count;
  };
  const int box = green(0.3, "box");
  const int mesh = green(0.7, "mesh");
  EXPECT_GT(box, 20) << "the 6 cm box is drawn";
  EXPECT_GT(mesh, 10 * box) << "the 0.4 m cube replaces it";
}

// The new options' bad values are usage errors (exit 4) naming the option.
TEST_F(Viewer, BadScriptAndChartOptionsAreUsageErrorsNamingTheOption) {
  const std::string scene = (kSource / "scenes/default").string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--sheet", "1,x=3"}, "--sheet"},
      {{"--chart-span", "0"}, "--chart-span"},
      {{"--no-script", "--script-file", "a.pas"}, "--script-file and --no-script"},
      {{"--show-window", "scripts"}, "script, log"},
  };
  for (const auto& [args, expected] : cases) {
    const Result r = view(scene, args);
    EXPECT_EQ(r.status, 4) << args[0] << "\n" << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
  }
}

}  // namespace
