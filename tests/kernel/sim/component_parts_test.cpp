// Components stepped in the island parts (kernel/src/sim/component_parts.cpp): which scenes
// run their components in the parts, that those give the serial run's numbers bit for bit,
// and that a local component is held to its declaration (ConfigureContext::declare_local) at
// any number of threads.
#include <s2sim/error.hpp>
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>
#include "common/temp_dir.hpp"

namespace s2sim {
namespace {

namespace fs = std::filesystem;

bool two_threads_available() {
  return std::thread::hardware_concurrency() >= 2;
}

/// Four peer-benchmark robots in a row (r0, r1 are dealt to part 0, r2, r3 to part 1), with
/// `plugins` (scene-level `<plugin>` elements) after them.
fs::path write_scene(const std::string& name, const std::string& plugins) {
  const fs::path dir = s2sim::test::process_temp_dir() / ("component_parts_" + name);
  fs::create_directories(dir);
  const fs::path robot = fs::path(S2SIM_SOURCE_DIR) / "bench/peers/scenes/diffbot.xml";
  std::ofstream f(dir / "scene.xml");
  f << "<scene>\n";
  for (int r = 0; r < 4; ++r)
    f << "  <robot><ID name='r" << r << "'/><pos x='" << 1.5 * r << "' y='0' z='0'/><body file='"
      << robot.string() << "'/></robot>\n";
  f << plugins << "</scene>\n";
  return dir;
}

std::unique_ptr<Simulation> load(const fs::path& scene, int threads) {
  SimulationOptions o;
  o.threads = threads;
  o.plugin_path = {fs::path(S2SIM_TEST_PLUGIN_DIR) / "scene", fs::path(S2SIM_PLUGIN_DIR)};
  return Simulation::load(scene, o);
}

/// A local speed controller on robot r's two wheels that also reads an encoder's count (its
/// own right wheel's unless `reads` says which).
std::string controller(int r, const std::string& extra = "", std::string reads = "") {
  const std::string axes = "robots/r" + std::to_string(r) + "/axes/";
  if (reads.empty()) reads = axes + "right/encoder";
  return "  <plugin kind='test_local_controller' id='c" + std::to_string(r) + "' axes='" + axes +
         "left " + axes + "right' reads='" + reads + "' gain='" + std::to_string(0.5 + 0.25 * r) +
         "' " + extra + "/>\n";
}

std::vector<double> signals(const Simulation& sim) {
  std::vector<double> out(sim.signal_count());
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = sim.signal(i);
  return out;
}

/// Steps both `ticks` times side by side: the first tick after which a signal's bits differ,
/// or -1.
int first_differing_tick(Simulation& serial, Simulation& parallel, int ticks) {
  for (int tick = 0; tick < ticks; ++tick) {
    serial.step();
    parallel.step();
    const std::vector<double> a = signals(serial), b = signals(parallel);
    if (a.size() != b.size() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) != 0)
      return tick;
  }
  return -1;
}

TEST(ComponentParts, LocalControllersAndTheDriveTrainRunInTheirPartsWithTheSerialResults) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  // Each controller also sums the contact force on its robot's brick (its caster's) from the
  // contact list: all of it on one thread, its part's on two.
  std::string plugins;
  for (int r = 0; r < 4; ++r)
    plugins += controller(r, "body='robots/r" + std::to_string(r) + "/solids/brick'");
  const fs::path scene = write_scene("local", plugins);
  auto serial = load(scene, 1);
  auto parallel = load(scene, 2);
  EXPECT_NE(serial->components_serial_reason().find("one part"), std::string::npos)
      << serial->components_serial_reason();
  ASSERT_EQ(parallel->components_serial_reason(), "");
  ASSERT_EQ(first_differing_tick(*serial, *parallel, 800), -1);
  // The controllers ran and drove the wheels.
  EXPECT_GT(std::abs(serial->signal("robots/r3/axes/right/speed")), 1.0);
  EXPECT_NE(serial->signal("controllers/c2/seen"), 0.0);   // its encoder's count, read
  EXPECT_GT(serial->signal("controllers/c3/touch"), 0.1);  // its caster's share of ~4.7 N
  // The list the façade reads is the whole one, merged from the parts' on demand.
  ASSERT_EQ(serial->contact_count(), parallel->contact_count());
  for (std::size_t c = 0; c < serial->contact_count(); ++c)
    EXPECT_EQ(std::memcmp(&serial->contact(c), &parallel->contact(c), sizeof(ContactInfo)), 0)
        << "contact " << c;
}

TEST(ComponentParts, RobotsWithLocalSensorsRunThemInTheirPartsWithTheSerialResults) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  // The peers' robot with an IMU, a pose sensor, a bumper on its caster and a force sensor in
  // its right wheel's joint: the sensors plugin's local kinds.
  const fs::path dir = s2sim::test::process_temp_dir() / "component_parts_sensors";
  fs::create_directories(dir);
  std::string robot;
  {
    std::ifstream in(fs::path(S2SIM_SOURCE_DIR) / "bench/peers/scenes/diffbot.xml");
    robot.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  robot.replace(robot.rfind("</robot>"), 8, R"(<sensors>
    <imu><ID value='imu'/><solid id='brick'/><period value='0.002'/>
      <accelerometer noise='0.02'/></imu>
    <pose><ID value='where'/><solid id='brick'/></pose>
    <touch><ID value='bump'/><solid id='brick'/><pos x='-0.06' y='0' z='-0.07'/>
      <region x='0.04' y='0.04' z='0.04'/></touch>
    <jointforce><ID value='axle'/><joint id='right'/></jointforce>
  </sensors>
</robot>)");
  std::ofstream(dir / "robot.xml") << robot;
  {
    std::ofstream f(dir / "scene.xml");
    f << "<scene>\n";
    for (int r = 0; r < 4; ++r)
      f << "  <robot><ID name='r" << r << "'/><pos x='" << 1.5 * r
        << "' y='0' z='0'/><body file='robot.xml'/></robot>\n";
    f << controller(0) + controller(1) + controller(2) + controller(3) << "</scene>\n";
  }
  auto serial = load(dir, 1);
  auto parallel = load(dir, 2);
  ASSERT_EQ(parallel->components_serial_reason(), "");
  ASSERT_EQ(first_differing_tick(*serial, *parallel, 600), -1);
  // The sensors read something: gravity, the pose, the caster's push, the axle's load.
  EXPECT_NEAR(serial->signal("robots/r2/sensors/imu/acc_z"), 9.81, 1.0);
  EXPECT_NEAR(serial->signal("robots/r2/sensors/where/x"), 3.0, 0.5);
  EXPECT_GT(serial->signal("robots/r2/sensors/bump/force"), 0.1);
  EXPECT_NE(serial->signal("robots/r2/sensors/axle/fz"), 0.0);
}

TEST(ComponentParts, AResetRunInThePartsRepeatsTheFirstBitForBit) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  std::string plugins;
  for (int r = 0; r < 4; ++r)
    plugins += controller(r, "body='robots/r" + std::to_string(r) + "/solids/brick'");
  auto sim = load(write_scene("reset", plugins), 2);
  ASSERT_EQ(sim->components_serial_reason(), "");
  sim->step(400);
  const std::vector<double> first = signals(*sim);
  sim->reset();
  sim->step(400);
  const std::vector<double> again = signals(*sim);
  ASSERT_EQ(first.size(), again.size());
  EXPECT_EQ(std::memcmp(first.data(), again.data(), first.size() * sizeof(double)), 0);
}

TEST(ComponentParts, AComponentThatIsNotLocalKeepsThemAllOnTheCallingThread) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  auto sim = load(write_scene("not_local", controller(0) + controller(1, "local='0'")), 2);
  EXPECT_NE(sim->components_serial_reason().find("controllers/c1"), std::string::npos)
      << sim->components_serial_reason();
  EXPECT_NE(sim->components_serial_reason().find("not declared local"), std::string::npos);
}

TEST(ComponentParts, AReaderOfTheScenesContactSignalsKeepsThemAllOnTheCallingThread) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  auto sim = load(write_scene("contact_signal", controller(0, "reader='contacts/count'")), 2);
  EXPECT_NE(sim->components_serial_reason().find("scene's contacts"), std::string::npos)
      << sim->components_serial_reason();
}

TEST(ComponentParts, OneComponentOnTheAxesOfTwoPartsKeepsThemAllOnTheCallingThread) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  // Directly, by its own axes; and through an input it shares with the other part's.
  auto both = load(write_scene("two_parts",
                               "  <plugin kind='test_local_controller' id='both' "
                               "axes='robots/r1/axes/left robots/r2/axes/left'/>\n"),
                   2);
  EXPECT_NE(both->components_serial_reason().find("controllers/both"), std::string::npos)
      << both->components_serial_reason();
  EXPECT_NE(both->components_serial_reason().find("two parts"), std::string::npos);
  auto through_signal =
      load(write_scene("two_parts_signal", controller(0, "", "robots/r3/axes/left/encoder")), 2);
  const std::string& reason = through_signal->components_serial_reason();
  EXPECT_NE(reason.find("two parts"), std::string::npos) << reason;
  EXPECT_NE(reason.find("robots/r0/"), std::string::npos) << reason;
  EXPECT_NE(reason.find("robots/r3/axes/left/encoder"), std::string::npos) << reason;
}

/// The message of the error `act` raises in a local controller on r2, at `threads` threads.
std::string refusal(const std::string& act, int threads) {
  auto sim = load(write_scene("act_" + act, controller(2, "act='" + act +
                                                              "' body='robots/r2/solids/brick'"
                                                              " stray_axis='0'")),
                  threads);
  try {
    sim->run_until(0.2);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::runtime);
    return e.message();
  }
  ADD_FAILURE() << "'" << act << "' went through at " << threads << " threads";
  return {};
}

TEST(ComponentParts, ALocalComponentThatCastsARayMovesABodyOrLogsIsStoppedByName) {
  for (const char* act : {"ray", "move", "log"})
    for (int threads : {1, 2}) {
      if (threads == 2 && !two_threads_available()) continue;
      const std::string message = refusal(act, threads);
      EXPECT_NE(message.find("controllers/c2"), std::string::npos) << message;
      EXPECT_NE(message.find("declared itself local"), std::string::npos) << message;
    }
  EXPECT_NE(refusal("ray", 1).find("cast a ray"), std::string::npos);
}

TEST(ComponentParts, ADriveOnAnAxisOfAnotherPartIsStoppedByName) {
  if (!two_threads_available()) GTEST_SKIP() << "one hardware thread";
  // Axis 0 is r0's (part 0); the controller is r2's (part 1). Serially nothing can tell.
  const std::string message = refusal("stray_drive", 2);
  EXPECT_NE(message.find("controllers/c2"), std::string::npos) << message;
  EXPECT_NE(message.find("did not look up"), std::string::npos) << message;
}

}  // namespace
}  // namespace s2sim
