// Robots from URDF, SDF and MJCF (docs/models/import.md): the same double pendulum in the
// three formats and in SimTwo's XML gives the same joint trajectories; located errors; a
// wheeled rover drives at r·ω; the effort limit bounds the torque input.

#include <s2sim/kernel/simulation.hpp>

#include "common/edited_copy.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kFixtures = fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/scene/fixtures/import";

SimulationOptions options() {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  return o;
}

/// The shoulder and elbow angles every 10 ms for `seconds`.
std::vector<std::pair<double, double>> pendulum_trajectory(const fs::path& file, double seconds) {
  auto sim = Simulation::load(file, options());
  const std::size_t shoulder = sim->signal_index("robots/double_pendulum/axes/shoulder/pos");
  const std::size_t elbow = sim->signal_index("robots/double_pendulum/axes/elbow/pos");
  std::vector<std::pair<double, double>> out;
  const auto ticks = static_cast<std::int64_t>(std::llround(seconds / sim->tick_s()));
  for (std::int64_t t = 0; t < ticks; t += 10) {
    sim->step(10);
    out.emplace_back(sim->signal(shoulder), sim->signal(elbow));
  }
  return out;
}

TEST(Import, TheDoublePendulumSwingsAlikeInUrdfSdfMjcfAndSimTwo) {
  const auto urdf = pendulum_trajectory(kFixtures / "double_pendulum.urdf", 5.0);
  ASSERT_EQ(urdf.size(), 500u);
  // It swings: released at 0.6 rad from the vertical, it passes the other side.
  double lowest = 0, highest_elbow = 0;
  for (const auto& [s, e] : urdf) {
    lowest = std::min(lowest, s);
    highest_elbow = std::max(highest_elbow, std::abs(e));
  }
  EXPECT_LT(lowest, -0.8) << "the shoulder never swung through";
  EXPECT_GT(highest_elbow, 0.1);
  for (const fs::path& other :
       {kFixtures / "double_pendulum.sdf", kFixtures / "double_pendulum_mjcf.xml",
        kFixtures / "pendulum_simtwo"}) {
    const auto traj = pendulum_trajectory(other, 5.0);
    ASSERT_EQ(traj.size(), urdf.size()) << other;
    double worst = 0;
    for (std::size_t k = 0; k < traj.size(); ++k)
      worst = std::max({worst, std::abs(traj[k].first - urdf[k].first),
                        std::abs(traj[k].second - urdf[k].second)});
    EXPECT_LT(worst, 1e-9) << other.filename() << ": largest difference " << worst << " rad";
    std::printf("%s: largest joint difference from the URDF over 5 s: %.3g rad\n",
                other.filename().c_str(), worst);
  }
}

/// The error `file` raises when loaded.
Error load_error(const fs::path& file) {
  try {
    Simulation::load(file, options());
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << file << " loaded";
  return Error(ErrorKind::runtime, Location{}, "none");
}

fs::path edited_pendulum(const std::string& from, const std::string& to) {
  return test::edited_copy(kFixtures, "double_pendulum.urdf", from, to) / "double_pendulum.urdf";
}

TEST(Import, AnUnknownJointTypeIsRefusedNamingTheJointAndTheType) {
  const Error e = load_error(edited_pendulum(R"(<joint name="elbow" type="continuous">)",
                                             R"(<joint name="elbow" type="hinge">)"));
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_EQ(e.where().file, "double_pendulum.urdf");
  EXPECT_EQ(e.where().element, "robot/joint[2]");
  EXPECT_EQ(e.where().attribute, "type");
  EXPECT_THAT(e.message(), HasSubstr("joint 'elbow': unknown joint type 'hinge'"));
}

TEST(Import, ANonPhysicalInertiaIsRefusedNamingTheLink) {
  const Error e = load_error(
      edited_pendulum(R"(<inertia ixx="0.021041666666666667")", R"(<inertia ixx="0.0001")"));
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_EQ(e.where().file, "double_pendulum.urdf");
  EXPECT_EQ(e.where().element, "robot/link[2]/inertial/inertia");
  EXPECT_THAT(e.message(), HasSubstr("link 'upper': non-physical inertial"));
  EXPECT_THAT(e.message(), HasSubstr("A + B >= C"));
  EXPECT_THAT(e.message(), HasSubstr("ixx 1e-04"));
}

TEST(Import, AMissingMeshIsRefusedNamingTheFile) {
  const Error e = load_error(edited_pendulum(
      R"(<collision><origin xyz="0 0 -0.2"/><geometry><box size="0.04 0.04 0.4"/>)",
      R"(<collision><origin xyz="0 0 -0.2"/><geometry><mesh filename="meshes/missing.stl"/>)"));
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_EQ(e.where().file, "double_pendulum.urdf");
  EXPECT_EQ(e.where().element, "robot/link[3]/collision/geometry/mesh");
  EXPECT_EQ(e.where().attribute, "filename");
  EXPECT_THAT(e.message(), HasSubstr("file 'meshes/missing.stl' not found"));
}

TEST(Import, AnUnresolvablePackageUriListsTheFoldersSearched) {
  const Error e = load_error(edited_pendulum(
      R"(<collision><origin xyz="0 0 -0.2"/><geometry><box size="0.04 0.04 0.4"/>)",
      R"(<collision><origin xyz="0 0 -0.2"/><geometry><mesh filename="package://nowhere_pkg/m.stl"/>)"));
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_EQ(e.where().element, "robot/link[3]/collision/geometry/mesh");
  EXPECT_EQ(e.where().attribute, "filename");
  EXPECT_THAT(e.message(), HasSubstr("cannot resolve 'package://nowhere_pkg/m.stl'"));
  EXPECT_THAT(e.message(), HasSubstr("searched:"));
}

TEST(Import, TheRunnerExitsWith2OnABadRobotFile) {
  const fs::path bad = edited_pendulum(R"(<joint name="elbow" type="continuous">)",
                                       R"(<joint name="elbow" type="hinge">)");
  const fs::path out = bad.parent_path() / "stderr.txt";
  const std::string command = std::string(S2SIM_BIN_DIR) + "/s2sim-run '" + bad.string() +
                              "' --duration 0.01 2> '" + out.string() + "' > /dev/null";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  std::ifstream in(out);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, HasSubstr("double_pendulum.urdf: robot/joint[2]@type"));
  EXPECT_THAT(text, HasSubstr("'hinge'"));
}

int body_of(const Simulation& sim, const std::string& id) {
  const auto& bodies = sim.scene().bodies;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (bodies[b].id == id) return static_cast<int>(b) + 1;
  ADD_FAILURE() << "no body " << id;
  return 0;
}

TEST(Import, TheRoverDrivesAtRadiusTimesWheelSpeed) {
  // Resting on its wheels (a free URDF robot run alone is lifted onto the floor), pushed by
  // 0.05 N·m per wheel for 0.5 s, then rolling on: the base moves at r·ω of every wheel.
  auto sim = Simulation::load(kFixtures / "rover_description/urdf/rover.urdf", options());
  const int base = body_of(*sim, "base_link");
  EXPECT_NEAR(sim->body_pose(base).position.z, 0.05, 1e-12) << "not lifted onto its wheels";
  const std::vector<std::string> wheels = {"fl", "fr", "rl", "rr"};
  auto axis = [](const std::string& w, const char* what) {
    return "robots/rover/axes/wheel_" + w + "_joint/" + what;
  };
  for (const std::string& w : wheels)
    sim->set_input(axis(w, "effort"), 0.05);
  sim->run_until(0.5);
  for (const std::string& w : wheels)
    sim->set_input(axis(w, "effort"), 0.0);
  sim->run_until(1.0);
  constexpr double r = 0.05;
  const double v = sim->body_twist(base).linear_m_s.x;
  EXPECT_GT(v, 0.5) << "the rover did not drive forward";
  for (const std::string& w : wheels) {
    const double rw = r * sim->signal(axis(w, "speed"));
    std::printf("rover at 1 s: v = %.6f m/s, wheel %s r*omega = %.6f m/s\n", v, w.c_str(), rw);
    EXPECT_NEAR(v, rw, 1e-3 * v) << w;
  }
  EXPECT_NEAR(sim->body_pose(base).position.z, 0.05, 2e-3) << "the rover sank or lifted";
  EXPECT_NEAR(sim->body_pose(base).position.y, 0.0, 1e-4) << "the rover turned";
}

TEST(Import, TheEffortLimitBoundsTheTorqueInput) {
  auto sim = Simulation::load(kFixtures / "rover_description/urdf/rover.urdf", options());
  sim->set_input("robots/rover/axes/wheel_fl_joint/effort", 7.0);
  sim->set_input("robots/rover/axes/wheel_fr_joint/effort", -7.0);
  sim->step(1);
  EXPECT_EQ(sim->signal("robots/rover/axes/wheel_fl_joint/effort_applied"), 0.5);
  EXPECT_EQ(sim->signal("robots/rover/axes/wheel_fr_joint/effort_applied"), -0.5);
  EXPECT_EQ(sim->signal("robots/rover/axes/wheel_rl_joint/effort_applied"), 0.0);
}

}  // namespace
}  // namespace s2sim
