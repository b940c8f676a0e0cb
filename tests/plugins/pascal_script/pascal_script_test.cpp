// The SimTwo script controller: SimTwo's shared projects run under their own control.pas,
// compile errors are located, the cache is used, run-time errors stop the script and not the
// simulation, UDP and serial talk to test peers, runs repeat exactly (docs/scripting.md).
#include <s2sim/kernel/annotations.hpp>
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include "loopback.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using s2sim::ScriptMode;
using s2sim::Simulation;
using s2sim::SimulationOptions;

namespace {

fs::path shared(const std::string& project) {
  return fs::path(S2SIM_SHARED_SCENES) / project;
}

#define SKIP_WITHOUT_SHARED(project)                                          \
  if (!fs::exists(shared(project))) GTEST_SKIP() << "no " << shared(project); \
  if (std::system("fpc -iV > /dev/null 2>&1") != 0) GTEST_SKIP() << "no fpc"

/// Every test compiles into the build tree's cache (concurrent processes share it safely).
class PascalScript : public ::testing::Test {
 protected:
  void SetUp() override {
    ::setenv("S2SIM_PASCAL_CACHE", S2SIM_PASCAL_TEST_CACHE, 1);
    ::unsetenv("S2SIM_FPC");
    ::unsetenv("S2SIM_COM_PORT");
    // A free UDP port for the script's socket, so parallel tests do not collide on 9808.
    const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
    socklen_t len = sizeof a;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
    udp_port_ = ntohs(a.sin_port);
    ::close(fd);
    ::setenv("S2SIM_UDP_PORT", std::to_string(udp_port_).c_str(), 1);
  }

  static SimulationOptions with_script(std::optional<fs::path> file = std::nullopt) {
    SimulationOptions o;
    o.script_mode = ScriptMode::always;
    o.script_file = std::move(file);
    return o;
  }

  int udp_port_ = 0;
};

double sig(const Simulation& sim, const char* name) {
  return sim.signal(name);
}

/// MotorModel_V3AGM's control.pas reads its cascade gains and its reference from sheet cells
/// the shipped Global.S2Sheet lacks (SimTwo would divide by an empty Ti): these values make it
/// a position loop to 1000 encoder pulses.
void motor_model_sheet(SimulationOptions& o) {
  o.sheet_cells = {{1, 4, "1000"}, {2, 10, "0.1"}, {3, 10, "0"}, {2, 7, "0.05"}, {3, 7, "1"}};
}

struct Project {
  const char* name;
  const char* script;  // nullptr: the one the project names
  double script_period_s;
};
void PrintTo(const Project& p, std::ostream* os) {
  *os << p.name;
}

class SharedProjects : public PascalScript, public ::testing::WithParamInterface<Project> {};

TEST_P(SharedProjects, RunTenSecondsUnderTheirScriptWithoutAScriptError) {
  const Project p = GetParam();
  SKIP_WITHOUT_SHARED(p.name);
  SimulationOptions o = with_script(p.script ? std::optional<fs::path>(p.script) : std::nullopt);
  if (std::string(p.name) == "MotorModel_V3AGM") motor_model_sheet(o);
  auto sim = Simulation::load(shared(p.name), o);
  sim->run_until(10.0);
  EXPECT_EQ(sig(*sim, "controllers/script/error"), 0);
  // One call per script period, the first at T - dt (SimTwo's phase): 10 s / T calls.
  EXPECT_EQ(sig(*sim, "controllers/script/calls"), std::round(10.0 / p.script_period_s));
}

INSTANTIATE_TEST_SUITE_P(Five, SharedProjects,
                         ::testing::Values(Project{"base", nullptr, 0.04},
                                           Project{"default", nullptr, 0.04},
                                           Project{"Manipulator6DoF", nullptr, 0.02},
                                           Project{"RobotFactoryLite", nullptr, 0.04},
                                           Project{"MotorModel_V3AGM", "control.pas", 0.04}),
                         [](const auto& p) { return std::string(p.param.name); });

TEST_F(PascalScript, FirstCallComesAtOnePeriodLessOneStep) {
  SKIP_WITHOUT_SHARED("base");
  auto sim = Simulation::load(shared("base"), with_script());  // dt 1 ms, T 40 ms
  sim->run_until(0.038);
  EXPECT_EQ(sig(*sim, "controllers/script/calls"), 0);
  sim->step(2);  // the tick at 39 ms runs the script
  EXPECT_EQ(sig(*sim, "controllers/script/calls"), 1);
}

TEST_F(PascalScript, MotorModelPositionScriptMovesTheMotorToItsSheetReference) {
  SKIP_WITHOUT_SHARED("MotorModel_V3AGM");
  SimulationOptions o = with_script("control.pas");
  motor_model_sheet(o);
  auto sim = Simulation::load(shared("MotorModel_V3AGM"), o);
  sim->run_until(10.0);
  const double pulses = sig(*sim, "robots/Motor/axes/InertialBoard/encoder");
  // The cascade ends on the reference: its integral removes the offset; +-5 pulses of 1000 is
  // half a degree of the board.
  EXPECT_NEAR(pulses, 1000, 5);
  EXPECT_NEAR(sig(*sim, "robots/Motor/axes/InertialBoard/speed"), 0, 0.05);
}

TEST_F(PascalScript, RobotFactoryAgvIsPlacedByItsSetButton) {
  SKIP_WITHOUT_SHARED("RobotFactoryLite");
  SimulationOptions o = with_script();
  o.sheet_cells = {{12, 3, "-0.525"}};  // the X the [Set] button (row 11, column 3) places at
  auto sim = Simulation::load(shared("RobotFactoryLite"), o);
  sim->run_until(0.5);
  EXPECT_NEAR(sig(*sim, "robots/AGV/x"), -0.725, 1e-3);
  sim->set_input("sheet/C11", 1);  // a click, as --press 11,3 gives
  sim->run_until(1.0);
  EXPECT_NEAR(sig(*sim, "robots/AGV/x"), -0.525, 1e-3);  // SetRobotPos: file X + sheet X
  EXPECT_NEAR(sig(*sim, "robots/AGV/y"), -0.4, 1e-3);
  EXPECT_NEAR(sig(*sim, "robots/AGV/yaw"), M_PI / 2, 1e-3);
  EXPECT_EQ(sig(*sim, "sheet/C11"), 0);  // the script consumed the click (the latch)
}

TEST_F(PascalScript, RobotFactoryAgvDrivesInManualModeWithTheUpKey) {
  SKIP_WITHOUT_SHARED("RobotFactoryLite");
  auto sim = Simulation::load(shared("RobotFactoryLite"), with_script());
  sim->set_input("keyboard/38", 1);  // VK_UP held
  sim->run_until(1.0);
  EXPECT_NEAR(sig(*sim, "robots/AGV/y"), -0.4, 2e-3);  // Serial mode: no port, no motion
  sim->set_input("sheet/C2", 1);                       // [Manual]
  sim->run_until(3.0);
  EXPECT_GT(sig(*sim, "robots/AGV/y"), -0.4 + 0.3);  // forward along +Y (yaw 90 deg)
  EXPECT_NEAR(sig(*sim, "robots/AGV/x"), -0.725, 0.02);
}

TEST_F(PascalScript, ManipulatorArmHoldsThePoseItsScriptSets) {
  SKIP_WITHOUT_SHARED("Manipulator6DoF");
  auto sim = Simulation::load(shared("Manipulator6DoF"), with_script());
  sim->run_until(10.0);
  // In its 'idle' state the script sets every joint reference to 0 (the arm upright). The
  // script's own tolerance for "reached" is a summed joint error of Tol = 0.2 rad; each of the
  // six joints within 0.2/6 rad keeps that sum below it.
  const char* joints[] = {"J1", "J2", "J3", "J4", "J5", "J6"};
  double sum = 0;
  for (const char* j : joints) {
    const double q = sig(*sim, ("robots/Arm6D/axes/" + std::string(j) + "/pos").c_str());
    EXPECT_NEAR(q, 0, 0.2 / 6) << j;
    sum += std::abs(q);
  }
  EXPECT_LT(sum, 0.2);
}

TEST_F(PascalScript, SyntaxErrorsAreLocatedCompileErrors) {
  SKIP_WITHOUT_SHARED("MotorModel_V3AGM");
  struct Case {
    const char* file;
    const char* where;
  };
  for (const Case& c : {Case{"control_PosCascata.pas",
                             "control_PosCascata.pas:38:3: Fatal: "
                             "Syntax error, \";\" expected"},
                        Case{"control_Vel.pas", "control_Vel.pas:88:3: Fatal: Syntax error"}}) {
    try {
      (void)Simulation::load(shared("MotorModel_V3AGM"), with_script(c.file));
      ADD_FAILURE() << c.file << " compiled";
    } catch (const s2sim::Error& e) {
      EXPECT_EQ(e.kind(), s2sim::ErrorKind::scene);  // the runner's exit 2
      EXPECT_NE(e.message().find(c.where), std::string::npos) << e.message();
    }
  }
  // The project's own choice (SimTwo.ini names control_PosCascata.pas) fails the same way.
  EXPECT_THROW((void)Simulation::load(shared("MotorModel_V3AGM"), with_script()), s2sim::Error);
}

// Seen from outside: the compiler is a wrapper that logs every invocation but the version
// query (`-iV`, part of the cache key) before it runs the real fpc.
TEST_F(PascalScript, SecondLoadOfAnUnchangedScriptDoesNotRunTheCompiler) {
  SKIP_WITHOUT_SHARED("base");
  const fs::path dir =
      fs::temp_directory_path() / ("s2sim-pascal-cache-test-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "cache");
  const fs::path wrapper = dir / "fpc", calls = dir / "calls.txt";
  std::ofstream(wrapper) << "#!/bin/sh\n"
                         << "[ \"$1\" = -iV ] || echo \"$@\" >> '" << calls.string() << "'\n"
                         << "exec fpc \"$@\"\n";
  fs::permissions(wrapper, fs::perms::owner_all);
  const char* previous = std::getenv("S2SIM_FPC");
  const std::string saved = previous ? previous : "";
  ::setenv("S2SIM_PASCAL_CACHE", (dir / "cache").c_str(), 1);
  ::setenv("S2SIM_FPC", wrapper.c_str(), 1);
  const auto compiles = [&] {
    std::ifstream in(calls);
    std::size_t n = 0;
    for (std::string line; std::getline(in, line);)
      ++n;
    return n;
  };
  auto first = Simulation::load(shared("base"), with_script());
  EXPECT_EQ(compiles(), 1u) << "the first load compiles";
  auto second = Simulation::load(shared("base"), with_script());
  EXPECT_EQ(compiles(), 1u) << "the second load ran the compiler again";
  if (previous) {
    ::setenv("S2SIM_FPC", saved.c_str(), 1);
  } else {
    ::unsetenv("S2SIM_FPC");
  }
  // Two simulations of one script: each has its own copy of the library (its own globals).
  first->run_until(0.1);
  second->run_until(0.1);
  EXPECT_EQ(sig(*first, "controllers/script/calls"), sig(*second, "controllers/script/calls"));
  fs::remove_all(dir);
}

TEST_F(PascalScript, WithoutTheCompilerTheSceneLoadsWarnsOnceAndRunsWithoutItsScript) {
  SKIP_WITHOUT_SHARED("RobotFactoryLite");
  ::setenv("S2SIM_FPC", "/nonexistent/fpc", 1);
  auto sim = Simulation::load(shared("RobotFactoryLite"), with_script());
  int warnings = 0;
  for (const auto& w : sim->warnings())
    if (w.find("fpc") != std::string::npos) ++warnings;
  EXPECT_EQ(warnings, 1);
  sim->run_until(1.0);
  EXPECT_EQ(sig(*sim, "controllers/script/calls"), 0);
}

TEST_F(PascalScript, RunTimeErrorStopsTheScriptNotTheSimulation) {
  SKIP_WITHOUT_SHARED("MotorModel_V3AGM");
  for (const char* mode : {"0", "1"}) {
    SimulationOptions o = with_script(fs::path(S2SIM_PASCAL_FIXTURES) / "runtime_error.pas");
    o.sheet_cells = {{1, 1, "0"}, {2, 1, mode}};
    auto sim = Simulation::load(shared("MotorModel_V3AGM"), o);
    ::testing::internal::CaptureStderr();
    sim->run_until(1.0);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(sig(*sim, "controllers/script/error"), 1);
    EXPECT_EQ(sig(*sim, "controllers/script/calls"), 3);  // no call after the error
    EXPECT_EQ(sig(*sim, "sheet/A1"), 3);
    EXPECT_NEAR(sim->time_s(), 1.0, 1e-9);
    EXPECT_NE(err.find("run-time error in Control"), std::string::npos) << err;
    if (std::string(mode) == "0") {
      EXPECT_NE(err.find("Invalid (row,col) value"), std::string::npos) << err;
      EXPECT_NE(err.find("(CONTROL at "), std::string::npos) << err;
      EXPECT_NE(err.find("runtime_error.pas:15"), std::string::npos) << err;  // Mgetv's line
    } else {
      EXPECT_NE(err.find("the camera's TCanvas belongs to SimTwo's own rendering"),
                std::string::npos)
          << err;
    }
  }
}

/// Free Pascal's line-info unit finds the executable by walking past the NULL that ends the
/// library's envp into what it takes for the auxiliary vector. After a setenv, envp is a heap
/// array and that walk read garbage (a segfault in CI). Here the entries after the NULL say
/// "4 program headers at address 8": a script library that still walks there crashes.
TEST_F(PascalScript, RunTimeErrorIsReportedWhateverFollowsTheEnvironment) {
  SKIP_WITHOUT_SHARED("MotorModel_V3AGM");
  std::vector<char*> env;
  for (char** e = environ; *e; ++e)
    env.push_back(*e);
  env.push_back(nullptr);
  for (std::uintptr_t word : {5u, 4u, 4u, 56u, 3u, 8u, 0u, 0u})  // AT_PHNUM, AT_PHENT, AT_PHDR
    env.push_back(reinterpret_cast<char*>(word));
  char** const saved = environ;
  environ = env.data();
  SimulationOptions o = with_script(fs::path(S2SIM_PASCAL_FIXTURES) / "runtime_error.pas");
  o.sheet_cells = {{1, 1, "0"}, {2, 1, "0"}};
  auto sim = Simulation::load(shared("MotorModel_V3AGM"), o);
  ::testing::internal::CaptureStderr();
  sim->run_until(0.5);
  const std::string err = ::testing::internal::GetCapturedStderr();
  sim.reset();
  environ = saved;
  EXPECT_NE(err.find("runtime_error.pas:15"), std::string::npos) << err;
}

/// SetMotorActive, GetMotorPars/SetMotorPars, IsMotorActive, GetAxisTorque and GetAxisIndex
/// (MotorModel_V3AGM's control.pas, simtwo-script-api.md §3.1): the motor's inputs change, the
/// current follows, and a bad record stops the script, not the simulation.
TEST_F(PascalScript, MotorCallsSwitchTheMotorAndChangeItsParameters) {
  SKIP_WITHOUT_SHARED("MotorModel_V3AGM");
  SimulationOptions o = with_script(fs::path(S2SIM_PASCAL_FIXTURES) / "motor_pars.pas");
  for (auto [r, c] : {std::pair{1, 1}, {1, 2}, {1, 3}, {2, 1}, {3, 1}, {4, 1}, {4, 2}, {4, 3}})
    o.sheet_cells.push_back({r, c, "9"});
  auto sim = Simulation::load(shared("MotorModel_V3AGM"), o);
  const std::string axis = "robots/Motor/axes/InertialBoard/";
  const double ri = sim->signal(axis + "motor_ri");
  EXPECT_EQ(ri, 7.1);     // Motor.xml's <motor ri>
  sim->run_until(0.035);  // 1st Control (at T - dt = 0.039 s) not yet
  sim->run_until(0.045);  // after the 1st: 12 V, the motor on
  EXPECT_EQ(sig(*sim, "sheet/A2"), 1);
  EXPECT_GT(std::abs(sim->signal(axis + "current")), 0.1);
  sim->run_until(0.085);  // after the 2nd: off, no current
  EXPECT_EQ(sim->signal(axis + "motor_active"), 0);
  EXPECT_EQ(sig(*sim, "sheet/A2"), 0);
  sim->run_until(0.12);
  EXPECT_EQ(sim->signal(axis + "current"), 0);
  EXPECT_EQ(sim->signal(axis + "motor_torque"), 0);
  sim->run_until(0.165);  // after the 4th: on again, Ri doubled
  EXPECT_EQ(sig(*sim, "sheet/A1"), ri);
  EXPECT_EQ(sig(*sim, "sheet/B1"), 1);  // <gear ratio>
  EXPECT_EQ(sig(*sim, "sheet/C1"), 0);  // read while off
  EXPECT_EQ(sim->signal(axis + "motor_active"), 1);
  EXPECT_EQ(sim->signal(axis + "motor_ri"), 2 * ri);
  EXPECT_EQ(sig(*sim, "sheet/A2"), 1);
  sim->run_until(0.2);
  EXPECT_GT(std::abs(sim->signal(axis + "current")), 0.1);
  // GetAxisTorque is the axis's torque signal of the tick before the call.
  EXPECT_NE(sig(*sim, "sheet/A3"), 0);
  EXPECT_EQ(sig(*sim, "sheet/A4"), 0);   // the hinge
  EXPECT_EQ(sig(*sim, "sheet/B4"), 1);   // the Fixed joint has an index too
  EXPECT_EQ(sig(*sim, "sheet/C4"), -1);  // no such joint
  ::testing::internal::CaptureStderr();
  sim->run_until(0.3);  // the 6th refuses Ri = -1: the script stops, the motor keeps 2 Ri
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(sig(*sim, "controllers/script/error"), 1);
  EXPECT_NE(err.find("SetMotorPars: Ri = -1"), std::string::npos) << err;
  EXPECT_EQ(sim->signal(axis + "motor_ri"), 2 * ri);
  EXPECT_NEAR(sim->time_s(), 0.3, 1e-9);
}

/// SetSolidPos, SetSolidRotationMat, SetSolidLinearVel, SetSolidAngularVel (CartPole's reset,
/// simtwo-script-api.md §3.3) on scenes/cartpole: the cart (on a slider) and the pole (on a
/// hinge) go back to their load poses at rest; SetSolidColor paints the pole.
TEST_F(PascalScript, SolidTeleportsPutAJointedRobotBackAtRestAndColourIt) {
  if (std::system("fpc -iV > /dev/null 2>&1") != 0) GTEST_SKIP() << "no fpc";
  auto sim = Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "scenes/cartpole",
                              with_script(fs::path(S2SIM_PASCAL_FIXTURES) / "teleport.pas"));
  const std::string axes = "robots/cartpole/axes/";
  int pole = 0;  // scene body i is body i + 1
  for (std::size_t b = 0; b < sim->scene().bodies.size(); ++b)
    if (sim->scene().bodies[b].id == "pole") pole = static_cast<int>(b) + 1;
  ASSERT_GT(pole, 0);
  sim->run_until(0.019);  // what Initialize reads at the first script tick: the pole has
  const s2sim::Pose pole0 = sim->body_pose(pole);  // begun to fall
  const double hinge0 = sim->signal(axes + "hinge/pos");
  EXPECT_GT(std::abs(hinge0), 1e-5);
  sim->run_until(0.49);  // 24 calls (at T - dt, then every T): pushed and falling
  EXPECT_GT(sim->signal(axes + "slide/pos"), 0.05);
  EXPECT_GT(std::abs(sim->signal(axes + "hinge/speed")), 0.05);
  sim->run_until(0.5);  // the 25th call's teleport (0.499 s), then one tick of the push
  EXPECT_EQ(sig(*sim, "controllers/script/error"), 0);
  // One tick from rest under 5 N: the cart moves 2 µm, the pole turns 7 mrad/s.
  EXPECT_NEAR(sim->signal(axes + "slide/pos"), 0, 1e-5);
  EXPECT_NEAR(sim->signal(axes + "hinge/pos"), hinge0, 1e-5);
  EXPECT_NEAR(sim->signal(axes + "slide/speed"), 0, 5e-3);
  EXPECT_NEAR(sim->signal(axes + "hinge/speed"), 0, 1e-2);
  const s2sim::Pose pole1 = sim->body_pose(pole);
  EXPECT_NEAR(pole1.position.x, pole0.position.x, 1e-5);
  EXPECT_NEAR(pole1.position.z, pole0.position.z, 1e-5);
  const auto* painted = sim->annotations().body_color(pole);
  ASSERT_NE(painted, nullptr);
  EXPECT_EQ(painted->rgb[0], 1.0);
  EXPECT_EQ(painted->rgb[1], 0.0);
  EXPECT_EQ(painted->rgb[2], 0.2);
  ::testing::internal::CaptureStderr();
  sim->run_until(0.52);  // a 2x2 rotation raises as SimTwo's Mgetv does
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(sig(*sim, "controllers/script/error"), 1);
  EXPECT_NE(err.find("Invalid (row,col) value"), std::string::npos) << err;
  sim->reset();
  EXPECT_EQ(sim->annotations().body_color(pole), nullptr);
}

TEST_F(PascalScript, NonFiniteOrDegenerateTeleportsAreScriptErrorsNamingTheCall) {
  if (std::system("fpc -iV > /dev/null 2>&1") != 0) GTEST_SKIP() << "no fpc";
  for (const char* mode : {"0", "1"}) {
    SimulationOptions o = with_script(fs::path(S2SIM_PASCAL_FIXTURES) / "teleport_bad.pas");
    o.sheet_cells = {{1, 1, mode}};
    auto sim = Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "scenes/cartpole", o);
    ::testing::internal::CaptureStderr();
    sim->run_until(0.1);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(sig(*sim, "controllers/script/error"), 1) << mode;
    EXPECT_NE(
        err.find(std::string(mode) == "0" ? "SetSolidPos: argument 3 is NaN"
                                          : "SetSolidRotationMat: the matrix is not a rotation"),
        std::string::npos)
        << err;
    EXPECT_TRUE(std::isfinite(sim->signal("robots/cartpole/axes/slide/pos")));
  }
}

/// A 0/0 voltage stops the script with an error naming the routine and the line; the motor
/// keeps finite inputs, the simulation goes on, and the runner ends the run with exit 0.
TEST_F(PascalScript, NonFiniteVoltageIsAScriptErrorNamingTheCallAndItsLine) {
  SKIP_WITHOUT_SHARED("MotorModel_V3AGM");
  const fs::path script = fs::path(S2SIM_PASCAL_FIXTURES) / "nan_voltage.pas";
  auto sim = Simulation::load(shared("MotorModel_V3AGM"), with_script(script));
  const std::string axis = "robots/Motor/axes/InertialBoard/";
  sim->run_until(0.1);  // two calls at 6 V
  EXPECT_GT(std::abs(sim->signal(axis + "current")), 0.1);
  ::testing::internal::CaptureStderr();
  sim->run_until(2.0);
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NEAR(sim->time_s(), 2.0, 1e-9);
  EXPECT_EQ(sig(*sim, "controllers/script/error"), 1);
  EXPECT_EQ(sig(*sim, "controllers/script/calls"), 3);  // none after the error
  EXPECT_EQ(sig(*sim, "sheet/A1"), 3);
  EXPECT_NE(err.find("run-time error in Control"), std::string::npos) << err;
  EXPECT_NE(err.find("SetAxisVoltageRef: argument 3 is NaN"), std::string::npos) << err;
  EXPECT_NE(err.find("nan_voltage.pas:13"), std::string::npos) << err;  // the call's line
  EXPECT_EQ(sim->input(sim->input_index(axis + "ref_voltage")), 0);     // zeroed, never NaN
  for (const char* s : {"voltage", "current", "pos", "speed"})
    EXPECT_TRUE(std::isfinite(sim->signal(axis + s))) << s;

  const fs::path log = fs::temp_directory_path() / ("s2sim-nan-" + std::to_string(::getpid()));
  const std::string cmd = std::string(S2SIM_BIN_DIR) + "/s2sim-run " +
                          shared("MotorModel_V3AGM").string() + " --script " + script.string() +
                          " --duration 2 --quiet > " + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(log);
  const std::string out(std::istreambuf_iterator<char>(in), {});
  fs::remove(log);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status << "\n" << out;
  EXPECT_NE(out.find("SetAxisVoltageRef: argument 3 is NaN"), std::string::npos) << out;
}

TEST_F(PascalScript, ResetRunsTheScriptAgainFromInitialize) {
  SKIP_WITHOUT_SHARED("MotorModel_V3AGM");
  SimulationOptions o = with_script(fs::path(S2SIM_PASCAL_FIXTURES) / "runtime_error.pas");
  o.sheet_cells = {{1, 1, "0"}, {2, 1, "0"}};
  auto sim = Simulation::load(shared("MotorModel_V3AGM"), o);
  ::testing::internal::CaptureStderr();
  sim->run_until(0.5);
  EXPECT_EQ(sig(*sim, "controllers/script/error"), 1);
  sim->reset();  // a fresh copy of the library: globals zeroed, Initialize at the first tick
  EXPECT_EQ(sig(*sim, "controllers/script/error"), 0);
  EXPECT_EQ(sig(*sim, "sheet/A1"), 0);
  sim->run_until(0.1);
  EXPECT_EQ(sig(*sim, "controllers/script/calls"), 2);
  EXPECT_EQ(sig(*sim, "sheet/A1"), 2);
  sim->run_until(0.5);
  EXPECT_EQ(sig(*sim, "controllers/script/calls"), 3);
  (void)::testing::internal::GetCapturedStderr();
}

TEST_F(PascalScript, LocalsAndResultsStartAtZeroAsInPascalScript) {
  SKIP_WITHOUT_SHARED("MotorModel_V3AGM");
  SimulationOptions o = with_script(fs::path(S2SIM_PASCAL_FIXTURES) / "zero_locals.pas");
  o.sheet_cells = {{1, 1, "-1"}};
  auto sim = Simulation::load(shared("MotorModel_V3AGM"), o);
  sim->run_until(0.2);
  EXPECT_EQ(sig(*sim, "controllers/script/error"), 0);
  EXPECT_EQ(sig(*sim, "sheet/A1"), 0);
}

TEST_F(PascalScript, SameSceneScriptSeedAndInputsGiveIdenticalRuns) {
  SKIP_WITHOUT_SHARED("RobotFactoryLite");
  auto run = [&] {
    auto sim = Simulation::load(shared("RobotFactoryLite"), with_script());
    sim->set_input("keyboard/38", 1);
    sim->set_input("sheet/C2", 1);
    std::vector<double> all;
    for (int k = 0; k < 20; ++k) {
      sim->run_until(0.1 * (k + 1));
      for (std::size_t i = 0; i < sim->signal_count(); ++i)
        all.push_back(sim->signal(i));
    }
    return all;
  };
  const auto a = run();
  const auto b = run();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    ASSERT_EQ(std::memcmp(&a[i], &b[i], sizeof(double)), 0) << "value " << i;
}

using s2sim::test::loopback;
using s2sim::test::loopback_socket;

TEST_F(PascalScript, UdpLoopbackClientDrivesTheMotorAndReadsItsSensors) {
  SKIP_WITHOUT_SHARED("MotorModel_V3AGM");
  // The test's client socket on an ephemeral loopback port.
  int client_port = 0;
  const int client = loopback_socket(client_port);
  ASSERT_GE(client, 0);
  SimulationOptions o = with_script(fs::path(S2SIM_PASCAL_FIXTURES) / "udp_motor.pas");
  o.sheet_cells = {{1, 1, std::to_string(client_port)}};
  auto sim = Simulation::load(shared("MotorModel_V3AGM"), o);
  sim->run_until(0.5);
  EXPECT_NEAR(sim->signal("robots/Motor/axes/InertialBoard/pos"), 0, 1e-3);  // no command yet
  const sockaddr_in to = loopback(udp_port_);
  const std::string command = "V\r\n6\r\n";
  ASSERT_EQ(::sendto(client, command.data(), command.size(), 0,
                     reinterpret_cast<const sockaddr*>(&to), sizeof to),
            static_cast<ssize_t>(command.size()));
  sim->run_until(2.0);
  // Read every packet the script sent; the last one carries the moved axis.
  std::string last;
  char buf[2048];
  int packets = 0;
  for (ssize_t n; (n = ::recv(client, buf, sizeof buf, 0)) > 0; ++packets)
    last.assign(buf, static_cast<std::size_t>(n));
  ::close(client);
  EXPECT_EQ(packets, 50);  // one per 40 ms period over 2 s
  const double pos = sim->signal("robots/Motor/axes/InertialBoard/pos");
  EXPECT_GT(std::abs(pos), 0.5);  // the voltage moved it
  ASSERT_EQ(last.rfind("Enc\r\n", 0), 0u) << last;
  const auto at = last.find("Pos\r\n");
  ASSERT_NE(at, std::string::npos) << last;
  // GetAxisPos wraps a hinge into (-pi, pi] as SimTwo's ODE angle does; a period old at most.
  const double wrapped = std::remainder(pos, 2 * M_PI);
  EXPECT_NEAR(std::remainder(std::stod(last.substr(at + 5)) - wrapped, 2 * M_PI), 0, 0.2);
}

/// A raw pseudo-terminal's master side, its slave named as the script's serial port
/// (S2SIM_COM_PORT); -1 when none could be made.
int open_raw_pty() {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) return -1;
  termios raw{};
  ::tcgetattr(master, &raw);
  ::cfmakeraw(&raw);
  ::tcsetattr(master, TCSANOW, &raw);
  ::setenv("S2SIM_COM_PORT", ::ptsname(master), 1);
  return master;
}

TEST_F(PascalScript, SerialPortOnAPseudoTerminalIsByteExact) {
  SKIP_WITHOUT_SHARED("MotorModel_V3AGM");
  const int master = open_raw_pty();
  ASSERT_GE(master, 0);
  auto sim = Simulation::load(shared("MotorModel_V3AGM"),
                              with_script(fs::path(S2SIM_PASCAL_FIXTURES) / "serial_echo.pas"));
  ::fcntl(master, F_SETFL, ::fcntl(master, F_GETFL) | O_NONBLOCK);
  auto read_all = [&] {
    std::string s;
    char buf[256];
    for (ssize_t n; (n = ::read(master, buf, sizeof buf)) > 0;)
      s.append(buf, static_cast<std::size_t>(n));
    return s;
  };
  sim->run_until(0.05);
  EXPECT_EQ(read_all(), "ready");
  const std::string bytes("AT\r\n\x00\x7f\xff", 7);
  ASSERT_EQ(::write(master, bytes.data(), bytes.size()), 7);
  sim->run_until(0.2);
  EXPECT_EQ(read_all(), "echo:" + bytes);
  ::close(master);
}

/// The same lines from a peer ending in LF, CR, CR LF or a mix: a script's TStringList.Text
/// splits them alike (SimTwo's does; FPC's splits on CR LF alone), and a CR LF peer's text
/// comes back unchanged.
const std::vector<std::string> kLineEnds = {"u 0.3\nV\n6\n", "u 0.3\rV\r6\r", "u 0.3\r\nV\r\n6\r\n",
                                            "u 0.3\nV\r\n6\r"};
const std::string kParsed = "3|u 0.3|V|6|u 0.3\r\nV\r\n6\r\n";

TEST_F(PascalScript, UdpTextLinesEndingInLfCrOrCrLfAreSplitAlike) {
  SKIP_WITHOUT_SHARED("MotorModel_V3AGM");
  int client_port = 0;
  const int client = loopback_socket(client_port);
  ASSERT_GE(client, 0);
  SimulationOptions o = with_script(fs::path(S2SIM_PASCAL_FIXTURES) / "text_lines.pas");
  o.sheet_cells = {{1, 1, std::to_string(client_port)}};
  auto sim = Simulation::load(shared("MotorModel_V3AGM"), o);
  const sockaddr_in to = loopback(udp_port_);
  double t = 0.05;
  for (const std::string& text : kLineEnds) {
    ASSERT_EQ(::sendto(client, text.data(), text.size(), 0, reinterpret_cast<const sockaddr*>(&to),
                       sizeof to),
              static_cast<ssize_t>(text.size()));
    sim->run_until(t += 0.05);  // one script period at least
    char buf[2048];
    std::vector<std::string> replies;
    for (ssize_t n; (n = ::recv(client, buf, sizeof buf, 0)) > 0;)
      replies.emplace_back(buf, static_cast<std::size_t>(n));
    ASSERT_EQ(replies.size(), 1u) << "for " << ::testing::PrintToString(text);
    EXPECT_EQ(replies[0], kParsed) << "for " << ::testing::PrintToString(text);
  }
  ::close(client);
  EXPECT_EQ(sig(*sim, "controllers/script/error"), 0);
}

TEST_F(PascalScript, SerialTextLinesEndingInLfCrOrCrLfAreSplitAlike) {
  SKIP_WITHOUT_SHARED("MotorModel_V3AGM");
  const int master = open_raw_pty();
  ASSERT_GE(master, 0);
  auto sim = Simulation::load(shared("MotorModel_V3AGM"),
                              with_script(fs::path(S2SIM_PASCAL_FIXTURES) / "text_lines.pas"));
  ::fcntl(master, F_SETFL, ::fcntl(master, F_GETFL) | O_NONBLOCK);
  double t = 0.05;
  for (const std::string& text : kLineEnds) {
    ASSERT_EQ(::write(master, text.data(), text.size()), static_cast<ssize_t>(text.size()));
    sim->run_until(t += 0.05);
    std::string reply;
    char buf[256];
    for (ssize_t n; (n = ::read(master, buf, sizeof buf)) > 0;)
      reply.append(buf, static_cast<std::size_t>(n));
    EXPECT_EQ(reply, kParsed) << "for " << ::testing::PrintToString(text);
  }
  ::close(master);
  EXPECT_EQ(sig(*sim, "controllers/script/error"), 0);
}

TEST_F(PascalScript, RunnerWritesIdenticalCsvLogsForTheSameSceneScriptSeedAndInputs) {
  SKIP_WITHOUT_SHARED("RobotFactoryLite");
  const fs::path dir =
      fs::temp_directory_path() / ("s2sim-pascal-csv-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  auto run = [&](const std::string& name) {
    const std::string cmd = std::string(S2SIM_BIN_DIR) + "/s2sim-run " +
                            shared("RobotFactoryLite").string() +
                            " --duration 2 --quiet --seed 7 --set keyboard/38=1 --press 2,3@0.3 "
                            "--log " +
                            (dir / name).string() + " > /dev/null 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0);
    std::ifstream in(dir / name, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string a = run("a.csv"), b = run("b.csv");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_TRUE(a == b) << "the two CSV logs differ";
  fs::remove_all(dir);
}

TEST_F(PascalScript, RunnerPressAndSheetOptionsAreValidated) {
  SKIP_WITHOUT_SHARED("RobotFactoryLite");
  const std::string run = std::string(S2SIM_BIN_DIR) + "/s2sim-run " +
                          shared("RobotFactoryLite").string() + " --duration 1 --quiet ";
  auto code = [](const std::string& cmd) {
    const int s = std::system((cmd + " > /dev/null 2>&1").c_str());
    return WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  };
  EXPECT_EQ(code(run + "--press 11,3@0.5 --sheet 12,3=-0.525"), 0);
  EXPECT_EQ(code(run + "--press 11"), 4);
  EXPECT_EQ(code(run + "--press 0,3"), 4);
  EXPECT_EQ(code(run + "--press 11,3@-1"), 4);
  EXPECT_EQ(code(run + "--sheet 12,3"), 4);
  EXPECT_EQ(code(run + "--sheet 12,3=abc"), 4);
  EXPECT_EQ(code(run + "--press 40,40"), 4);  // no such cell in the sheet
  EXPECT_EQ(code(run + "--no-script --sheet 12,3=1"), 4);
}

}  // namespace
