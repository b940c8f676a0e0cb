// SimTwo's routines that S2Sim added for the whole script API (docs/scripting.md, coverage), on
// this folder's script_api scene: the pure ones against numbers worked by hand, things pushed
// and spun, trails cut, UDP datagrams read one by one.
#include <s2sim/kernel/annotations.hpp>
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include "loopback.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using s2sim::ScriptMode;
using s2sim::Simulation;
using s2sim::SimulationOptions;

namespace {

const fs::path kScene = fs::path(S2SIM_PASCAL_FIXTURES) / ".." / "script_api";

#define SKIP_WITHOUT_FPC \
  if (std::system("fpc -iV > /dev/null 2>&1") != 0) GTEST_SKIP() << "no fpc"

using s2sim::test::loopback;
using s2sim::test::loopback_socket;

class ScriptApi : public ::testing::Test {
 protected:
  void SetUp() override {
    ::setenv("S2SIM_PASCAL_CACHE", S2SIM_PASCAL_TEST_CACHE, 1);
    ::unsetenv("S2SIM_FPC");
    ::unsetenv("S2SIM_COM_PORT");
    int port = 0;
    const int fd = loopback_socket(port);  // a free port for the script's socket
    ::close(fd);
    script_port_ = port;
    ::setenv("S2SIM_UDP_PORT", std::to_string(port).c_str(), 1);
    work_ = fs::temp_directory_path() / ("s2sim-script-api-" + std::to_string(::getpid()));
    fs::create_directories(work_);
    ::setenv("S2SIM_SCRIPT_API_DIR", work_.c_str(), 1);
  }
  void TearDown() override { fs::remove_all(work_); }

  static SimulationOptions with(const char* fixture) {
    SimulationOptions o;
    o.script_mode = ScriptMode::always;
    o.script_file = fs::path(S2SIM_PASCAL_FIXTURES) / fixture;
    return o;
  }

  int script_port_ = 0;
  fs::path work_;
};

std::vector<std::string> lines_starting(const Simulation& sim, const std::string& head) {
  std::vector<std::string> found;
  for (const auto& line : sim.annotations().lines)
    if (line.text.rfind(head, 0) == 0) found.push_back(line.text);
  return found;
}

TEST_F(ScriptApi, PureRoutinesGiveTheNumbersWorkedByHand) {
  SKIP_WITHOUT_FPC;
  auto sim = Simulation::load(kScene, with("pure_routines.pas"));
  sim->run_until(0.1);
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  const auto checks = lines_starting(*sim, "CHECK ");
  EXPECT_GE(checks.size(), 59u);
  for (const auto& c : checks)
    EXPECT_EQ(c.substr(c.size() - 3), " ok") << c;
  EXPECT_EQ(lines_starting(*sim, "CHECKS DONE").size(), 1u);
}

TEST_F(ScriptApi, SceneQueriesGiveTheSceneFilesSizesColoursAndCentresOfMass) {
  SKIP_WITHOUT_FPC;
  auto sim = Simulation::load(kScene, with("scene_queries.pas"));
  sim->run_until(0.1);
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  const auto checks = lines_starting(*sim, "CHECK ");
  EXPECT_EQ(checks.size(), 11u);
  for (const auto& c : checks)
    EXPECT_EQ(c.substr(c.size() - 3), " ok") << c;
  EXPECT_EQ(lines_starting(*sim, "CHECKS DONE").size(), 1u);
}

TEST_F(ScriptApi, JointWayPointsAreReadAndWrittenAsSimTwoDoes) {
  SKIP_WITHOUT_FPC;
  auto sim = Simulation::load(kScene, with("joint_waypoints.pas"));
  sim->run_until(0.1);
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  const auto checks = lines_starting(*sim, "CHECK ");
  EXPECT_EQ(checks.size(), 6u);
  for (const auto& c : checks)
    EXPECT_EQ(c.substr(c.size() - 3), " ok") << c;
  EXPECT_EQ(lines_starting(*sim, "CHECKS DONE").size(), 1u);
}

TEST_F(ScriptApi, BeltSpeedSetByTheScriptCarriesTheCrateOnIt) {
  SKIP_WITHOUT_FPC;
  SimulationOptions o = with("belt_speed.pas");
  o.sheet_cells = {{1, 1, "0"}};
  auto sim = Simulation::load(kScene, o);
  EXPECT_EQ(sim->signal("robots/conveyor/solids/belt/belt_speed"), 0.5);  // the scene's
  sim->run_until(1.0);
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  EXPECT_EQ(sim->signal("robots/conveyor/solids/belt/belt_speed"), 0.2);
  EXPECT_EQ(sim->signal("sheet/A1"), 0.2);
  EXPECT_NEAR(sim->signal("things/crate/vx"), 0.2, 0.01);  // carried at the belt's speed
  // Snapshot and reset bring the run back exactly.
  const auto snap = sim->save();
  sim->run_until(1.5);
  const double x = sim->signal("things/crate/x");
  sim->restore(snap);
  sim->run_until(1.5);
  EXPECT_EQ(sim->signal("things/crate/x"), x);
  sim->reset();
  EXPECT_EQ(sim->signal("robots/conveyor/solids/belt/belt_speed"), 0.5);
}

TEST_F(ScriptApi, UnitsOfTheSameNameWhereS2SimRunsAreNotTakenForTheSupportUnits) {
  SKIP_WITHOUT_FPC;
  // A folder holding a broken s2simtwo_types.pas, made the working folder for the compile.
  const fs::path here = work_ / "cwd";
  fs::create_directories(here);
  std::ofstream(here / "s2simtwo_types.pas") << "unit s2simtwo_types; this is not Pascal\n";
  const fs::path before = fs::current_path();
  fs::current_path(here);
  const fs::path cache = work_ / "cache";  // a compile of its own, not the shared cache's copy
  ::setenv("S2SIM_PASCAL_CACHE", cache.c_str(), 1);
  std::unique_ptr<Simulation> sim;
  EXPECT_NO_THROW(sim = Simulation::load(kScene, with("belt_speed.pas")));
  fs::current_path(before);
  ::setenv("S2SIM_PASCAL_CACHE", S2SIM_PASCAL_TEST_CACHE, 1);
  ASSERT_TRUE(sim);
  sim->run_until(0.1);
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
}

TEST_F(ScriptApi, ThingPushedForOneStepGainsImpulseOverMassAndSpinsAsSet) {
  SKIP_WITHOUT_FPC;
  SimulationOptions o = with("thing_motion.pas");
  o.sheet_cells = {{1, 1, "0"}, {1, 2, "0"}, {1, 3, "0"}};  // the cells the script writes
  auto sim = Simulation::load(kScene, o);
  sim->run_until(0.1);  // calls at 39 and 79 ms
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  // 100 N for one 1 ms step on 0.2 kg: 0.5 m/s sliding; by the read, 40 ms later, the floor's
  // friction has made the ball roll, at 5/7 of it (a solid sphere, I = 2/5 m r^2: 0.357 m/s;
  // 0.3576 seen). Its spin about the vertical, set at 3 rad/s, meets no friction torque.
  EXPECT_NEAR(sim->signal("sheet/A1"), 0.5 * 5 / 7, 0.005);
  EXPECT_NEAR(sim->signal("sheet/B1"), 3, 1e-6);
  EXPECT_DOUBLE_EQ(sim->signal("sheet/C1"), 0.5);  // the link's mass as loaded
}

TEST_F(ScriptApi, ThingsAddedAndDeletedByTheScriptKeepSimTwosListAndFallAsFreeFallSays) {
  SKIP_WITHOUT_FPC;
  SimulationOptions o = with("add_things.pas");
  for (int c = 1; c <= 6; ++c)
    o.sheet_cells.push_back({1, c, "0"});
  for (int c = 1; c <= 5; ++c)
    o.sheet_cells.push_back({2, c, "0"});
  auto sim = Simulation::load(kScene, o);
  EXPECT_EQ(sim->scene().runtime_things.size(), 32u) << "the script adds things: the default";
  auto run = [&] {
    sim->run_until(1.25);  // calls every 40 ms from 39 ms on
    EXPECT_EQ(sim->signal("controllers/script/error"), 0);
    std::vector<double> cells;
    for (const char* cell : {"A1", "B1", "C1", "D1", "E1", "F1", "A2", "B2", "C2", "E2"})
      cells.push_back(sim->signal(std::string("sheet/") + cell));
    return cells;
  };
  const std::vector<double> cells = run();
  EXPECT_EQ(cells[0], 2) << "after the scene's ball and crate";
  EXPECT_EQ(cells[1], 3);
  EXPECT_EQ(cells[2], 2);
  EXPECT_EQ(cells[5], 2) << "a duplicate ID and a negative mass refused";
  EXPECT_EQ(cells[3], 0) << "DeleteThing returns the index it removed";
  EXPECT_EQ(cells[4], 1) << "the later things' indices shift down";
  // Added at rest at 1 m after the call at 39 ms, read 40 ms later: z = 1 - g t^2 / 2.
  EXPECT_NEAR(cells[6], 1 - 0.5 * 9.81 * 0.04 * 0.04, 1e-3);
  EXPECT_NEAR(cells[7], 0.05, 2e-3) << "landed on the floor by 1.2 s";
  EXPECT_EQ(cells[8], 0) << "ClearThings removes every thing";
  EXPECT_EQ(cells[9], -1) << "an unknown ID";
  for (const auto& t : sim->things())
    EXPECT_FALSE(t.present) << t.id;
  // A reset brings the scene's things back and a second run is the first, bit for bit.
  sim->reset();
  EXPECT_TRUE(sim->things()[0].present);
  EXPECT_EQ(run(), cells);
}

TEST_F(ScriptApi, ShellObstacleAndSensorColoursReachTheViewerAndReadBack) {
  SKIP_WITHOUT_FPC;
  SimulationOptions o = with("paint.pas");
  o.sheet_cells = {{1, 1, "0"}, {1, 2, "0"}, {1, 3, "1"}};
  auto sim = Simulation::load(kScene, o);
  sim->run_until(0.05);
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  EXPECT_EQ(sim->signal("sheet/A1"), 51);
  EXPECT_EQ(sim->signal("sheet/B1"), 255);
  EXPECT_EQ(sim->signal("sheet/C1"), 0) << "the motor turns with the axis";
  const s2sim::Annotations& notes = sim->annotations();
  ASSERT_EQ(notes.shape_colors.size(), 2u);
  const auto& shells = sim->scene().robots[0].shells;
  ASSERT_FALSE(shells.empty());
  const auto* shell = notes.shape_color(shells[0].first + 1, shells[0].second);
  ASSERT_NE(shell, nullptr);
  EXPECT_DOUBLE_EQ(shell->rgb[0], 1);
  EXPECT_DOUBLE_EQ(shell->rgb[2], 0.2);
  const auto* obstacle = notes.shape_color(0, 0);
  ASSERT_NE(obstacle, nullptr);
  EXPECT_DOUBLE_EQ(obstacle->rgb[1], 1);
  ASSERT_EQ(notes.sensor_colors.size(), 1u);
  EXPECT_DOUBLE_EQ(notes.sensor_colors[0].rgb[2], 1);
  EXPECT_EQ(sim->scene().sensors[static_cast<std::size_t>(notes.sensor_colors[0].sensor)].robot, 0);
  sim->reset();
  EXPECT_TRUE(sim->annotations().shape_colors.empty()) << "a reset restores the scene's colours";
}

TEST_F(ScriptApi, ObstaclesAddedMovedAndDeletedByTheScriptHoldAndReleaseWhatLiesOnThem) {
  SKIP_WITHOUT_FPC;
  SimulationOptions o = with("add_obstacles.pas");
  for (int c = 1; c <= 6; ++c)
    o.sheet_cells.push_back({1, c, "0"});
  o.sheet_cells.push_back({2, 1, "0"});
  auto sim = Simulation::load(kScene, o);
  sim->run_until(2.45);  // calls every 40 ms from 39 ms on
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  EXPECT_EQ(sim->signal("sheet/A1"), 1) << "after the scene's wall";
  EXPECT_NEAR(sim->signal("sheet/B1"), 0.51 + 0.05, 2e-3) << "the parcel rests on the shelf";
  EXPECT_NEAR(sim->signal("sheet/C1"), 0.3, 1e-12) << "the shelf moved down";
  EXPECT_NEAR(sim->signal("sheet/D1"), 0.31 + 0.05, 2e-3) << "and the parcel followed it";
  EXPECT_EQ(sim->signal("sheet/E1"), 1);
  EXPECT_NEAR(sim->signal("sheet/F1"), 0.05, 2e-3) << "deleted, it let the parcel fall";
  EXPECT_EQ(sim->signal("sheet/A2"), -1) << "ClearObstacles removed the scene's wall too";
  EXPECT_FALSE(sim->obstacle_present(0));
  sim->reset();
  EXPECT_TRUE(sim->obstacle_present(0));
}

TEST_F(ScriptApi, SizesAndSurfacesSetByTheScriptTakeEffectAndReadBack) {
  SKIP_WITHOUT_FPC;
  SimulationOptions o = with("resize.pas");
  o.sheet_cells = {{1, 1, "0"}, {1, 2, "0"}, {1, 3, "0"}};
  auto sim = Simulation::load(kScene, o);
  sim->run_until(1.05);
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  EXPECT_DOUBLE_EQ(sim->signal("sheet/A1"), 0.1);
  EXPECT_DOUBLE_EQ(sim->signal("sheet/B1"), 0.3);
  EXPECT_NEAR(sim->signal("sheet/C1"), 0.1, 2e-3) << "the grown ball rests on its new radius";
  const int ball = sim->things()[0].body;
  EXPECT_EQ(*sim->resized(ball), (s2sim::Vec3{0.1, 0.1, 0.1}));
  sim->reset();
  EXPECT_FALSE(sim->resized(ball));
}

TEST_F(ScriptApi, AMassSetByTheScriptTakesEffectAndReadsBack) {
  SKIP_WITHOUT_FPC;
  SimulationOptions o = with("mass.pas");
  o.sheet_cells = {{1, 1, "0"}, {1, 2, "0"}, {1, 3, "0"}};
  auto sim =
      Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/pendulum_mass", o);
  sim->run_until(0.2);
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  EXPECT_DOUBLE_EQ(sim->signal("sheet/A1"), 1.0);
  EXPECT_DOUBLE_EQ(sim->signal("sheet/B1"), 2.5);
  EXPECT_DOUBLE_EQ(sim->signal("sheet/C1"), 1.0) << "a negative mass raises in the script";
  const int bob = 1;
  const Simulation::MassProperties m = sim->body_mass(bob);
  EXPECT_EQ(m.mass_kg, 2.5);
  EXPECT_NEAR(m.inertia_kg_m2.m[1][1], 2.5 * 0.4 * 0.02 * 0.02, 1e-15) << "scaled with the mass";
  sim->reset();
  EXPECT_EQ(sim->body_mass(bob).mass_kg, 1.0);
}

TEST_F(ScriptApi, TheFireEffectBurnsWhereTheScriptPutsItAndGoesOut) {
  SKIP_WITHOUT_FPC;
  auto sim = Simulation::load(kScene, with("fire.pas"));
  sim->run_until(0.05);  // the first call, at 39 ms
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  const s2sim::Annotations::Fire& fire = sim->annotations().fire;
  EXPECT_TRUE(fire.burning);
  EXPECT_EQ(fire.body, 0);
  EXPECT_EQ(fire.position_m.x, 1);
  EXPECT_EQ(fire.position_m.y, 0.5);
  EXPECT_EQ(fire.scale.z, 3);
  sim->run_until(0.13);  // the third
  EXPECT_TRUE(sim->annotations().fire.burning);
  EXPECT_GT(sim->annotations().fire.body, 0) << "on the arm's link";
  sim->run_until(0.21);  // the fifth
  EXPECT_FALSE(sim->annotations().fire.burning);
  sim->reset();
  EXPECT_FALSE(sim->annotations().fire.burning);
}

/// Every datagram waiting on `client`, in order.
std::vector<std::string> received(int client) {
  std::vector<std::string> got;
  char buf[2048];
  for (ssize_t n; (n = ::recv(client, buf, sizeof buf, 0)) > 0;)
    got.emplace_back(buf, static_cast<std::size_t>(n));
  return got;
}

TEST_F(ScriptApi, DelTrailNodeRemovesTheOldestNodeAndPacketsAreReadOneByOne) {
  SKIP_WITHOUT_FPC;
  int client_port = 0;
  const int client = loopback_socket(client_port);
  ASSERT_GE(client, 0);
  SimulationOptions o = with("trails_and_packets.pas");
  o.sheet_cells = {{1, 1, std::to_string(client_port)}};
  auto sim = Simulation::load(kScene, o);
  const sockaddr_in to = loopback(script_port_);
  for (const std::string text : {"one", "two\n", "three"})
    ASSERT_EQ(::sendto(client, text.data(), text.size(), 0, reinterpret_cast<const sockaddr*>(&to),
                       sizeof to),
              static_cast<ssize_t>(text.size()));
  sim->run_until(0.05);
  const std::vector<std::string> replies = received(client);
  ::close(client);
  EXPECT_EQ(replies, (std::vector<std::string>{"count 3", "one", "two\n", "three", "after 0"}));
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  bool found = false;
  for (const auto& trail : sim->annotations().trails)
    if (trail.id == 3) {
      found = true;
      ASSERT_EQ(trail.points_m.size(), 2u);
      EXPECT_EQ(trail.points_m.front().x, 2);
      EXPECT_EQ(trail.points_m.back().x, 3);
    }
  EXPECT_TRUE(found);
}

// One stream of bytes as in SimTwo: UDPDataRead holds what arrived, ReadUDPData takes the
// same bytes and empties it, and the datagrams ReadUDPPacket reads are kept apart.
TEST_F(ScriptApi, UdpDataReadHoldsTheBytesReceivedUntilReadUdpDataTakesThem) {
  SKIP_WITHOUT_FPC;
  int client_port = 0;
  const int client = loopback_socket(client_port);
  ASSERT_GE(client, 0);
  SimulationOptions o = with("udp_stream.pas");
  o.sheet_cells = {{1, 1, std::to_string(client_port)}};
  auto sim = Simulation::load(kScene, o);
  const sockaddr_in to = loopback(script_port_);
  auto send = [&](const std::string& text) {
    ASSERT_EQ(::sendto(client, text.data(), text.size(), 0, reinterpret_cast<const sockaddr*>(&to),
                       sizeof to),
              static_cast<ssize_t>(text.size()));
  };
  auto replies = [&] { return received(client); };
  for (const std::string text : {"one", "two\n", "three"})
    send(text);
  sim->run_until(0.09);  // two calls: the second finds nothing
  EXPECT_EQ(replies(), (std::vector<std::string>{"size 12", "stream onetwo\nthree",
                                                 "read onetwo\nthree", "after 0 packets 3"}));
  send("four");
  sim->run_until(0.13);
  EXPECT_EQ(replies(),
            (std::vector<std::string>{"size 4", "stream four", "read four", "after 0 packets 4"}));
  ::close(client);
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
}

// MeshThing changes the picture only (Annotations::body_meshes, which the viewer draws): the
// file is resolved against the script's folder, the spare body's next thing forgets the mesh,
// a reset forgets them all, and bad input is a script error naming it.
TEST_F(ScriptApi, MeshThingDrawsAThingAsAMeshFileUntilItsBodyTakesAnotherThing) {
  SKIP_WITHOUT_FPC;
  auto sim = Simulation::load(kScene, with("mesh_thing.pas"));
  auto body_of = [&](const std::string& id) {
    for (const auto& t : sim->things())
      if (t.id == id && t.present) return t.body;
    return -1;
  };
  sim->run_until(0.05);
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
  const fs::path obj = fs::absolute(fs::path(S2SIM_PASCAL_FIXTURES) / "crate.obj");
  const int crate = body_of("crate"), b1 = body_of("b1");
  ASSERT_GT(crate, 0);
  ASSERT_GT(b1, 0);
  const s2sim::Annotations& notes = sim->annotations();
  ASSERT_EQ(notes.body_meshes.size(), 2u);
  const auto* on_crate = notes.body_mesh(crate);
  ASSERT_NE(on_crate, nullptr);
  EXPECT_EQ(fs::weakly_canonical(on_crate->file), fs::weakly_canonical(obj));
  EXPECT_EQ(on_crate->scale, 2);
  EXPECT_FALSE(on_crate->casts_shadow);
  EXPECT_TRUE(on_crate->shadow_file.empty());
  const auto* on_b1 = notes.body_mesh(b1);
  ASSERT_NE(on_b1, nullptr);
  EXPECT_EQ(fs::weakly_canonical(on_b1->shadow_file), fs::weakly_canonical(obj));
  EXPECT_TRUE(on_b1->casts_shadow);
  EXPECT_EQ(lines_starting(*sim, "MeshThing: no thing 'nothing'").size(), 1u);

  sim->run_until(0.09);
  EXPECT_EQ(body_of("b2"), b1) << "the spare body the deleted thing left";
  EXPECT_EQ(sim->annotations().body_mesh(b1), nullptr) << "b2 is drawn as its own box";
  EXPECT_NE(sim->annotations().body_mesh(crate), nullptr);
  const auto caught = lines_starting(*sim, "caught ");
  ASSERT_EQ(caught.size(), 2u);
  EXPECT_NE(caught[0].find("MeshThing('b2'): cannot find the mesh file"), std::string::npos)
      << caught[0];
  EXPECT_NE(caught[0].find("missing.stl"), std::string::npos) << caught[0];
  EXPECT_NE(caught[1].find("MeshScale must be finite and > 0, got 0"), std::string::npos)
      << caught[1];

  sim->reset();
  EXPECT_TRUE(sim->annotations().body_meshes.empty());
}

/// A free TCP port on loopback (bound and released).
int free_tcp_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in me = loopback(0);
  socklen_t len = sizeof me;
  ::bind(fd, reinterpret_cast<sockaddr*>(&me), sizeof me);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&me), &len);
  ::close(fd);
  return ntohs(me.sin_port);
}

std::string bytes(std::initializer_list<int> b) {
  std::string s;
  for (int v : b)
    s += static_cast<char>(v);
  return s;
}

TEST_F(ScriptApi, ModbusTcpHoldingRegistersCoilsAndInputsByteForByte) {
  SKIP_WITHOUT_FPC;
  const int port = free_tcp_port();
  ::setenv("S2SIM_MODBUS_PORT", std::to_string(port).c_str(), 1);
  SimulationOptions o = with("modbus_mirror.pas");
  o.sheet_cells = {{1, 1, "0"}};
  auto sim = Simulation::load(kScene, o);
  ::unsetenv("S2SIM_MODBUS_PORT");
  const int client = ::socket(AF_INET, SOCK_STREAM, 0);
  const sockaddr_in to = loopback(port);
  ASSERT_EQ(::connect(client, reinterpret_cast<const sockaddr*>(&to), sizeof to), 0);
  const int yes = 1;
  ::setsockopt(client, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
  // One request, one script period (the server answers at each script tick), the answer.
  auto exchange = [&](const std::string& request) {
    EXPECT_EQ(::send(client, request.data(), request.size(), 0),
              static_cast<ssize_t>(request.size()));
    sim->run_until(sim->time_s() + 0.04);
    std::string reply;
    char buf[512];
    for (ssize_t n; (n = ::recv(client, buf, sizeof buf, MSG_DONTWAIT)) > 0;)
      reply.append(buf, static_cast<std::size_t>(n));
    return reply;
  };
  // Write 3 holding registers at 100 (function 16), transaction 0x0102, unit 7.
  EXPECT_EQ(exchange(bytes({0x01, 0x02, 0, 0, 0, 13, 7, 16, 0, 100, 0, 3, 6, 0x12, 0x34, 0xAB, 0xCD,
                            0x00, 0x01})),
            bytes({0x01, 0x02, 0, 0, 0, 6, 7, 16, 0, 100, 0, 3}));
  // Read them back (function 3).
  EXPECT_EQ(exchange(bytes({0x00, 0x03, 0, 0, 0, 6, 7, 3, 0, 100, 0, 3})),
            bytes({0x00, 0x03, 0, 0, 0, 9, 7, 3, 6, 0x12, 0x34, 0xAB, 0xCD, 0x00, 0x01}));
  // Coil 3 on (function 5): the script mirrors it into input 5 at its next call.
  EXPECT_EQ(exchange(bytes({0x00, 0x04, 0, 0, 0, 6, 7, 5, 0, 3, 0xFF, 0x00})),
            bytes({0x00, 0x04, 0, 0, 0, 6, 7, 5, 0, 3, 0xFF, 0x00}));
  EXPECT_EQ(sim->signal("sheet/A1"), 1);
  // Discrete inputs 0..7 (function 2): bit 5.
  EXPECT_EQ(exchange(bytes({0x00, 0x05, 0, 0, 0, 6, 7, 2, 0, 0, 0, 8})),
            bytes({0x00, 0x05, 0, 0, 0, 4, 7, 2, 1, 0x20}));
  // Coils 0..15 (function 1), and a function the server has not: exception 1.
  EXPECT_EQ(exchange(bytes({0x00, 0x06, 0, 0, 0, 6, 7, 1, 0, 0, 0, 16})),
            bytes({0x00, 0x06, 0, 0, 0, 5, 7, 1, 2, 0x08, 0x00}));
  EXPECT_EQ(exchange(bytes({0x00, 0x07, 0, 0, 0, 2, 7, 0x2B})),
            bytes({0x00, 0x07, 0, 0, 0, 3, 7, 0xAB, 1}));
  ::close(client);
  EXPECT_EQ(sim->signal("controllers/script/error"), 0);
}

}  // namespace
