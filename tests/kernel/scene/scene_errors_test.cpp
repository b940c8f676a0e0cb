// Every error names the file (relative to the scene folder), the element path and the
// attribute; fixtures under tests/kernel/scene/fixtures/err_*.

#include "scene_test_util.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <map>

namespace s2sim::scene {
namespace {

using ::testing::HasSubstr;
using namespace testing;

TEST(SceneErrors, NonPositiveMass) {
  const Error e = load_error(fixture("err_mass"));
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_EQ(e.where().file, "bot.xml");
  EXPECT_EQ(e.where().element, "robot/solids/cuboid[2]/mass");
  EXPECT_EQ(e.where().attribute, "value");
  EXPECT_THAT(e.message(), HasSubstr("must be > 0, got -2"));
  EXPECT_THAT(std::string(e.what()), HasSubstr("bot.xml: robot/solids/cuboid[2]/mass@value:"));
}

TEST(SceneErrors, ZeroSize) {
  const Error e = load_error(fixture("err_size"));
  EXPECT_EQ(e.where().file, "bot.xml");
  EXPECT_EQ(e.where().element, "robot/solids/cuboid/size");
  EXPECT_EQ(e.where().attribute, "y");
  EXPECT_THAT(e.message(), HasSubstr("got 0"));
}

TEST(SceneErrors, UnknownJointTypeNamesTheValue) {
  const Error e = load_error(fixture("err_joint_type"));
  EXPECT_EQ(e.where().file, "bot.xml");
  EXPECT_EQ(e.where().element, "robot/articulations/joint/type");
  EXPECT_EQ(e.where().attribute, "value");
  EXPECT_THAT(e.message(), HasSubstr("'Hinged'"));
}

TEST(SceneErrors, JointToAMissingSolid) {
  const Error e = load_error(fixture("err_joint_missing"));
  EXPECT_EQ(e.where().file, "bot.xml");
  EXPECT_EQ(e.where().element, "robot/articulations/joint[2]/connect");
  EXPECT_EQ(e.where().attribute, "B2");
  EXPECT_THAT(e.message(), HasSubstr("'Nope'"));
}

TEST(SceneErrors, MotherSolidMustComeEarlier) {
  const Error e = load_error(fixture("err_mother"));
  EXPECT_EQ(e.where().file, "robot.xml");
  EXPECT_EQ(e.where().element, "robot/solids/cuboid[1]/solid");
  EXPECT_EQ(e.where().attribute, "id");
  EXPECT_THAT(e.message(), HasSubstr("'Later'"));
}

TEST(SceneErrors, FailingExpressionWithColumn) {
  const Error e = load_error(fixture("err_expression"));
  EXPECT_EQ(e.where().file, "bot.xml");
  EXPECT_EQ(e.where().element, "robot/solids/cuboid/pos");
  EXPECT_EQ(e.where().attribute, "y");
  EXPECT_THAT(e.message(), HasSubstr("expression '1 + * 2': "));
  EXPECT_THAT(e.message(), HasSubstr("column 5"));
  EXPECT_THAT(std::string(e.what()), HasSubstr("bot.xml: robot/solids/cuboid/pos@y: expression"));
}

TEST(SceneErrors, MalformedXmlNamesTheLine) {
  const Error e = load_error(fixture("err_xml"));
  EXPECT_EQ(e.where().file, "scene.xml:5");
  EXPECT_THAT(std::string(e.what()), HasSubstr("scene.xml:5: expected"));
}

TEST(SceneErrors, BadIniStep) {
  const Error e = load_error(fixture("err_ini_step"));
  EXPECT_EQ(e.where().file, "SimTwo.ini");
  EXPECT_EQ(e.where().attribute, "EditOde_dt_Text");
  EXPECT_THAT(e.message(), HasSubstr("'fast'"));
}

TEST(SceneErrors, PluginWithoutKind) {
  const Error e = load_error(fixture("err_plugin_kind"));
  EXPECT_EQ(e.where().file, "scene.xml");
  EXPECT_EQ(e.where().element, "scene/plugin");
  EXPECT_EQ(e.where().attribute, "kind");
}

TEST(SceneErrors, MissingScene) {
  const Error e = load_error(fixture("no_such_folder"));
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_THAT(std::string(e.what()), HasSubstr("no_such_folder"));
}

// Smaller cases written to a temporary folder: scene.xml plus a robot file `bot.xml`.
std::filesystem::path temp_scene(const std::string& name, const std::string& robot_body,
                                 const std::string& scene_extra = "") {
  const auto dir = std::filesystem::path(::testing::TempDir()) / ("s2sim_scene_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "scene.xml")
      << "<scene><robot><body file='bot.xml'/></robot>" << scene_extra << "</scene>";
  std::ofstream(dir / "bot.xml") << "<robot>" << robot_body << "</robot>";
  return dir;
}

const char* kTwoSolids =
    "<solids><cuboid><ID value='A'/></cuboid><cuboid><ID value='B'/></cuboid></solids>";

TEST(SceneErrors, ZeroJointAxis) {
  const Error e = load_error(temp_scene(
      "zero_axis", std::string(kTwoSolids) +
                       "<articulations><joint><type value='Hinge'/><connect B1='A' B2='B'/>"
                       "<axis x='0' y='0' z='0'/></joint></articulations>"));
  EXPECT_EQ(e.where().element, "robot/articulations/joint/axis");
  EXPECT_THAT(e.message(), HasSubstr("zero"));
}

TEST(SceneErrors, JointBetweenWorldAndWorld) {
  const Error e = load_error(temp_scene(
      "both_world",
      std::string(kTwoSolids) +
          "<articulations><joint><type value='Hinge'/><connect B1='0' B2='world'/></joint>"
          "</articulations>"));
  EXPECT_EQ(e.where().element, "robot/articulations/joint/connect");
  EXPECT_THAT(e.message(), HasSubstr("world"));
}

TEST(SceneErrors, JointWithoutType) {
  const Error e = load_error(temp_scene(
      "no_type", std::string(kTwoSolids) +
                     "<articulations><joint><connect B1='A' B2='B'/></joint></articulations>"));
  EXPECT_EQ(e.where().element, "robot/articulations/joint");
  EXPECT_THAT(e.message(), HasSubstr("type"));
}

TEST(SceneErrors, WheelsNeedAMainBody) {
  const Error e = load_error(temp_scene("wheels_first", "<wheels><wheel/></wheels>"));
  EXPECT_EQ(e.where().element, "robot/wheels/wheel");
}

TEST(SceneErrors, NonPositiveTyreAndShellSizes) {
  Error e = load_error(temp_scene(
      "tyre", std::string(kTwoSolids) + "<wheels><wheel><tyre radius='-0.1'/></wheel></wheels>"));
  EXPECT_EQ(e.where().element, "robot/wheels/wheel/tyre");
  EXPECT_EQ(e.where().attribute, "radius");
  e = load_error(temp_scene(
      "shell",
      std::string(kTwoSolids) + "<shells><cylinder><size x='0' z='1'/></cylinder></shells>"));
  EXPECT_EQ(e.where().element, "robot/shells/cylinder/size");
  EXPECT_EQ(e.where().attribute, "x");
  e = load_error(
      temp_scene("sphere", "<solids><sphere><ID value='S'/><radius value='0'/></sphere></solids>"));
  EXPECT_EQ(e.where().element, "robot/solids/sphere/radius");
  EXPECT_EQ(e.where().attribute, "value");
}

TEST(SceneErrors, BadBooleanAndIntegers) {
  Error e = load_error(
      temp_scene("bool", std::string(kTwoSolids) +
                             "<articulations><joint><type value='Hinge'/><connect B1='A' B2='B'/>"
                             "<motor active='yes'/></joint></articulations>"));
  EXPECT_EQ(e.where().element, "robot/articulations/joint/motor");
  EXPECT_EQ(e.where().attribute, "active");
  EXPECT_THAT(e.message(), HasSubstr("'yes'"));
  e = load_error(
      temp_scene("color", "<solids><cuboid><ID value='A'/><color_rgb r='300'/></cuboid></solids>"));
  EXPECT_EQ(e.where().attribute, "r");
}

TEST(SceneErrors, S2SimSettingsAreValidated) {
  Error e =
      load_error(temp_scene("substeps", kTwoSolids, "<s2sim><physics substeps='0'/></s2sim>"));
  EXPECT_EQ(e.where().file, "scene.xml");
  EXPECT_EQ(e.where().element, "scene/s2sim/physics");
  EXPECT_EQ(e.where().attribute, "substeps");
  e = load_error(temp_scene("step", kTwoSolids, "<s2sim><physics step_ms='-1'/></s2sim>"));
  EXPECT_EQ(e.where().attribute, "step_ms");
  EXPECT_THAT(e.message(), HasSubstr("must be > 0, got -1"));
  e = load_error(temp_scene("frac", kTwoSolids, "<s2sim><physics substeps='2.5'/></s2sim>"));
  EXPECT_THAT(e.message(), HasSubstr("integer"));
}

TEST(SceneErrors, WrongRootOfAReferencedFile) {
  const auto dir = temp_scene("root", kTwoSolids, "<sensors file='bot.xml'/>");
  const Error e = load_error(dir);
  EXPECT_EQ(e.where().file, "bot.xml");
  EXPECT_THAT(e.message(), HasSubstr("<sensors>"));
}

TEST(SceneErrors, FailingDefine) {
  const Error e =
      load_error(temp_scene("define", "<defines><const name='a' value='b + 1'/></defines>"));
  EXPECT_EQ(e.where().file, "bot.xml");
  EXPECT_EQ(e.where().element, "robot/defines/const");
  EXPECT_EQ(e.where().attribute, "value");
}

TEST(SceneErrors, UnknownControllerModeIsAnError) {
  const Error e = load_error(
      temp_scene("mode", std::string(kTwoSolids) +
                             "<articulations><joint><type value='Hinge'/><connect B1='A' B2='B'/>"
                             "<controller mode='fuzzy'/></joint></articulations>"));
  EXPECT_EQ(e.where().file, "bot.xml");
  EXPECT_EQ(e.where().element, "robot/articulations/joint/controller");
  EXPECT_EQ(e.where().attribute, "mode");
  EXPECT_NE(std::string(e.what()).find("unknown controller mode 'fuzzy'"), std::string::npos);
}

TEST(SceneWarnings, RobotTilt) {
  const auto dir = temp_scene("warn", std::string(kTwoSolids) +
                                          "<articulations><joint><type value='Hinge'/>"
                                          "<connect B1='A' B2='B'/></joint></articulations>");
  std::ofstream(dir / "scene.xml")
      << "<scene><robot><rot_deg x='10' z='90'/><body file='bot.xml'/></robot></scene>";
  const Scene s = load_scene(dir);
  EXPECT_TRUE(has_warning(s, "rot_deg x and y are ignored"));
  EXPECT_NEAR(s.robots.at(0).yaw_rad, kPi / 2, 1e-15);
}

}  // namespace
}  // namespace s2sim::scene
