// Joints of several degrees of freedom from the formats as one-axis joints in series: MJCF's
// several joints in a body, URDF's planar joint, SDF's universal and revolute2
// (docs/models/import.md, "Joints").

#include <s2sim/kernel/simulation.hpp>

#include "common/edited_copy.hpp"
#include "kernel/import/import_fixtures.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kMulti = test::kImportFixtures / "multi_joint";

/// The largest difference of the named joints' positions, every 10 ms over `seconds` at 1 ms,
/// between two files loaded by S2Sim; `moved` gets the largest position of the first.
double largest_difference(const fs::path& a, const fs::path& b,
                          const std::vector<std::string>& joints, double seconds, double& moved,
                          const std::vector<test::JointEffort>& efforts = {}) {
  auto sa = Simulation::load(a, test::import_options());
  auto sb = Simulation::load(b, test::import_options());
  const auto ia = test::joint_signals(*sa, joints);
  const auto ib = test::joint_signals(*sb, joints);
  for (const test::JointEffort& e : efforts)
    for (Simulation* sim : {sa.get(), sb.get()})
      sim->set_input("robots/" + sim->scene().robots.at(0).id + "/axes/" + e.joint + "/effort",
                     e.value);
  double worst = 0;
  moved = 0;
  for (int k = 0; k < static_cast<int>(std::llround(seconds / 0.01)); ++k) {
    sa->step(10);
    sb->step(10);
    for (std::size_t j = 0; j < joints.size(); ++j) {
      worst = std::max(worst, std::abs(sa->signal(ia[j]) - sb->signal(ib[j])));
      moved = std::max(moved, std::abs(sa->signal(ia[j])));
    }
  }
  return worst;
}

TEST(ImportJoints, AnMjcfBodyWithSeveralJointsMovesAsMuJoCoMovesIt) {
  auto sim = Simulation::load(kMulti / "hip_knee.xml", test::import_options());
  // thigh.hip_x and thigh.hip_y between the world and the thigh, shin.knee before the shin.
  std::vector<std::string> bodies;
  for (const scene::Body& b : sim->scene().bodies)
    bodies.push_back(b.id + (b.mass_kg > 0 ? "" : " (massless)"));
  EXPECT_THAT(bodies, ::testing::ElementsAre("thigh", "shin", "thigh.hip_x (massless)",
                                             "thigh.hip_y (massless)", "shin.knee (massless)"));
  EXPECT_EQ(sim->scene().joints.size(), 5u);
#ifndef S2SIM_TEST_HAVE_MUJOCO
  GTEST_SKIP() << "MuJoCo (libmujoco-dev) is not installed: the comparison with it is skipped";
#else
  const fs::path file = kMulti / "hip_knee.xml";
  const std::vector<std::string> joints = {"hip_x", "hip_y", "hip_z", "knee", "shin_slide"};
  const auto d = test::difference_from_mujoco(file, file, joints, 1e-3, 1.0,
                                              test::MujocoIntegration::s2sim_law);
  std::printf(
      "hip_knee over 1 s, MuJoCo integrating as S2Sim: largest joint difference %.3g "
      "(MuJoCo's largest position %.3f)\n",
      d.largest_rad, d.swing);
  EXPECT_GT(d.swing, 0.3) << "hardly moved";
  EXPECT_LT(d.largest_rad, 1e-9);
#endif
}

TEST(ImportJoints, AUrdfPlanarJointSlidesInItsPlaneAndTurnsAboutItsNormalAsMjcfsThreeJoints) {
  // The plane is vertical (normal along y): the plate falls in it and never leaves it; a torque
  // on the pendulum's hinge turns the plate the other way.
  const std::vector<std::string> joints = {"slide_plane_x", "slide_plane_y", "slide_plane_rot",
                                           "swing"};
  const std::vector<test::JointEffort> torque = {{"swing", 0.2}};
  auto sim = Simulation::load(kMulti / "planar.urdf", test::import_options());
  const auto axes = test::joint_signals(*sim, joints);
  sim->set_input("robots/planar/axes/swing/effort", 0.2);
  const std::size_t y = sim->signal_index("robots/planar/solids/plate/y");
  const std::size_t z = sim->signal_index("robots/planar/solids/plate/z");
  const double z0 = sim->signal(z);
  sim->run_until(0.5);
  std::printf("planar: plate fell %.4f m, y %.3g m, turned %.4f rad; the bob swung %.4f rad\n",
              z0 - sim->signal(z), sim->signal(y), sim->signal(axes[2]), sim->signal(axes[3]));
  EXPECT_NEAR(sim->signal(y), 0.0, 1e-12);
  EXPECT_GT(z0 - sim->signal(z), 1.0);  // about g·t²/2, the plate's origin is off its centre
  EXPECT_LT(sim->signal(axes[2]), -0.01) << "the reaction of the bob's torque turns the plate";
  EXPECT_GT(sim->signal(axes[3]), 0.1);

  double moved = 0;
  const double worst = largest_difference(kMulti / "planar.urdf", kMulti / "planar_mjcf.xml",
                                          joints, 2.0, moved, torque);
  std::printf(
      "planar.urdf against planar_mjcf.xml over 2 s: largest difference %.3g (moved %.3f)\n", worst,
      moved);
  EXPECT_GT(moved, 1.0);
  EXPECT_LT(worst, 1e-9);
#ifdef S2SIM_TEST_HAVE_MUJOCO
  const auto d =
      test::difference_from_mujoco(kMulti / "planar.urdf", kMulti / "planar_mjcf.xml", joints, 1e-3,
                                   1.0, test::MujocoIntegration::s2sim_law, torque);
  std::printf("planar.urdf against MuJoCo's planar_mjcf.xml over 1 s: %.3g\n", d.largest_rad);
  EXPECT_LT(d.largest_rad, 1e-9);
#endif
}

TEST(ImportJoints, SdfUniversalAndRevolute2AreTwoHingesInSeriesAsInMjcf) {
  auto sim = Simulation::load(kMulti / "universal.sdf", test::import_options());
  EXPECT_EQ(sim->scene().joints.size(), 4u);
  double moved = 0;
  const std::vector<std::string> joints = {"hook", "hook_axis2", "wrist", "wrist_axis2"};
  const double worst = largest_difference(kMulti / "universal.sdf", kMulti / "universal_mjcf.xml",
                                          joints, 2.0, moved);
  std::printf(
      "universal.sdf against universal_mjcf.xml over 2 s: largest difference %.3g rad "
      "(swing %.3f rad)\n",
      worst, moved);
  EXPECT_GT(moved, 0.3);
  EXPECT_LT(worst, 1e-9);
#ifdef S2SIM_TEST_HAVE_MUJOCO
  const auto d =
      test::difference_from_mujoco(kMulti / "universal.sdf", kMulti / "universal_mjcf.xml", joints,
                                   1e-3, 1.0, test::MujocoIntegration::s2sim_law);
  std::printf("universal.sdf against MuJoCo's universal_mjcf.xml over 1 s: %.3g rad\n",
              d.largest_rad);
  EXPECT_LT(d.largest_rad, 1e-9);
#endif
}

TEST(ImportJoints, AMasslessLinkAtTheEndOfAChainIsStillRefused) {
  // The planar joint's links between its joints are massless and move the plate; a bob without
  // mass at the end would move nothing.
  const fs::path dir = test::edited_copy(kMulti, "planar.urdf",
                                         R"(<inertial><origin xyz="0 0 -0.25"/><mass value="0.5"/>
      <inertia ixx="0.003" ixy="0" ixz="0" iyy="0.003" iyz="0" izz="0.0005"/></inertial>)",
                                         "");
  try {
    Simulation::load(dir / "planar.urdf", test::import_options());
    ADD_FAILURE() << "loaded";
  } catch (const Error& e) {
    std::printf("%s\n", e.what());
    EXPECT_THAT(e.message(), HasSubstr("link 'bob' moves but has no mass"));
  }
}

}  // namespace
}  // namespace s2sim

namespace s2sim {
namespace {

TEST(ImportJoints, JointsInOneBodyThatRepeatAMotionAreALocatedError) {
  // The thigh's hip_y turned onto hip_x's axis: the two hinges would turn it the same way.
  const fs::path dir = test::edited_copy(test::kImportFixtures / "multi_joint", "hip_knee.xml",
                                         R"(axis="0 1 0.2")", R"(axis="2 0 0")");
  try {
    Simulation::load(dir / "hip_knee.xml", test::import_options());
    ADD_FAILURE() << "loaded";
  } catch (const Error& e) {
    std::printf("%s\n", e.what());
    EXPECT_EQ(e.where().file, "hip_knee.xml");
    EXPECT_EQ(e.where().element, "joint 'hip_y'");
    EXPECT_THAT(e.message(), ::testing::HasSubstr("its mass matrix would be singular"));
  }
}

}  // namespace
}  // namespace s2sim
