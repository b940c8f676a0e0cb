// Every error names the file (relative to the scene folder), the element path and the
// attribute; fixtures under tests/kernel/scene/fixtures/err_*.

#include "scene_test_util.hpp"

#include "common/edited_copy.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include "common/temp_dir.hpp"

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

TEST(SceneErrors, AThingsFileWithoutThingsNamesItsRoot) {
  const Error e = load_error(
      test::edited_copy(fixture("things_defines"), "scene.xml", "flat.xml", "no_things.xml"));
  EXPECT_EQ(e.where().file, "no_things.xml");
  EXPECT_EQ(e.where().element, "root");
  EXPECT_THAT(e.message(), HasSubstr("expected a <things> file, found <root>"));
  const Error f = load_error(
      test::edited_copy(fixture("things_defines"), "scene.xml", "flat.xml", "no_things_flat.xml"));
  EXPECT_EQ(f.where().file, "no_things_flat.xml");
  EXPECT_EQ(f.where().element, "defines");
  EXPECT_THAT(f.message(), HasSubstr("found <defines>"));
}

// SimTwo puts a shell or a sensor whose <solid id> names no solid on the main body.
TEST(SceneErrors, AnUnknownSolidOfASensorOrShellIsTheMainBodyWithAWarning) {
  const Scene s = load_scene(test::edited_copy(fixture("sensors"), "robot.xml", "<solid id='Arm'/>",
                                               "<solid id='Elbow'/>"));
  const Sensor& r = sensor(s, "r");
  EXPECT_EQ(r.body, s.robots.at(0).main_body);
  EXPECT_THAT(s.warnings, ::testing::Contains(::testing::AllOf(
                              HasSubstr("robot.xml: robot/sensors/ranger2d/solid@id"),
                              HasSubstr("'Elbow'"), HasSubstr("main body 'Base'"))));

  const Scene t =
      load_scene(test::edited_copy(fixture("shells"), "robot.xml", "<ID value='Light'/>",
                                   "<ID value='Light'/><solid id='Lid'/>"));
  EXPECT_THAT(t.warnings, ::testing::Contains(::testing::AllOf(
                              HasSubstr("robot.xml: robot/shells/cuboid"), HasSubstr("solid@id"),
                              HasSubstr("'Lid'"), HasSubstr("main body 'Body'"))));
  bool light_on_body = false;
  for (const Geom& g : body(t, 0, "Body").geoms)
    light_on_body = light_on_body || g.id == "Light";
  EXPECT_TRUE(light_on_body);
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

// Found by the hour-long libFuzzer run (docs/reliability.md): a joint from a solid to itself
// reached Simbody as a loop on one body, which aborts on an assertion.
TEST(SceneErrors, JointFromASolidToItselfIsRefused) {
  const Error e = load_error(test::edited_copy(fixture("err_joint_missing"), "bot.xml",
                                               "B1='A' B2='Nope'", "B1='A' B2='A'"));
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_EQ(e.where().file, "bot.xml");
  EXPECT_EQ(e.where().element, "robot/articulations/joint[2]/connect");
  EXPECT_EQ(e.where().attribute, "B2");
  EXPECT_THAT(e.message(), HasSubstr("joins solid 'A' to itself"));
}

TEST(SceneErrors, MotherSolidMustComeEarlier) {
  const Error e = load_error(fixture("err_mother"));
  EXPECT_EQ(e.where().file, "robot.xml");
  EXPECT_EQ(e.where().element, "robot/solids/cuboid[1]/solid");
  EXPECT_EQ(e.where().attribute, "id");
  EXPECT_THAT(e.message(), HasSubstr("'Later'"));
}

// ../shared/repro R17: a hinge whose limits hold no position was accepted.
TEST(SceneErrors, LimitsWithMinAboveMaxAreRefused) {
  const Error e = load_error(fixture("err_limits_inverted"));
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_EQ(e.where().file, "arm.xml");
  EXPECT_EQ(e.where().element, "robot/articulations/joint/limits");
  EXPECT_EQ(e.where().attribute, "Min");
  EXPECT_THAT(e.message(), HasSubstr("Min (45) is greater than Max (-45)"));
}

// ../shared/repro R16: two robots with one ID ended as a plugin error (exit 3) about a signal.
TEST(SceneErrors, DuplicateRobotIdIsASceneErrorAtTheSecondRobot) {
  const Error e = load_error(fixture("err_duplicate_robot"));
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_EQ(e.where().file, "scene.xml");
  EXPECT_EQ(e.where().element, "scene/robot[2]/ID");
  EXPECT_EQ(e.where().attribute, "name");
  EXPECT_THAT(e.message(), HasSubstr("duplicate robot ID 'bot'"));
  EXPECT_THAT(e.message(), HasSubstr("scene/robot[1]"));
}

// ../shared/repro R09: bounce 2 made a ball fall through the floor, exit 0; negative bounce and
// softness <= 0 were accepted.
TEST(SceneErrors, BounceOutsideZeroToOneAndNonPositiveSoftnessAreRefused) {
  const Error e = load_error(fixture("err_bounce"));
  EXPECT_EQ(e.where().file, "things.xml");
  EXPECT_EQ(e.where().element, "things/sphere/surface");
  EXPECT_EQ(e.where().attribute, "bounce");
  EXPECT_THAT(e.message(), HasSubstr("must be in [0, 1], got 2"));
  for (const char* bad : {"bounce='-0.5'", "bounce='1.5'"}) {
    const Error b =
        load_error(test::edited_copy(fixture("err_bounce"), "things.xml", "bounce='2'", bad));
    EXPECT_EQ(b.where().attribute, "bounce") << bad;
  }
  for (const char* bad : {"softness='0'", "softness='-1e-5'"}) {
    const Error s =
        load_error(test::edited_copy(fixture("err_bounce"), "things.xml", "bounce='2'", bad));
    EXPECT_EQ(s.where().attribute, "softness") << bad;
    EXPECT_THAT(s.message(), HasSubstr("must be > 0")) << bad;
  }
}

// ../shared/repro R05, R06, R04: counts and steps beyond the documented limits
// (kernel/src/scene/limits.hpp) hung the run, exhausted memory or were silently truncated.
TEST(SceneErrors, CountsAndStepsBeyondTheLimitsAreRefusedWithoutTruncation) {
  struct Case {
    const char* folder;
    const char* file;
    const char* from;
    const char* to;
    const char* attribute;
    const char* message;
  };
  const Case cases[] = {
      {"s2sim_settings", "scene.xml", "substeps='4'", "substeps='1e12'", "substeps",
       "must be an integer from 1 to 1000, got 1000000000000"},
      {"s2sim_settings", "scene.xml", "substeps='4'", "substeps='4294967297'", "substeps",
       "got 4294967297"},
      {"s2sim_settings", "scene.xml", "step_ms='dt'", "step_ms='1e-12'", "step_ms",
       "must be from 0.001 to 1000 ms, got 1e-12"},
      {"tracks", "track.xml", "times='1'", "times='2147483647'", "times",
       "must be an integer from 0 to 10000, got 2147483647"},
      {"tracks", "track.xml", "times='1'", "times='4294967296'", "times", "got 4294967296"},
      {"tracks", "track.xml", "step='30'", "step='1e-12'", "step",
       "more than the 100000 an arc may have"},
      // Counts read into an int were cast from 64 bits: 4294967297 became 1.
      {"sensors", "robot.xml", "rays='3'", "rays='4294967297'", "rays",
       "must be an integer from 1 to 100000, got 4294967297"},
      {"shells", "robot.xml", "width='640'", "width='4294967297'", "width",
       "must be an integer from 1 to 16384, got 4294967297"},
      {"shells", "robot.xml", "decimation='2'", "decimation='0'", "decimation",
       "must be an integer from 1 to 16384, got 0"},
  };
  for (const Case& c : cases) {
    const Error e = load_error(test::edited_copy(fixture(c.folder), c.file, c.from, c.to));
    EXPECT_EQ(e.kind(), ErrorKind::scene) << c.to;
    EXPECT_EQ(e.where().file, c.file) << c.to;
    EXPECT_EQ(e.where().attribute, c.attribute) << c.to;
    EXPECT_THAT(e.message(), HasSubstr(c.message)) << c.to;
  }
}

// ../shared/repro R03: a file name longer than the file system allows ended as an internal
// error (exit 1) from the file system library.
TEST(SceneErrors, UnreadableFileNameIsALocatedSceneError) {
  const std::string long_name(300, 'a');
  const Error e = load_error(test::edited_copy(
      fixture("err_duplicate_robot"), "scene.xml", "<robot><ID name='bot'/><body file='bot.xml'/>",
      "<robot><ID name='bot'/><body file='" + long_name + "'/>"));
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_EQ(e.where().element, "scene/robot[1]/body");
  EXPECT_EQ(e.where().attribute, "file");
  EXPECT_THAT(e.message(), HasSubstr("cannot read 'aaa"));
}

// ../shared/repro R19: a 1e16 m shell hung the narrow phase for minutes.
TEST(SceneErrors, SizesBeyondTenKilometresAreRefused) {
  const Error e = load_error(test::edited_copy(fixture("err_duplicate_robot"), "bot.xml",
                                               "size x='0.1'", "size x='1e16'"));
  EXPECT_EQ(e.where().file, "bot.xml");
  EXPECT_EQ(e.where().attribute, "x");
  EXPECT_THAT(e.message(), HasSubstr("must be at most 10000 m, got 1e+16"));
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
  const auto dir = s2sim::test::process_temp_dir() / ("s2sim_scene_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "scene.xml")
      << "<scene><robot><body file='bot.xml'/></robot>" << scene_extra << "</scene>";
  std::ofstream(dir / "bot.xml") << "<robot>" << robot_body << "</robot>";
  return dir;
}

const char* kTwoSolids =
    "<solids><cuboid><ID value='A'/></cuboid><cuboid><ID value='B'/></cuboid></solids>";

TEST(SceneErrors, ControlSemanticsIsSimTwoOrS2Sim) {
  const auto semantics = [](const std::string& name, const std::string& value) {
    return temp_scene(name, kTwoSolids, "<s2sim><control semantics='" + value + "'/></s2sim>");
  };
  EXPECT_EQ(load_scene(semantics("sem_simtwo", "simtwo")).settings.control_semantics,
            ControlSemantics::simtwo);
  EXPECT_EQ(load_scene(semantics("sem_s2sim", "s2sim")).settings.control_semantics,
            ControlSemantics::s2sim);
  const Error e = load_error(semantics("sem_bad", "ode"));
  EXPECT_EQ(e.where().element, "scene/s2sim/control");
  EXPECT_EQ(e.where().attribute, "semantics");
  EXPECT_THAT(e.message(), HasSubstr("'ode'"));
}

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
  // A drive-train boolean (`<motor active='yes'/>`) is the plugin's to read:
  // DriveTrain.BadParametersNameFileElementAttributeAndValue.
  Error e = load_error(
      temp_scene("bool", std::string(kTwoSolids) +
                             "<articulations><joint><type value='Hinge'/><connect B1='A' B2='B'/>"
                             "<axis x='1' y='0' z='0' wrap='yes'/></joint></articulations>"));
  EXPECT_EQ(e.where().element, "robot/articulations/joint/axis");
  EXPECT_EQ(e.where().attribute, "wrap");
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
  e = load_error(temp_scene("udp", kTwoSolids, "<s2sim><udp address='localhost'/></s2sim>"));
  EXPECT_EQ(e.where().element, "scene/s2sim/udp");
  EXPECT_EQ(e.where().attribute, "address");
  EXPECT_THAT(e.message(), HasSubstr("numeric IPv4 address, got 'localhost'"));
  e = load_error(temp_scene("udp_port", kTwoSolids, "<s2sim><udp port='70000'/></s2sim>"));
  EXPECT_EQ(e.where().attribute, "port");
  EXPECT_THAT(e.message(), HasSubstr("from 0 to 65535, got 70000"));
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

// An unknown controller mode is the drive-train plugin's error, located the same way:
// DriveTrain.BadParametersNameFileElementAttributeAndValue.

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
