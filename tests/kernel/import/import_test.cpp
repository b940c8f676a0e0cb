// Robots from URDF, SDF and MJCF (docs/models/import.md): the same double pendulum in the
// three formats and in SimTwo's XML gives the same joint trajectories; located errors; a
// wheeled rover drives at r·ω; the effort limit bounds the torque input.

#include <s2sim/kernel/simulation.hpp>

#include "common/edited_copy.hpp"
#include "common/recording_renderer.hpp"
#include "kernel/import/import_fixtures.hpp"

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
using ::testing::Not;

const fs::path kFixtures = test::kImportFixtures;

SimulationOptions options() {
  return test::import_options();
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

namespace s2sim {
namespace {

TEST(Import, ASimTwoScenePlacesImportedRobotsWithTheirIdAndPose) {
  auto sim = Simulation::load(kFixtures / "placed_scene", options());
  const scene::Scene& s = sim->scene();
  ASSERT_EQ(s.robots.size(), 2u);
  EXPECT_EQ(s.robots[0].id, "rover_a");
  EXPECT_EQ(s.robots[1].id, "pendulum");
  EXPECT_EQ(s.bodies[static_cast<std::size_t>(s.robots[0].main_body)].id, "base_link");
  EXPECT_EQ(s.bodies[static_cast<std::size_t>(s.robots[1].main_body)].id, "upper");
  const Pose& base = sim->body_pose(body_of(*sim, "base_link"));
  EXPECT_NEAR(base.position.x, 1, 1e-12);
  EXPECT_NEAR(base.position.y, 2, 1e-12);
  EXPECT_NEAR(base.position.z, 0.05, 1e-12);
  EXPECT_NEAR(yaw_of(base.rotation), kPi / 2, 1e-12);
  // The rover's front-left wheel (x = 0.1, y = 0.125 in the file) turned by 90°.
  const Pose& wheel = sim->body_pose(body_of(*sim, "wheel_fl"));
  EXPECT_NEAR(wheel.position.x, 1 - 0.125, 1e-12);
  EXPECT_NEAR(wheel.position.y, 2 + 0.1, 1e-12);
  // The MJCF pendulum's joint to the world moved with it, and it swings as it does alone.
  for (const scene::Joint& j : s.joints)
    if (j.id == "shoulder") {
      EXPECT_NEAR(j.anchor_m.x, 3, 1e-12);
    }
  auto alone = Simulation::load(kFixtures / "double_pendulum_mjcf.xml", options());
  const std::size_t placed = sim->signal_index("robots/pendulum/axes/elbow/pos");
  const std::size_t own = alone->signal_index("robots/double_pendulum/axes/elbow/pos");
  double worst = 0;
  for (int k = 0; k < 100; ++k) {
    sim->step(10);
    alone->step(10);
    worst = std::max(worst, std::abs(sim->signal(placed) - alone->signal(own)));
  }
  EXPECT_LT(worst, 1e-9) << worst;
  EXPECT_GT(std::abs(alone->signal(own)), 0.01);
}

}  // namespace
}  // namespace s2sim

namespace s2sim {
namespace {

TEST(Import, MeshWheelsCollideAsTheirHullsAndTheRoverDrivesAtRadiusTimesWheelSpeed) {
  // The rover on its STL wheels (32-sided prisms): a polygon of circumradius r rolling
  // without slip covers r·sin(π/32)/(π/32) = 0.99839 r per radian.
  auto sim = Simulation::load(kFixtures / "rover_description/urdf/rover_mesh.urdf", options());
  const scene::Scene& s = sim->scene();
  int hulls = 0;
  for (const scene::Body& b : s.bodies)
    for (const scene::Geom& g : b.geoms)
      if (g.shape.type == scene::ShapeType::convex) {
        ++hulls;
        EXPECT_EQ(g.shape.hull->vertices.size(), 64u);
        EXPECT_EQ(g.visual.mesh.file.filename(), "wheel.stl");
      }
  EXPECT_EQ(hulls, 4);
  // What the viewer draws: the URDF's visuals, the chassis blue, each wheel its STL mesh.
  const int base = body_of(*sim, "base_link");
  const scene::Body& chassis = s.bodies.at(static_cast<std::size_t>(base - 1));
  ASSERT_EQ(chassis.visuals.size(), 1u);
  EXPECT_EQ(chassis.visuals[0].shape.type, scene::ShapeType::box);
  EXPECT_FLOAT_EQ(static_cast<float>(chassis.visuals[0].visual.color.b), 0.8f);
  const scene::Body& wheel = s.bodies.at(static_cast<std::size_t>(body_of(*sim, "wheel_fl") - 1));
  ASSERT_EQ(wheel.visuals.size(), 1u);
  EXPECT_EQ(wheel.visuals[0].visual.mesh.file.filename(), "wheel.stl");
  EXPECT_NEAR(sim->body_pose(base).position.z, 0.05, 1e-9) << "not lifted onto its wheels";
  auto axis = [](const std::string& w, const char* what) {
    return "robots/rover_mesh/axes/wheel_" + w + "_joint/" + what;
  };
  const std::vector<std::string> wheels = {"fl", "fr", "rl", "rr"};
  for (const std::string& w : wheels)
    sim->set_input(axis(w, "effort"), 0.05);
  sim->run_until(0.5);
  for (const std::string& w : wheels)
    sim->set_input(axis(w, "effort"), 0.0);
  sim->run_until(1.0);
  // Over the last 0.5 s: distance against the wheel's turn (the polygon's speed ripples).
  const double x0 = sim->body_pose(base).position.x;
  const double q0 = sim->signal(axis("fl", "pos"));
  double turned = 0, last = q0, lowest = 1;
  for (int k = 0; k < 500; ++k) {
    sim->step(1);
    const double q = sim->signal(axis("fl", "pos"));
    double dq = q - last;
    if (dq > kPi) dq -= 2 * kPi;  // the hinge angle wraps at ±π
    if (dq < -kPi) dq += 2 * kPi;
    turned += dq;
    last = q;
    lowest = std::min(lowest, sim->body_pose(base).position.z);
  }
  const double moved = sim->body_pose(base).position.x - x0;
  constexpr double r = 0.05;
  const double rolling = r * std::sin(kPi / 32) / (kPi / 32);
  std::printf(
      "mesh rover: moved %.6f m while the wheel turned %.6f rad: %.6f m/rad (r = %.3f, "
      "polygon %.6f); lowest base %.6f m\n",
      moved, turned, moved / turned, r, rolling, lowest);
  EXPECT_GT(moved, 0.1);
  // Between the polygon's rolling distance per radian and the circle's: within 0.3% of r.
  EXPECT_NEAR(moved / turned, r, 3e-3 * r);
  EXPECT_GT(moved / turned, rolling - 1e-4);
  EXPECT_GT(lowest, 0.05 * std::cos(kPi / 32) - 2e-3) << "sank into the floor";
}

#ifdef S2SIM_TEST_HAVE_MUJOCO
/// The arm's six joints against MuJoCo loading the same URDF (its links never meet).
test::MujocoDifference arm_difference_from_mujoco(
    double step_s, double seconds,
    test::MujocoIntegration integration = test::MujocoIntegration::rk4_fine) {
  const fs::path file = kFixtures / "arm6/arm6.urdf";
  return test::difference_from_mujoco(file, file, {"j1", "j2", "j3", "j4", "j5", "j6"}, step_s,
                                      seconds, integration);
}
#endif

TEST(Import, TheMeshArmHangsAsMuJoCoLoadingTheSameUrdfSwingsIt) {
#ifndef S2SIM_TEST_HAVE_MUJOCO
  GTEST_SKIP() << "MuJoCo (libmujoco-dev) is not installed: the comparison with it is skipped";
#else
  // The same model: S2Sim's trajectory converges to MuJoCo's as the step shrinks, at the
  // first order of S2Sim's integrator (docs/models/import.md, "Validation").
  const test::MujocoDifference at_1ms = arm_difference_from_mujoco(1e-3, 0.2);
  const test::MujocoDifference at_250us = arm_difference_from_mujoco(2.5e-4, 0.2);
  std::printf(
      "arm6 over 0.2 s (MuJoCo swings up to %.3f rad): largest joint difference %.3g rad "
      "at 1 ms, %.3g rad at 0.25 ms\n",
      at_1ms.swing, at_1ms.largest_rad, at_250us.largest_rad);
  EXPECT_GT(at_1ms.swing, 0.3) << "the arm hardly moved";
  EXPECT_LT(at_1ms.largest_rad, 5e-4);
  EXPECT_LT(at_250us.largest_rad, 1e-4);
  EXPECT_GT(at_1ms.largest_rad / at_250us.largest_rad, 3.0)
      << "not converging to MuJoCo's trajectory";
  const test::MujocoDifference over_1s = arm_difference_from_mujoco(1e-3, 1.0);
  std::printf("arm6 over 1 s at 1 ms: largest joint difference %.3g rad (swing %.3f rad)\n",
              over_1s.largest_rad, over_1s.swing);
#endif
}

TEST(Import, TheMeshArmHangsAsMuJoCoIntegratingTheSameUrdfTheSameWayWithin1e4RadOver1s) {
#ifndef S2SIM_TEST_HAVE_MUJOCO
  GTEST_SKIP() << "MuJoCo (libmujoco-dev) is not installed: the comparison with it is skipped";
#else
  // With the integration law the same on both sides, what is left is the model: masses,
  // inertias, frames and axes as each simulator read them from the file, and each one's
  // equations of motion.
  const auto law = test::MujocoIntegration::s2sim_law;
  const test::MujocoDifference at_1ms = arm_difference_from_mujoco(1e-3, 1.0, law);
  const test::MujocoDifference at_4ms = arm_difference_from_mujoco(4e-3, 1.0, law);
  std::printf(
      "arm6 over 1 s, MuJoCo integrating as S2Sim (swings up to %.3f rad): largest joint "
      "difference %.3g rad at 1 ms, %.3g rad at 4 ms\n",
      at_1ms.swing, at_1ms.largest_rad, at_4ms.largest_rad);
  EXPECT_GT(at_1ms.swing, 1.0) << "the arm hardly moved";
  EXPECT_LT(at_1ms.largest_rad, 1e-4);
  EXPECT_LT(at_4ms.largest_rad, 1e-4);
#endif
}

}  // namespace
}  // namespace s2sim

namespace s2sim {
namespace {

TEST(Import, SdfAndMjcfErrorsNameTheFileTheLineAndTheValue) {
  const Error sdf = load_error(test::edited_copy(kFixtures, "double_pendulum.sdf",
                                                 R"(<joint name="elbow" type="continuous">)",
                                                 R"(<joint name="elbow" type="hinge">)") /
                               "double_pendulum.sdf");
  std::printf("SDF: %s\n", sdf.what());
  EXPECT_EQ(sdf.kind(), ErrorKind::scene);
  EXPECT_EQ(sdf.where().file, "double_pendulum.sdf");
  EXPECT_EQ(sdf.where().element, "sdf/model/joint[2]");
  EXPECT_EQ(sdf.where().attribute, "type");
  EXPECT_THAT(sdf.message(), HasSubstr("joint 'elbow': unknown joint type 'hinge'"));

  const Error mjcf = load_error(test::edited_copy(kFixtures, "double_pendulum_mjcf.xml",
                                                  R"(<joint name="elbow" type="hinge")",
                                                  R"(<joint name="elbow" type="hinje")") /
                                "double_pendulum_mjcf.xml");
  std::printf("MJCF: %s\n", mjcf.what());
  EXPECT_EQ(mjcf.kind(), ErrorKind::scene);
  EXPECT_EQ(mjcf.where().file, "double_pendulum_mjcf.xml");
  EXPECT_THAT(std::string(mjcf.what()), HasSubstr("hinje"));
  EXPECT_THAT(std::string(mjcf.what()), HasSubstr("line"));

  const Error inertia = load_error(
      test::edited_copy(
          kFixtures, "double_pendulum_mjcf.xml",
          R"(diaginertia="0.006733333333333333 0.006733333333333333 0.00013333333333333334")",
          R"(diaginertia="0.006733333333333333 0.0001 0.00013333333333333334")") /
      "double_pendulum_mjcf.xml");
  std::printf("MJCF inertia: %s\n", inertia.what());
  EXPECT_EQ(inertia.kind(), ErrorKind::scene);
  EXPECT_EQ(inertia.where().file, "double_pendulum_mjcf.xml");
  EXPECT_THAT(inertia.message(), HasSubstr("A + B >= C"));
  EXPECT_THAT(inertia.message(), HasSubstr("Object name = lower"));
}

}  // namespace
}  // namespace s2sim

namespace s2sim {
namespace {

TEST(Import, TheQuadrupedStandsOnItsMeshFeetUnderPositionControl) {
  // Hips and knees under the <s2sim> extension's DC motors and pidposition controllers,
  // holding their start angles; the feet are STL icosahedra colliding as their hulls.
  auto sim = Simulation::load(kFixtures / "quadruped/quadruped.urdf", options());
  int hulls = 0;
  for (const scene::Body& b : sim->scene().bodies)
    for (const scene::Geom& g : b.geoms)
      hulls += g.shape.type == scene::ShapeType::convex;
  EXPECT_EQ(hulls, 4);
  const std::size_t z = sim->signal_index("robots/quadruped/solids/body/z");
  const std::size_t pitch = sim->signal_index("robots/quadruped/solids/body/pitch");
  const double start = sim->signal(z);
  sim->run_until(3.0);
  const double sink = start - sim->signal(z);
  std::printf(
      "quadruped: body from %.6f m to %.6f m in 3 s: sank %.3f mm; pitch %.2g rad; "
      "%zu contacts\n",
      start, sim->signal(z), 1e3 * sink, sim->signal(pitch), sim->contact_count());
  EXPECT_GE(sink, 0.0);
  EXPECT_LT(sink, 2e-3);
  EXPECT_LT(std::abs(sim->signal(pitch)), 1e-3);
  EXPECT_GE(sim->contact_count(), 4u);
  EXPECT_LT(std::abs(sim->signal("robots/quadruped/axes/fl_knee/pos")), 2e-3);
}

}  // namespace
}  // namespace s2sim

namespace s2sim {
namespace {

TEST(Import, ARosStyleDescriptionLoadsWithItsPackageOnTheModelPathAndSaysWhatItIgnores) {
  // The meshes' package `probe_meshes` lies outside the folders above the URDF: it is found
  // through the model path (--model-path), then through ROS_PACKAGE_PATH.
  const fs::path share = kFixtures / "ros_style/share";
  const fs::path other = kFixtures / "ros_style/other";
  SimulationOptions o = options();
  o.model_path = {other};
  auto sim = Simulation::load(share / "probe_description/urdf/probe.urdf", o);
  const scene::Scene& s = sim->scene();
  ASSERT_EQ(s.robots.size(), 1u);
  // base_footprint, base_link and imu_link are one body (fixed joints merged), then the flaps.
  EXPECT_EQ(s.bodies.size(), 3u);
  EXPECT_EQ(s.bodies[0].id, "base_footprint");
  EXPECT_DOUBLE_EQ(s.bodies[0].mass_kg, 3.0);
  ASSERT_EQ(s.bodies[0].geoms.size(), 1u);
  EXPECT_EQ(s.bodies[0].geoms[0].shape.type, scene::ShapeType::convex);
  EXPECT_EQ(s.bodies[0].geoms[0].shape.hull->vertices.size(), 8u);
  EXPECT_EQ(s.bodies[0].geoms[0].visual.mesh.file.filename(), "chassis.obj");
  // The chassis rests on the floor: its box bottom at z = 0.
  EXPECT_NEAR(sim->body_pose(1).position.z, 0.0, 1e-9);  // assimp reads floats
  std::string warnings;
  for (const std::string& w : sim->warnings())
    warnings += w + "\n";
  EXPECT_THAT(warnings, Not(HasSubstr("mimic")));
  ASSERT_EQ(s.couplings.size(), 1u);  // flap2_joint follows flap_joint, multiplier 1
  EXPECT_EQ(s.joints[static_cast<std::size_t>(s.couplings[0].follower)].id, "flap2_joint");
  EXPECT_EQ(s.joints[static_cast<std::size_t>(s.couplings[0].leader)].id, "flap_joint");
  EXPECT_EQ(s.couplings[0].multiplier, 1.0);
  EXPECT_EQ(s.couplings[0].offset, 0.0);
  EXPECT_THAT(warnings, HasSubstr("<gazebo> extension elements are ignored"));
  EXPECT_THAT(warnings, HasSubstr("velocity limits are not applied"));
  EXPECT_THAT(warnings, HasSubstr("effort limits of joints without an actuator bound nothing "
                                  "(joint 'flap2_joint')"));
  // Only the transmission's joint gets the bounded input; damping and friction are applied.
  EXPECT_TRUE(sim->find_signal("robots/probe/axes/flap_joint/effort_applied").has_value());
  EXPECT_FALSE(sim->find_signal("robots/probe/axes/flap2_joint/effort_applied").has_value());
  for (const scene::Joint& j : s.joints)
    if (j.id == "flap_joint") {
      EXPECT_TRUE(j.limits1.active);
      EXPECT_DOUBLE_EQ(j.limits1.min, -0.5);
      ASSERT_NE(j.drive1.element.child("friction"), nullptr);
      EXPECT_EQ(*j.drive1.element.child("friction")->attribute("bv"), "0.01");
      EXPECT_EQ(*j.drive1.element.child("friction")->attribute("fc"), "0.001");
    }
  sim->run_until(0.5);
  EXPECT_TRUE(std::isfinite(sim->signal("robots/probe/axes/flap_joint/pos")));
  // Without the model path the package is not found, and the error lists what was searched.
  const Error e = load_error(share / "probe_description/urdf/probe.urdf");
  EXPECT_THAT(e.message(), HasSubstr("cannot resolve 'package://probe_meshes/meshes/chassis.obj'"));
  EXPECT_THAT(e.message(), HasSubstr((share / "probe_description/urdf").generic_string()));
  ::setenv("ROS_PACKAGE_PATH", ("/nonexistent:" + other.string()).c_str(), 1);
  EXPECT_NO_THROW(Simulation::load(share / "probe_description/urdf/probe.urdf", options()));
  ::unsetenv("ROS_PACKAGE_PATH");
}

}  // namespace
}  // namespace s2sim

namespace s2sim {
namespace {

TEST(Import, SdfAndMjcfFrictionReachesTheSurface) {
  const fs::path sdf =
      test::edited_copy(kFixtures, "double_pendulum.sdf",
                        "<geometry><box><size>0.04 0.04 0.4</size></box></geometry>",
                        "<geometry><box><size>0.04 0.04 0.4</size></box></geometry>"
                        "<surface><friction><ode><mu>0.3</mu><mu2>0.2</mu2></ode>"
                        "</friction></surface>") /
      "double_pendulum.sdf";
  auto a = Simulation::load(sdf, options());
  const scene::Geom& lower = a->scene().bodies.at(1).geoms.at(0);
  EXPECT_TRUE(lower.surface.explicit_surface);
  EXPECT_EQ(lower.surface.mu, 0.3);
  EXPECT_EQ(lower.surface.mu2, 0.2);
  EXPECT_FALSE(a->scene().bodies.at(0).geoms.at(0).surface.explicit_surface);  // none written
  auto b = Simulation::load(kFixtures / "double_pendulum_mjcf.xml", options());
  EXPECT_EQ(b->scene().bodies.at(0).geoms.at(0).surface.mu, 1.0);  // MuJoCo's default
}

}  // namespace
}  // namespace s2sim

namespace s2sim {
namespace {

TEST(Import, SdfSensorsBecomeS2SimSensorsAndMeasure) {
  auto sim = Simulation::load(kFixtures / "sensor_cart.sdf", options());
  const scene::Scene& s = sim->scene();
  ASSERT_EQ(s.sensors.size(), 4u);
  EXPECT_EQ(s.sensors[0].kind, "imu");
  EXPECT_DOUBLE_EQ(s.sensors[0].period_s, 0.01);
  const scene::Sensor& lidar = s.sensors[1];
  EXPECT_EQ(lidar.kind, "ranger2d");
  EXPECT_EQ(lidar.beam.rays, 5);
  EXPECT_NEAR(lidar.beam.angle_rad, 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(lidar.beam.length_m, 2.0);
  EXPECT_EQ(s.sensors[2].kind, "touch");
  // Gazebo's camera: 64 × 48 pixels across a horizontal field of 1 rad, its clip planes
  // sdformat's defaults (0.1 m, 100 m).
  EXPECT_EQ(s.sensors[3].kind, "camera");
  const Image& eye = sim->image("robots/sensor_cart/sensors/eye/rgb");
  EXPECT_EQ(eye.width_px, 64);
  EXPECT_EQ(eye.height_px, 48);
  std::vector<CameraShot> shots;
  test::record_shots(*sim, shots);
  std::string warnings;
  for (const std::string& w : sim->warnings())
    warnings += w + "\n";
  EXPECT_THAT(warnings, Not(HasSubstr("'eye' of type 'camera' is not imported")));
  EXPECT_THAT(warnings, HasSubstr("sensor 'down_lidar': its <noise> is not imported"));
  EXPECT_THAT(warnings, HasSubstr("the minimum range is not applied"));
  // Resting on the floor (its bottom at z = 0), the cart's lidar looks down from 0.5 m.
  sim->run_until(0.5);
  const double middle = sim->signal("robots/sensor_cart/sensors/down_lidar/ray/2");
  std::printf("lidar's middle ray: %.6f m\n", middle);
  EXPECT_NEAR(middle, 0.5, 2e-3);
  EXPECT_EQ(sim->signal("robots/sensor_cart/sensors/bumper/value"), 1.0);  // on the floor
  EXPECT_NEAR(sim->signal("robots/sensor_cart/sensors/bumper/force"), 9.81, 0.1);
  ASSERT_FALSE(shots.empty());
  EXPECT_NEAR(shots[0].vertical_fov_rad, 2 * std::atan(std::tan(0.5) * 48 / 64), 1e-9);
  EXPECT_NEAR(shots[0].near_m, 0.1, 1e-12);
  EXPECT_NEAR(shots[0].far_m, 100, 1e-12);
}

}  // namespace
}  // namespace s2sim

namespace s2sim {
namespace {

TEST(Import, MjcfCamerasRideTheirBodyLookingAlongTheirMinusZ) {
  // A camera on the upper bar looking along the body's -Z (MuJoCo's default orientation),
  // 45° high; one fixed to the world, which S2Sim does not import.
  const fs::path xml = test::edited_copy(kFixtures, "double_pendulum_mjcf.xml",
                                         "<joint name=\"shoulder\" type=\"hinge\" axis=\"0 1 0\"/>",
                                         "<joint name=\"shoulder\" type=\"hinge\" axis=\"0 1 0\"/>"
                                         "<camera name=\"tip\" pos=\"0 0 -0.5\" fovy=\"45\"/>") /
                       "double_pendulum_mjcf.xml";
  const fs::path with_world =
      test::edited_copy(xml.parent_path(), "double_pendulum_mjcf.xml", "<geom name=\"floor\"",
                        "<camera name=\"overhead\" pos=\"0 0 5\"/>"
                        "<geom name=\"floor\"") /
      "double_pendulum_mjcf.xml";
  auto sim = Simulation::load(with_world, options());
  std::vector<CameraShot> shots;
  test::record_shots(*sim, shots);
  const Pose upper = sim->body_pose(1);
  sim->step(1);
  ASSERT_EQ(shots.size(), 1u);
  const CameraShot& shot = shots[0];
  EXPECT_NEAR(shot.vertical_fov_rad, 45 * kPi / 180, 1e-12);
  // The shot looks along the shot frame's +Z: the body's -Z; its +Y (up) is the body's +Y.
  const Mat3 in_body = upper.rotation.transposed() * shot.pose.rotation;
  EXPECT_NEAR(in_body.m[2][2], -1, 1e-9);
  EXPECT_NEAR(in_body.m[1][1], 1, 1e-9);
  const Vec3 at = upper.rotation * Vec3{0, 0, -0.5} + upper.position;
  EXPECT_NEAR(shot.pose.position.x, at.x, 1e-9);
  EXPECT_NEAR(shot.pose.position.z, at.z, 1e-9);
  std::string warnings;
  for (const std::string& w : sim->warnings())
    warnings += w + "\n";
  EXPECT_THAT(warnings,
              HasSubstr("camera 'overhead': a camera fixed to the world is not imported"));
}

}  // namespace
}  // namespace s2sim
