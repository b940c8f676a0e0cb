// The drive-train element the kernel hands each axis: the joint's elements as written.
#include "sim/drive_train_components.hpp"
#include "scene/element_params.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace s2sim::sim {
namespace {

namespace fs = std::filesystem;

const scene::Scene& joints_scene() {
  static const scene::Scene s =
      scene::load_scene(fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/scene/fixtures/joints");
  return s;
}

int joint_index(const scene::Scene& s, const std::string& id) {
  for (std::size_t j = 0; j < s.joints.size(); ++j)
    if (s.joints[j].id == id) return static_cast<int>(j);
  ADD_FAILURE() << id;
  return -1;
}

scene::ElementParams params(const std::string& joint, int which, bool linear = false) {
  const scene::Scene& s = joints_scene();
  const std::string name = which == 0 ? joint : joint + ":2";
  return scene::ElementParams(drive_train_params(
      s, DriveAxis{name, "robots/arm/axes/" + name, 0, joint_index(s, joint), which, linear}));
}

TEST(DriveTrainComponents, UniversalAxesGetTheirOwnChildrenAndTheDefaults) {
  const scene::ElementParams a1 = params("Uni", 0), a2 = params("Uni", 1);
  EXPECT_EQ(a1.text("axis"), "robots/arm/axes/Uni");
  EXPECT_EQ(a2.text("axis"), "robots/arm/axes/Uni:2");
  EXPECT_EQ(a1.number("motor.ri"), 2.0);  // <default><motor ri='2'/>
  EXPECT_EQ(a2.number("motor.ri"), 5.0);  // the joint's <motor2 ri='5'/>
  EXPECT_EQ(a1.number("motor.vmax"), 6.0);
  EXPECT_EQ(a2.number("motor.vmax"), 6.0);  // *2 starts from the axis-1 defaults
  EXPECT_EQ(a2.number("controller.kp"), 7.0);
  EXPECT_EQ(a1.text("controller.mode"), "pidposition");
  EXPECT_EQ(a1.number("controller.period"), 20.0);  // ms, as written
  EXPECT_EQ(a1.number("encoder.ppr"), 700.8);       // as written: the plugin rounds
  EXPECT_FALSE(a1.boolean("wrap", true));           // <axis wrap='0'>
  EXPECT_FALSE(a2.boolean("wrap", true));           // limits2 ±30° engage
  EXPECT_FALSE(a1.has("motor.backemf"));            // the plugin's default
  EXPECT_FALSE(a2.has("controller.mode"));          // <controller2> without mode: reset
  EXPECT_EQ(a1.number("control_period"), 40.0);     // ms, the encoder's default period
  // Errors name the joint's file and the child as the user writes it.
  EXPECT_EQ(a2.location(), "robot.xml: robot/articulations/joint[3]");
  try {
    (void)a2.number("motor.ri", Range{0, 1});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.where().element, "robot/articulations/joint[3]/motor2");
    EXPECT_EQ(e.where().attribute, "ri");
  }
  // An inherited value is reported where it is written: the <default>.
  try {
    (void)a2.number("motor.vmax", Range{0, 1});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.where().element, "robot/articulations/default/motor");
    EXPECT_EQ(e.where().attribute, "vmax");
  }
}

TEST(DriveTrainComponents, ValuesAreAsWritten) {
  const scene::ElementParams slider = params("S", 0, true);
  EXPECT_EQ(slider.number("spring.zeropos"), 0.2);  // metres on a slider (the plugin knows)
  EXPECT_EQ(slider.number("spring.k"), 100.0);
  EXPECT_FALSE(slider.boolean("wrap", true));
  EXPECT_TRUE(slider.boolean("linear", false));
  EXPECT_FALSE(slider.has("friction.fc"));
  const scene::ElementParams hinge = params("H", 0);
  EXPECT_EQ(hinge.number("spring.zeropos"), 10.0);  // degrees, from the <default>
}

TEST(DriveTrainComponents, ThreeComponentsPerAxisInOrder) {
  const scene::Scene& s = joints_scene();
  const auto list = drive_train_components(
      s, {DriveAxis{"H", "robots/arm/axes/H", 0, joint_index(s, "H"), 0, false},
          DriveAxis{"Uni:2", "robots/arm/axes/Uni:2", 0, joint_index(s, "Uni"), 1, false}});
  ASSERT_EQ(list.size(), 6u);
  EXPECT_EQ(list[0].kind, "encoder");
  EXPECT_EQ(list[1].kind, "motor_controller");
  EXPECT_EQ(list[2].kind, "dc_motor");
  EXPECT_EQ(list[5].prefix, "robots/arm/axes/Uni:2/dc_motor");
  EXPECT_EQ(list[5].where.file, "robot.xml");
}

}  // namespace
}  // namespace s2sim::sim
