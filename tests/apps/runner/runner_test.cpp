// s2sim-run as a user sees it: the real binary runs the shared SimTwo scenes and small broken
// scenes written to a temp folder; the tests check exit codes, messages, the CSV log and the
// JSON summary. Nothing here depends on ground contact (bodies still fall through the floor).

#include "runner_harness.hpp"

#include <recording.hpp>

namespace {

using namespace s2sim::runner_test;

// --- The shared scenes run ---------------------------------------------------------------

struct SharedScene {
  std::string folder;
  std::vector<std::string> robots;
  std::vector<std::pair<std::string, std::string>> axes;  ///< (robot, axis)
};

// Names the case in gtest and ctest output instead of dumping the struct's bytes.
void PrintTo(const SharedScene& s, std::ostream* os) {
  *os << s.folder;
}

class SharedSceneRun : public Runner, public ::testing::WithParamInterface<SharedScene> {};

TEST_P(SharedSceneRun, FiveSecondsGiveTheSummary) {
  SKIP_WITHOUT_SHARED_SCENES();
  const SharedScene& s = GetParam();
  const Result r = run({scene(s.folder), "--duration", "5", "--quiet", "--summary", "f.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "") << "--quiet prints nothing on stdout";

  const pt::ptree j = read_json(dir_ / "f.json");
  EXPECT_DOUBLE_EQ(j.get<double>("sim_time"), 5.0);
  EXPECT_EQ(j.get<long>("steps"), 5000);
  EXPECT_THAT(names(j, "robots"), ElementsAreArray(s.robots));
  std::vector<std::pair<std::string, std::string>> axes;
  for (const auto& [k, ax] : j.get_child("axes")) {
    axes.emplace_back(ax.get<std::string>("robot"), ax.get<std::string>("name"));
    // null (a non-finite value) would not read as a double.
    EXPECT_TRUE(std::isfinite(ax.get<double>("pos")));
    EXPECT_TRUE(std::isfinite(ax.get<double>("vel")));
  }
  EXPECT_THAT(axes, ElementsAreArray(s.axes));
  for (const char* key : {"robots", "things"})
    for (const auto& [k, item] : j.get_child(key))
      for (const char* c : {"x", "y", "z", "yaw"})
        EXPECT_TRUE(std::isfinite(item.get<double>(c))) << key << " " << c;
  // Without --no-timing the summary carries the wall time.
  EXPECT_GT(j.get<double>("wall_time"), 0.0);
  EXPECT_GT(j.get<double>("rtf"), 0.0);
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, SharedSceneRun,
    ::testing::Values(SharedScene{"base",
                                  {"Classic", "Conveyor Belt"},
                                  {{"Classic", "W1"}, {"Classic", "W2"}, {"Classic", "W3"}}},
                      SharedScene{"default", {"belt"}, {}},
                      SharedScene{"MotorModel_V3AGM", {"Motor"}, {{"Motor", "InertialBoard"}}}),
    [](const auto& param_info) { return param_info.param.folder; });

// --- Determinism --------------------------------------------------------------------------

TEST_F(Runner, SameSeedGivesByteIdenticalLogAndSummary) {
  SKIP_WITHOUT_SHARED_SCENES();
  const std::vector<std::string> args = {scene("base"), "--duration",  "2",      "--seed",
                                         "7",           "--no-timing", "--log",  "a.csv",
                                         "--summary",   "a.json",      "--quiet"};
  ASSERT_EQ(run(args).status, 0);
  const std::string csv1 = read_file(dir_ / "a.csv");
  const std::string json1 = read_file(dir_ / "a.json");
  ASSERT_EQ(run(args).status, 0);
  const std::string csv2 = read_file(dir_ / "a.csv");
  const std::string json2 = read_file(dir_ / "a.json");

  ASSERT_GT(csv1.size(), 1000u);
  EXPECT_EQ(csv1.size(), csv2.size());
  // Not EXPECT_EQ: a failure would print megabytes.
  EXPECT_TRUE(csv1 == csv2)
      << "CSV logs differ from byte "
      << std::mismatch(csv1.begin(), csv1.end(), csv2.begin(), csv2.end()).first - csv1.begin();
  EXPECT_EQ(json1, json2);
  EXPECT_THAT(json1, AllOf(Not(HasSubstr("wall_time")), Not(HasSubstr("rtf"))));
}

// --- The CSV log --------------------------------------------------------------------------

TEST_F(Runner, CsvHeaderNamesEverySignalOnceWithItsUnit) {
  SKIP_WITHOUT_SHARED_SCENES();
  const Result r = run({motor(), "--duration", "0.01", "--quiet", "--log", "all.csv"});
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv csv = read_csv(dir_ / "all.csv");
  ASSERT_FALSE(csv.header.empty());
  EXPECT_EQ(csv.header[0], "time [s]");
  EXPECT_THAT(csv.header, Contains("robots/Motor/axes/InertialBoard/pos [rad]"));
  EXPECT_THAT(csv.header, Contains("robots/Motor/axes/InertialBoard/ref_torque [N*m]"));
  for (const auto& c : csv.header)
    EXPECT_THAT(c, ::testing::MatchesRegex("[^ ]+ \\[[^]]*\\]")) << "not 'name [unit]'";
  const std::set<std::string> unique(csv.header.begin(), csv.header.end());
  EXPECT_EQ(unique.size(), csv.header.size()) << "a column appears twice";

  // The columns are exactly what --list-signals names, in the same order.
  const Result list = run({motor(), "--list-signals", "--quiet"});
  ASSERT_EQ(list.status, 0) << list.err;
  EXPECT_THAT(csv.header, ElementsAreArray(split(list.out, '\n')));

  ASSERT_EQ(csv.rows.size(), 11u);  // t = 0 and each of the 10 ticks
  for (const auto& row : csv.rows)
    EXPECT_EQ(row.size(), csv.header.size());
}

TEST_F(Runner, SignalPatternsRestrictTheColumns) {
  SKIP_WITHOUT_SHARED_SCENES();
  const Result r =
      run({motor(), "--duration", "0.01", "--quiet", "--log", "z.csv", "--signals", "robots/*/z"});
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv csv = read_csv(dir_ / "z.csv");
  ASSERT_GE(csv.header.size(), 2u);
  EXPECT_EQ(csv.header[0], "time [s]");
  const std::vector<std::string> rest(csv.header.begin() + 1, csv.header.end());
  EXPECT_THAT(rest, Each(EndsWith("/z [m]")));
  EXPECT_THAT(rest, Contains("robots/Motor/z [m]"));

  // Overlapping patterns, and `time` itself, add no column twice.
  ASSERT_EQ(run({motor(), "--duration", "0.01", "--quiet", "--log", "z2.csv", "--signals", "time",
                 "robots/*/z", "robots/Motor/z"})
                .status,
            0);
  EXPECT_EQ(read_csv(dir_ / "z2.csv").header, csv.header);
}

TEST_F(Runner, LogPeriodGivesOneRowPerPeriodIncludingTimeZero) {
  SKIP_WITHOUT_SHARED_SCENES();
  const Result r = run({motor(), "--duration", "1", "--quiet", "--log", "p.csv", "--log-period",
                        "0.01", "--signals", "robots/Motor/z"});
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv csv = read_csv(dir_ / "p.csv");
  ASSERT_EQ(csv.rows.size(), 101u);
  for (std::size_t i = 0; i < csv.rows.size(); ++i)
    EXPECT_NEAR(std::stod(csv.rows[i][0]), 0.01 * static_cast<double>(i), 1e-9) << "row " << i;
  EXPECT_EQ(csv.rows.back()[0], "1.000000");
}

// --- Inputs -------------------------------------------------------------------------------

TEST_F(Runner, SetTorqueTurnsTheUndrivenAxis) {
  SKIP_WITHOUT_SHARED_SCENES();
  const std::string input = "robots/Motor/axes/InertialBoard/ref_torque";
  const Result r =
      run({motor(), "--duration", "2", "--quiet", "--summary", "on.json", "--set", input + "=0.5",
           "--log", "on.csv", "--log-period", "0.1", "--signals", input});
  ASSERT_EQ(r.status, 0) << r.err;
  const pt::ptree on = read_json(dir_ / "on.json");
  ASSERT_EQ(on.get_child("axes").size(), 1u);
  EXPECT_GT(on.get_child("axes").front().second.get<double>("pos"), 0.1);
  EXPECT_GT(on.get_child("axes").front().second.get<double>("vel"), 0.0);
  // The input holds for the whole run, from the first logged row on.
  const Csv csv = read_csv(dir_ / "on.csv");
  const std::size_t col = column(csv, input + " [N*m]");
  ASSERT_EQ(csv.rows.size(), 21u);
  for (const auto& row : csv.rows)
    EXPECT_EQ(row.at(col), "0.5") << "at t = " << row[0];

  ASSERT_EQ(run({motor(), "--duration", "2", "--quiet", "--summary", "off.json"}).status, 0);
  const pt::ptree off = read_json(dir_ / "off.json");
  EXPECT_NEAR(off.get_child("axes").front().second.get<double>("pos"), 0.0, 1e-6);
  EXPECT_NEAR(off.get_child("axes").front().second.get<double>("vel"), 0.0, 1e-6);
}

// --- Exit codes and messages --------------------------------------------------------------

TEST_F(Runner, MissingSceneFolderIsASceneErrorNamingThePath) {
  const std::string missing = (dir_ / "no_such_scene").string();
  const Result r = run({missing, "--quiet"});
  EXPECT_EQ(r.status, 2);
  EXPECT_THAT(r.err, HasSubstr(missing));
}

TEST_F(Runner, MalformedSceneXmlIsASceneErrorWithFileAndLine) {
  write_file(dir_ / "broken/scene.xml",
             "<?xml version=\"1.0\"?>\n<scene>\n  <robot>\n    <ID name='x' y=/>\n  </robot>\n"
             "</scene>\n");
  const Result r = run({(dir_ / "broken").string(), "--quiet"});
  EXPECT_EQ(r.status, 2);
  EXPECT_THAT(r.err, HasSubstr("scene.xml:4"));
}

TEST_F(Runner, UnknownPluginKindIsAPluginErrorNamingKindAndFolders) {
  write_file(dir_ / "plugged/scene.xml",
             "<?xml version=\"1.0\"?>\n<scene>\n  <plugin kind='no_such_kind'/>\n</scene>\n");
  const Result r = run({(dir_ / "plugged").string(), "--quiet"});
  EXPECT_EQ(r.status, 3);
  EXPECT_THAT(r.err, AllOf(HasSubstr("no_such_kind"), HasSubstr("searched")));

  // With --plugin-path the folder named is the one searched.
  const fs::path empty = dir_ / "empty_plugins";
  fs::create_directories(empty);
  const Result r2 = run({(dir_ / "plugged").string(), "--quiet", "--plugin-path", empty.string()});
  EXPECT_EQ(r2.status, 3);
  EXPECT_THAT(r2.err, AllOf(HasSubstr("no_such_kind"), HasSubstr(empty.string())));
}

TEST_F(Runner, UnknownOptionIsAUsageError) {
  const Result r = run({"some_scene", "--bogus"});
  EXPECT_EQ(r.status, 4);
  EXPECT_THAT(r.err, HasSubstr("--bogus"));
}

TEST_F(Runner, UnknownInputIsAUsageErrorWithASuggestion) {
  SKIP_WITHOUT_SHARED_SCENES();
  const Result r = run({motor(), "--quiet", "--set", "nosuch/input=1"});
  EXPECT_EQ(r.status, 4);
  EXPECT_THAT(r.err, AllOf(HasSubstr("nosuch/input"), HasSubstr("did you mean")));
}

TEST_F(Runner, UnknownSignalIsAUsageError) {
  SKIP_WITHOUT_SHARED_SCENES();
  const Result r = run({motor(), "--quiet", "--log", "x.csv", "--signals", "nosuch"});
  EXPECT_EQ(r.status, 4);
  EXPECT_THAT(r.err, HasSubstr("nosuch"));
  EXPECT_FALSE(fs::exists(dir_ / "x.csv")) << "no log is started for a bad pattern";
  // Without --log, --signals would otherwise be silently ignored.
  EXPECT_EQ(run({motor(), "--quiet", "--signals", "nosuch"}).status, 4);
  EXPECT_EQ(run({motor(), "--quiet", "--log-period", "0.1"}).status, 4);
}

TEST_F(Runner, BadNumbersAreUsageErrors) {
  SKIP_WITHOUT_SHARED_SCENES();
  const Result r = run({motor(), "--duration", "abc"});
  EXPECT_EQ(r.status, 4);
  EXPECT_THAT(r.err, HasSubstr("abc"));
  // More ticks than an int64 holds must not wrap round into "0 steps, exit 0".
  EXPECT_EQ(run({motor(), "--quiet", "--duration", "1e20"}).status, 4);
}

TEST_F(Runner, HelpPrintsUsage) {
  const Result r = run({"--help"});
  EXPECT_EQ(r.status, 0);
  EXPECT_THAT(r.out, HasSubstr("Usage"));
}

TEST_F(Runner, ListSignalsPrintsNamesWithUnits) {
  SKIP_WITHOUT_SHARED_SCENES();
  const Result r = run({motor(), "--list-signals", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto lines = split(r.out, '\n');
  EXPECT_THAT(lines, Contains("time [s]"));
  EXPECT_THAT(lines, Contains("robots/Motor/axes/InertialBoard/pos [rad]"));
}

// ../shared/repro R10: IDs with ',', '"' or a line break corrupted the CSV header.
TEST_F(Runner, CsvHeaderQuotesNamesPerRfc4180) {
  const Result r = run({(kFixtures / "odd_names").string(), "--quiet", "--duration", "0.002",
                        "--log", "a.csv", "--signals", "things/*/x"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string text = read_file(dir_ / "a.csv");
  EXPECT_THAT(text, StartsWith("time [s],\"things/crate,\"\"big\"\"/x [m]\",\"things/two\nlines/x "
                               "[m]\"\n"));
  // Three rows after the header, each with three fields: the quoted line break is not a row.
  std::size_t unquoted_newlines = 0;
  bool quoted = false;
  for (char c : text) {
    if (c == '"') quoted = !quoted;
    if (c == '\n' && !quoted) ++unquoted_newlines;
  }
  EXPECT_EQ(unquoted_newlines, 4u);
}

// ../shared/repro R14: an encoder count overflowing to infinity was written as "inf", exit 0.
TEST_F(Runner, NonFiniteSignalStopsTheRunWithExit5NamingItAndKeepsTheFiniteRows) {
  const Result r = run(
      {(kFixtures / "nonfinite_encoder").string(), "--quiet", "--duration", "1", "--log", "a.csv"});
  EXPECT_EQ(r.status, 5);
  EXPECT_THAT(r.err, HasSubstr("signal 'robots/r/axes/swing/encoder' is inf at t = "));
  const std::string text = read_file(dir_ / "a.csv");
  EXPECT_EQ(text.find("inf"), std::string::npos);
  EXPECT_EQ(text.find("nan"), std::string::npos);
  EXPECT_EQ(text.back(), '\n') << "the last row is complete";
}

// A physics step below the documented limit blamed the encoder (exit 3); it is a usage error.
TEST_F(Runner, PhysicsStepOutsideItsLimitsIsAUsageError) {
  for (const char* step : {"1e-300", "2"}) {
    const Result r = run({(fs::path(S2SIM_SOURCE_DIR) / "scenes/nxt").string(), "--quiet",
                          "--duration", "0.01", "--physics-step", step});
    EXPECT_EQ(r.status, 4) << step;
    EXPECT_THAT(r.err, HasSubstr("the physics step must be from 1e-06 to 1 s")) << step;
  }
}

TEST_F(Runner, WriteFailuresAreNotReportedAsSuccess) {
  SKIP_WITHOUT_SHARED_SCENES();
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full to simulate a full disk";
  // A short log fits in the stdio buffer: only the final flush fails.
  // Exit 6 for both: neither is a failed simulation (5) nor bad usage (4).
  const Result log = run({motor(), "--quiet", "--duration", "0.001", "--log", "/dev/full"});
  EXPECT_EQ(log.status, 6);
  EXPECT_THAT(log.err, HasSubstr("/dev/full"));
  const Result summary = run({motor(), "--quiet", "--duration", "0.001", "--summary", "/dev/full"});
  EXPECT_EQ(summary.status, 6);
  EXPECT_THAT(summary.err, HasSubstr("/dev/full"));
}

// A crash inside a plugin's code is named (component, kind, plugin), exits 7, and the
// log keeps every complete row. The hostile controller raises SIGSEGV in its update at 40 ms
// (controllers run every 40 ms, from tick 0; it acts from tick 3), after the row of t = 40 ms.
TEST_F(Runner, AComponentThatCrashesIsNamedExits7AndTheLogKeepsItsCompleteRows) {
  const fs::path scene =
      s2sim::test::edited_copy(fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/hostile",
                               "scene.xml", "MODE", "update_segv");
  const Result r = run({scene.string(), "--quiet", "--duration", "1", "--log", "crash.csv",
                        "--plugin-path", std::string(S2SIM_TEST_PLUGIN_DIR) + "/hostile"});
  EXPECT_EQ(r.status, 7) << r.err;
  EXPECT_THAT(r.err, HasSubstr("fatal signal SIGSEGV"));
  EXPECT_THAT(r.err, HasSubstr("in component 'controllers/villain' (kind 'test_hostile') from "));
  EXPECT_THAT(r.err, HasSubstr("libs2sim_test_hostile_plugin.so"));
  const Csv csv = read_csv(dir_ / "crash.csv");
  ASSERT_EQ(csv.rows.size(), 41u);  // t = 0, 1, ..., 40 ms
  for (const auto& row : csv.rows)
    EXPECT_EQ(row.size(), csv.header.size());
  EXPECT_EQ(csv.rows.back().front(), "0.040000");
}

// An endless recursion in a component's update exhausts its thread's stack: the handler runs
// on its alternate stack, names the component and says it was a stack overflow (it died with
// SIGSEGV, exit 139 and no word before).
TEST_F(Runner, AComponentsStackOverflowIsNamedAsOne) {
  const fs::path scene =
      s2sim::test::edited_copy(fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/hostile",
                               "scene.xml", "MODE", "update_recurse");
  for (const char* threads : {"1", "2"}) {
    const Result r = run({scene.string(), "--quiet", "--duration", "1", "--threads", threads,
                          "--plugin-path", std::string(S2SIM_TEST_PLUGIN_DIR) + "/hostile"});
    EXPECT_EQ(r.status, 7) << r.err;
    EXPECT_THAT(r.err, HasSubstr("fatal signal SIGSEGV (invalid memory access), a stack overflow"));
    EXPECT_THAT(r.err, HasSubstr("in component 'controllers/villain' (kind 'test_hostile')"));
  }
}

// A component whose update never returns (a `while true do;`) hung the runner with no word
// until killed: the watchdog stops the run, names it and exits 8; the log keeps its rows.
TEST_F(Runner, AComponentThatNeverReturnsIsStoppedByTheWatchdogNamingIt) {
  const fs::path scene =
      s2sim::test::edited_copy(fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/hostile",
                               "scene.xml", "MODE", "update_hang");
  const Result r =
      run({scene.string(), "--quiet", "--duration", "1", "--watchdog", "0.5", "--log", "hang.csv",
           "--plugin-path", std::string(S2SIM_TEST_PLUGIN_DIR) + "/hostile"});
  EXPECT_EQ(r.status, 8) << r.err;
  EXPECT_THAT(r.err, HasSubstr("watchdog: component 'controllers/villain' (kind 'test_hostile')"));
  EXPECT_THAT(r.err, HasSubstr("has not returned from one call for"));
  EXPECT_EQ(read_csv(dir_ / "hang.csv").rows.size(), 41u);  // t = 0 … 40 ms, as for a crash
  const Result bad = run({scene.string(), "--watchdog", "-1"});
  EXPECT_EQ(bad.status, 4);
  EXPECT_THAT(bad.err, HasSubstr("--watchdog must be"));
}

// Memory the system refused (a process limit, a full machine) was "internal error:
// std::bad_alloc", exit 1 as for a bug, and a thread it refused "internal error: Resource
// temporarily unavailable"; out of memory inside the step was reported as a diverged state. Each
// limit below what the run needs now ends it saying what was refused (exit 1, as documented),
// or, when a plugin's library could not be mapped, as a plugin that cannot be loaded (exit 3).
TEST_F(Runner, MemoryOrAThreadTheSystemRefusesIsSaidSo) {
  const std::string scene = (fs::path(S2SIM_SOURCE_DIR) / "bench/peers/scenes/robots_64").string();
  auto limited = [&](int kB) {
    return run({scene, "--duration", "0.05", "--quiet"},
               "ulimit -v " + std::to_string(kB) + "; exec");
  };
  // The least address space the run needs, to 1 MB (the libraries' share differs by machine).
  int enough = 4 << 20, too_little = 8 << 10;
  ASSERT_EQ(limited(enough).status, 0) << limited(enough).err;
  while (enough - too_little > 1024) {
    const int middle = (enough + too_little) / 2;
    (limited(middle).status == 0 ? enough : too_little) = middle;
  }
  int said_out_of_memory = 0;
  for (int kB = enough - 1024; kB > enough - 16 * 1024; kB -= 1024) {
    const Result r = limited(kB);
    if (r.status == 127) break;   // the loader could not map the runner: before S2Sim runs
    if (r.status == 0) continue;  // the need varies by a little from run to run
    EXPECT_THAT(r.err, Not(HasSubstr("internal error"))) << kB << " kB";
    EXPECT_THAT(r.err, Not(HasSubstr("diverged"))) << kB << " kB";
    if (r.status == 1) {
      EXPECT_THAT(r.err, AnyOf(HasSubstr("out of memory: the system refused"),
                               HasSubstr("the system refused a resource")))
          << kB << " kB";
      said_out_of_memory += r.err.find("out of memory") != std::string::npos;
    } else {
      EXPECT_EQ(r.status, 3) << kB << " kB: " << r.err;
    }
  }
  EXPECT_GT(said_out_of_memory, 0) << "no limit ran out of memory in S2Sim's own code";
}

// A plugin's exit(0) ended the run with exit 0, no word and the CSV cut short; exit(3) passed
// for a plugin error. Both are named now, with their own code.
// _exit(0) and _Exit(3), which run no atexit handler, ended the run with their codes unnamed.
TEST_F(Runner, AComponentThatCallsExitIsNamedWithItsOwnCode) {
  for (const char* mode : {"update_exit0", "update_exit3", "update__exit0", "update__Exit3"}) {
    const fs::path scene =
        s2sim::test::edited_copy(fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/hostile",
                                 "scene.xml", "MODE", mode);
    const Result r = run({scene.string(), "--quiet", "--duration", "1", "--log", "exit.csv",
                          "--plugin-path", std::string(S2SIM_TEST_PLUGIN_DIR) + "/hostile"});
    EXPECT_EQ(r.status, 9) << mode << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr("component 'controllers/villain' (kind 'test_hostile')"));
    EXPECT_THAT(r.err, AnyOf(HasSubstr("called exit() during its call"),
                             HasSubstr("called _exit() during its call")));
    EXPECT_EQ(read_csv(dir_ / "exit.csv").rows.size(), 41u) << mode;
  }
}

// A component that holds the run back (a script taking 0.1 s per call) is named once.
TEST_F(Runner, AComponentThatHoldsTheRunBackGetsOneWarning) {
  const fs::path scene =
      s2sim::test::edited_copy(fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/hostile",
                               "scene.xml", "MODE", "update_slow");
  const Result r = run({scene.string(), "--quiet", "--duration", "1", "--plugin-path",
                        std::string(S2SIM_TEST_PLUGIN_DIR) + "/hostile"});
  EXPECT_EQ(r.status, 0) << r.err;
  const std::string warning = "warning: component 'controllers/villain' (kind 'test_hostile')";
  EXPECT_THAT(r.err, HasSubstr(warning));
  EXPECT_THAT(r.err, HasSubstr("of the wall time"));
  EXPECT_EQ(r.err.find(warning), r.err.rfind(warning)) << "warned more than once";
}

// A crash on a thread the plugin started itself, outside any call of the kernel into it, is
// found by the faulting code's library (it was reported as S2Sim's own).
TEST_F(Runner, ACrashOnAPluginsOwnThreadNamesItsLibrary) {
  const fs::path scene =
      s2sim::test::edited_copy(fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/hostile",
                               "scene.xml", "MODE", "thread_trap");
  const Result r = run({scene.string(), "--quiet", "--duration", "5", "--plugin-path",
                        std::string(S2SIM_TEST_PLUGIN_DIR) + "/hostile"});
  EXPECT_EQ(r.status, 7) << r.err;
  EXPECT_THAT(r.err, HasSubstr("fatal signal SIGILL"));
  EXPECT_THAT(r.err, HasSubstr("libs2sim_test_hostile_plugin.so, outside any call of the kernel"));
  EXPECT_THAT(r.err, Not(HasSubstr("in S2Sim itself")));
}

// A crash in a component's constructor (the plugin's factory) or its destructor is
// named like one in its update: the kernel marks those calls too.
TEST_F(Runner, ACrashInAComponentsConstructorOrDestructorIsNamed) {
  const std::string plugins = std::string(S2SIM_TEST_PLUGIN_DIR) + "/hostile";
  const fs::path destroy =
      s2sim::test::edited_copy(fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/hostile",
                               "scene.xml", "MODE", "destroy_segv");
  const Result at_end = run({destroy.string(), "--quiet", "--duration", "0.1", "--log",
                             "destroy.csv", "--plugin-path", plugins});
  EXPECT_EQ(at_end.status, 7) << at_end.err;
  EXPECT_THAT(at_end.err,
              HasSubstr("in component 'controllers/villain' (kind 'test_hostile') from "));
  // Every row was written before the components were destroyed.
  EXPECT_EQ(read_csv(dir_ / "destroy.csv").rows.size(), 101u);

  const fs::path quiet =
      s2sim::test::edited_copy(fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/hostile",
                               "scene.xml", "MODE", "none");
  ASSERT_EQ(setenv("S2SIM_TEST_HOSTILE_CRASH_IN_CONSTRUCTOR", "1", 1), 0);
  const Result at_start =
      run({quiet.string(), "--quiet", "--duration", "0.1", "--plugin-path", plugins});
  unsetenv("S2SIM_TEST_HOSTILE_CRASH_IN_CONSTRUCTOR");
  EXPECT_EQ(at_start.status, 7) << at_start.err;
  EXPECT_THAT(at_start.err,
              HasSubstr("in component 'controllers/villain' (kind 'test_hostile') from "));
}

// ../shared/repro R03 (eacces/): a scene naming a file in a folder its user may not read
// ended as an internal error (exit 1). Run as an unprivileged user where the test is root (root
// reads everything).
TEST_F(Runner, AFileInAnUnreadableFolderIsALocatedSceneError) {
  const fs::path scene = dir_ / "sc";
  fs::create_directories(scene / "locked");
  std::ofstream(scene / "scene.xml") << "<scene><things file='locked/t.xml'/></scene>\n";
  std::ofstream(scene / "locked" / "t.xml") << "<things/>\n";
  fs::permissions(scene / "locked", fs::perms::none);
  std::string cmd;
  if (::geteuid() == 0) {
    if (std::system("command -v setpriv >/dev/null 2>&1") != 0) {
      fs::permissions(scene / "locked", fs::perms::owner_all);
      GTEST_SKIP() << "running as root without setpriv: no unprivileged user to read as";
    }
    cmd = "setpriv --reuid=65534 --regid=65534 --clear-groups ";
  }
  cmd += quote(kRunner.string());
  cmd += ' ';
  cmd += quote(scene.string());
  cmd += " --quiet --duration 0.01 >";
  cmd += quote((dir_ / "out.txt").string());
  cmd += " 2>&1 </dev/null";
  const int status = std::system(cmd.c_str());
  fs::permissions(scene / "locked", fs::perms::owner_all);  // for the clean-up
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_THAT(read_file(dir_ / "out.txt"),
              HasSubstr("scene.xml: scene/things@file: cannot read 'locked/t.xml': "));
}

// A run stopped by an error still closes its recording: the frames before the error, readable.
TEST_F(Runner, ARunStoppedByAnErrorLeavesAReadableRecording) {
  const Result r = run({(kFixtures / "nonfinite_encoder").string(), "--quiet", "--duration", "1",
                        "--log", "a.csv", "--record", "a.s2rec"});
  EXPECT_EQ(r.status, 5) << r.err;
  const s2sim::apps::Recording rec = s2sim::apps::read_recording((dir_ / "a.s2rec").string());
  EXPECT_GT(rec.frame_count(), 1u);
  EXPECT_LT(rec.times_s.back(), 1.0);
  // One frame per CSV row: the same ticks.
  const std::string text = read_file(dir_ / "a.csv");
  EXPECT_EQ(static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) - 1,
            rec.frame_count());
  // And a file that cannot be written is exit 4, naming it.
  const Result bad = run({(kFixtures / "nonfinite_encoder").string(), "--quiet", "--duration",
                          "0.1", "--record", (dir_ / "no" / "such" / "a.s2rec").string()});
  EXPECT_EQ(bad.status, 4);
  EXPECT_THAT(bad.err, HasSubstr("--record: cannot write '"));
}

// Bodies placed into one another stop the run at the first tick with a runtime error naming
// two of them, in bounded memory (3 000 coincident cuboids once took 3.1 GB). 200
// coincident boxes overlap in 19 900 pairs, above the limit of 1024 + 64 × 200.
TEST_F(Runner, BodiesPlacedIntoOneAnotherStopTheRunNamingTwoOfThem) {
  {
    std::ofstream things(dir_ / "things.xml");
    things << "<things>\n";
    for (int i = 0; i < 200; ++i)
      things << "<cuboid><ID value='box" << i
             << "'/><mass value='0.5'/><size x='0.1' y='0.1' z='0.1'/>"
                "<pos x='0' y='0' z='0.5'/></cuboid>\n";
    things << "</things>\n";
    std::ofstream(dir_ / "scene.xml") << "<scene><things file='things.xml'/></scene>\n";
  }
  const Result r = run({(dir_ / "scene.xml").string(), "--quiet", "--duration", "0.01"});
  EXPECT_EQ(r.status, 5) << r.err;
  EXPECT_THAT(r.err, HasSubstr("at t = 0.000000 s more than 13824 pairs of collision shapes "
                               "overlap (the limit: 1024 + 64 per shape), among them bodies 'box"));
  EXPECT_THAT(r.err, HasSubstr("bodies are placed into one another"));
}

// --- Plugin search ---------------------------------------------------------------------------

const fs::path kDefaultScene = fs::path(S2SIM_SOURCE_DIR) / "scenes/default";
const fs::path kScenePlugins = fs::path(S2SIM_TEST_PLUGIN_DIR) / "scene";

TEST_F(Runner, VersionIsTheProjectVersion) {
  const Result r = run({"--version"});
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind("s2sim-run " S2SIM_PROJECT_VERSION " (SDK " S2SIM_PROJECT_VERSION ",", 0),
            0u)
      << r.out;
}

TEST_F(Runner, PluginPathAddsToTheDefaultFolders) {
  // A scene with joints needs the drive train from the default folder, found although
  // --plugin-path names another folder.
  const fs::path empty = dir_ / "empty_plugins";
  fs::create_directories(empty);
  const Result r =
      run({kDefaultScene.string(), "--duration", "0.01", "--plugin-path", empty.string()});
  EXPECT_EQ(r.status, 0) << r.err;
  // Only the folders named: the drive train is missing.
  const Result only = run({kDefaultScene.string(), "--duration", "0.01", "--plugin-path",
                           empty.string(), "--no-default-plugin-path"});
  EXPECT_EQ(only.status, 3);
  EXPECT_THAT(only.err, AllOf(HasSubstr("drive-train kind"), HasSubstr(empty.string())));
}

TEST_F(Runner, DuplicateKindFirstOnThePathWinsWithAWarningNamingBoth) {
  // A stale copy of the drive train (a real copy, not a link to the same file) first on the
  // path: it wins, the build's is skipped, the run goes on (it used to refuse every scene).
  const fs::path stale = dir_ / "stale";
  fs::create_directories(stale);
  const fs::path build_copy = fs::path(S2SIM_PLUGIN_DIR) / "libdrive_train.so";
  fs::copy_file(build_copy, stale / "libdrive_train.so");
  const Result r =
      run({kDefaultScene.string(), "--duration", "0.01", "--plugin-path", stale.string()});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.err, AllOf(HasSubstr("warning: plugin search: " + build_copy.string() +
                                     ": kind 'dc_motor' of plugin 'drive_train' ignored"),
                           HasSubstr((stale / "libdrive_train.so").string()),
                           HasSubstr("comes first on the search path")));
}

TEST_F(Runner, LibraryNotNamedLibSoIsNamedInAWarning) {
  const fs::path odd = dir_ / "odd";
  fs::create_directories(odd);
  fs::copy_file(fs::path(S2SIM_PLUGIN_DIR) / "libservo.so", odd / "servo.so");
  const Result r =
      run({kDefaultScene.string(), "--duration", "0.01", "--plugin-path", odd.string()});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("warning: plugin search: " + (odd / "servo.so").string() +
                               ": ignored: a plugin library's file name must be lib<name>.so"));
}

TEST_F(Runner, UnknownPluginAttributeWarnsWithDidYouMean) {
  // `valeu` has a default (`value`, 1): without the warning the misspelling goes unseen.
  write_file(dir_ / "plugged/scene.xml",
             "<?xml version=\"1.0\"?>\n<scene>\n"
             "  <plugin kind='test_reference_controller' id='w' input='sheet/A1' valeu='2'>\n"
             "    <extra flag='1'/>\n"
             "  </plugin>\n</scene>\n");
  const Result r = run(
      {(dir_ / "plugged").string(), "--duration", "0.1", "--plugin-path", kScenePlugins.string()});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("warning: scene.xml: scene/plugin@valeu: attribute ignored: kind "
                               "'test_reference_controller' does not read it; did you mean "
                               "'value'?"));
  // A child's attribute nobody reads is named too; read attributes are not.
  EXPECT_THAT(r.err, HasSubstr("scene/plugin/extra@flag: attribute ignored"));
  EXPECT_THAT(r.err, Not(HasSubstr("@input")));
}

TEST_F(Runner, MisspeltKindGetsADidYouMean) {
  write_file(dir_ / "plugged/scene.xml",
             "<?xml version=\"1.0\"?>\n<scene>\n"
             "  <plugin kind='test_reference_controler' input='sheet/A1'/>\n</scene>\n");
  const Result r =
      run({(dir_ / "plugged").string(), "--quiet", "--plugin-path", kScenePlugins.string()});
  EXPECT_EQ(r.status, 3);
  EXPECT_THAT(r.err, HasSubstr("no plugin provides kind 'test_reference_controler' (did you "
                               "mean 'test_reference_controller'?)"));
}

}  // namespace
