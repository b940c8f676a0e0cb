// Robot files and placements a fuzzer made: each a located error, never a crash
// (tests/fuzz/seeds/import are the seeds; docs/reliability.md, "Fuzzing").

#include <s2sim/kernel/simulation.hpp>

#include "common/edited_copy.hpp"
#include "common/temp_dir.hpp"
#include "kernel/import/import_fixtures.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <unistd.h>

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kSeeds = fs::path(S2SIM_SOURCE_DIR) / "tests/fuzz/seeds/import";

TEST(ImportHostile, AQuadrupedPlacedFarUnderTheFloorRisesWithoutBlowingUp) {
  // Its hull feet 2e9 m under the floor: the whole spring once sent the state to NaN, and the
  // contact of that state picked hull vertices it never set, and the run crashed. Its points
  // are born far deeper than any motion explains: the overlap relaxes, at the recovery speed
  // at most (docs/models/contact.md, "Overlap recovery").
  const fs::path dir =
      test::edited_copy(kSeeds / "urdf_quadruped", "scene.xml", "<pos x='0' y='0' z='0.281'/>",
                        "<pos x='0' y='0' z='-2147483648'/>");
  auto sim = Simulation::load(dir, test::import_options());
  sim->run_until(0.2);
  double fastest = 0;
  for (int b = 1; b < sim->body_count(); ++b) {
    const Vec3& p = sim->body_pose(b).position;
    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << "body " << b;
    fastest = std::max(fastest, norm(sim->body_twist(b).linear_m_s));
  }
  std::printf("quadruped 2e9 m under the floor: fastest body after 0.2 s %.4f m/s\n", fastest);
  EXPECT_LT(fastest, 0.5) << "thrown";
}

TEST(ImportHostile, AnSdfVersionThatIsNoNumberIsALocatedError) {
  for (const char* version : {"(1.9)*1e6", "99999999999999999999", "1..9", ""}) {
    const fs::path dir =
        test::edited_copy(kSeeds / "sdf_joints", "universal.xml", R"(<sdf version="1.9">)",
                          std::string(R"(<sdf version=")") + version + R"(">)");
    try {
      Simulation::load(dir, test::import_options());
      ADD_FAILURE() << "loaded version '" << version << "'";
    } catch (const Error& e) {
      std::printf("%s\n", e.what());
      EXPECT_EQ(e.kind(), ErrorKind::scene);
      EXPECT_EQ(e.where().file, "universal.xml");
      EXPECT_EQ(e.where().element, "sdf");
      EXPECT_EQ(e.where().attribute, "version");
    }
  }
}

TEST(ImportHostile, AJointThatMovesNoInertiaIsALocatedErrorNotANaNAtTheFirstStep) {
  // A spinner with a mass on its axis and no inertia, as xacro defaults leave a sensor's link.
  const fs::path dir =
      test::process_temp_dir() / ("s2sim_zero_inertia_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "spinner.urdf") << R"(<?xml version="1.0"?>
<robot name="spinner">
  <link name="base"><inertial><mass value="2"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="rotor"><inertial><mass value="0.1"/>
    <inertia ixx="0" iyy="0" izz="0" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="spin" type="continuous"><parent link="base"/><child link="rotor"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/></joint>
</robot>
)";
  try {
    Simulation::load(dir / "spinner.urdf", test::import_options());
    ADD_FAILURE() << "loaded";
  } catch (const Error& e) {
    std::printf("%s\n", e.what());
    EXPECT_EQ(e.kind(), ErrorKind::scene);
    EXPECT_EQ(e.where().file, "spinner.urdf");
    EXPECT_THAT(e.message(), HasSubstr("joint 'spin' moves link 'rotor'"));
    EXPECT_THAT(e.message(), HasSubstr("no inertia about its axis"));
  }
  fs::remove_all(dir);
}

TEST(ImportHostile, ACollisionUrdfdomCannotReadIsALocatedErrorNotADroppedGeom) {
  // urdfdom logs what it cannot read and still returns the model without that <collision>:
  // a link that would fall through the floor.
  const fs::path dir = test::process_temp_dir() / ("s2sim_dropped_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path stl =
      fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/scene/fixtures/import/arm6/link.stl";
  for (const std::string& geometry :
       {"<mesh filename='" + stl.string() + "' scale='0.5'/>", std::string()}) {
    std::ofstream(dir / "dropped.urdf") << R"(<?xml version="1.0"?>
<robot name="dropped">
  <link name="base"><inertial><mass value="2"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry>)" << geometry << R"(</geometry></collision></link>
</robot>
)";
    try {
      Simulation::load(dir / "dropped.urdf", test::import_options());
      ADD_FAILURE() << "loaded with " << geometry;
    } catch (const Error& e) {
      std::printf("%s\n", e.what());
      EXPECT_EQ(e.kind(), ErrorKind::scene);
      EXPECT_EQ(e.where().element, "robot/link");
      EXPECT_THAT(e.message(), HasSubstr("urdfdom could not read 1 of its <collision>"));
    }
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace s2sim
