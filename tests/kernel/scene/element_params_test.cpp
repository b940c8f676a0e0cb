// ElementParams: the Params a component reads from its scene element.

#include "scene/element_params.hpp"
#include "scene/xml.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>

namespace s2sim::scene {
namespace {

using ::testing::HasSubstr;

ElementParams make(const std::string& xml) {
  auto constants = std::make_shared<ConstantTable>();
  constants->set("two", 2);
  Element root = parse_xml(xml, "robot.xml");
  // The component's element is the first child of <robot><sensors>.
  Element el = root.children.at(0).children.at(0);
  return ElementParams(ParamSource{el, "robot.xml", constants});
}

const char* kXml = R"(<robot><sensors>
  <ranger2d gain='two * 1.5' count='3' half='2.5' on='true' off='0' bad='yes' name='  abc  '
            neg='-2' broken='1 +'>
    <motor ri='0.5' vmax='12'>
      <limits max='two'/>
    </motor>
    <pos x='1' z='3'/>
    <motor ri='99'/>
  </ranger2d>
</sensors></robot>)";

Error error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no error";
  return Error(ErrorKind::runtime, "none");
}

TEST(ElementParams, TypedGettersAndExpressions) {
  const ElementParams p = make(kXml);
  EXPECT_DOUBLE_EQ(p.number("gain"), 3);
  EXPECT_DOUBLE_EQ(p.number("missing", 7.5), 7.5);
  EXPECT_DOUBLE_EQ(p.number("gain", 1.0), 3);
  EXPECT_EQ(p.integer("count"), 3);
  EXPECT_EQ(p.integer("missing", 42), 42);
  EXPECT_TRUE(p.boolean("on", false));
  EXPECT_FALSE(p.boolean("off", true));
  EXPECT_TRUE(p.boolean("missing", true));
  EXPECT_EQ(p.text("name"), "abc");
  EXPECT_EQ(p.text("missing", "dflt"), "dflt");
  EXPECT_TRUE(p.has("gain"));
  EXPECT_FALSE(p.has("missing"));
}

TEST(ElementParams, DottedPathsAndElements) {
  const ElementParams p = make(kXml);
  EXPECT_DOUBLE_EQ(p.number("motor.ri"), 0.5);  // the FIRST <motor>
  EXPECT_DOUBLE_EQ(p.number("motor.limits.max"), 2);
  EXPECT_TRUE(p.has("motor.vmax"));
  EXPECT_FALSE(p.has("motor.imax"));
  EXPECT_FALSE(p.has("rotor.j"));
  EXPECT_TRUE(p.has_element("motor"));
  EXPECT_TRUE(p.has_element("motor.limits"));
  EXPECT_FALSE(p.has_element("rotor"));
  EXPECT_DOUBLE_EQ(p.number("rotor.j", 0.25), 0.25);
  const Vec3 pos = p.vec3("pos", {9, 8, 7});
  EXPECT_DOUBLE_EQ(pos.x, 1);
  EXPECT_DOUBLE_EQ(pos.y, 8);
  EXPECT_DOUBLE_EQ(pos.z, 3);
  const Vec3 absent = p.vec3("nowhere", {1, 2, 3});
  EXPECT_DOUBLE_EQ(absent.z, 3);
  EXPECT_EQ(p.location(), "robot.xml: robot/sensors/ranger2d");
}

TEST(ElementParams, RangeErrorsAreLocated) {
  const ElementParams p = make(kXml);
  const Error e = error_of([&] { p.number("neg", Range::positive()); });
  EXPECT_EQ(e.where().file, "robot.xml");
  EXPECT_EQ(e.where().element, "robot/sensors/ranger2d");
  EXPECT_EQ(e.where().attribute, "neg");
  EXPECT_EQ(e.message(), "must be > 0, got -2");
  EXPECT_EQ(error_of([&] { p.number("neg", 1.0, Range::non_negative()); }).message(),
            "must be >= 0, got -2");
  EXPECT_EQ(error_of([&] {
              p.number("gain", Range{0, 1});
            }).message(),
            "must be >= 0 and <= 1, got 3");
  EXPECT_EQ(error_of([&] {
              p.number("motor.vmax", Range{0, 10, false, true});
            })
                .where()
                .element,
            "robot/sensors/ranger2d/motor[1]");
  EXPECT_DOUBLE_EQ(p.number("gain", Range{3, 3}), 3);  // inclusive bounds
}

TEST(ElementParams, OtherErrorsAreLocated) {
  const ElementParams p = make(kXml);
  Error e = error_of([&] { p.number("missing"); });
  EXPECT_EQ(e.where().attribute, "missing");
  EXPECT_THAT(e.message(), HasSubstr("missing"));
  e = error_of([&] { p.number("motor.imax"); });
  EXPECT_EQ(e.where().element, "robot/sensors/ranger2d/motor[1]");
  EXPECT_EQ(e.where().attribute, "imax");
  e = error_of([&] { p.number("rotor.j"); });
  EXPECT_EQ(e.where().element, "robot/sensors/ranger2d/rotor");
  e = error_of([&] { p.integer("half"); });
  EXPECT_THAT(e.message(), HasSubstr("integer"));
  EXPECT_THAT(e.message(), HasSubstr("2.5"));
  e = error_of([&] { p.boolean("bad", false); });
  EXPECT_THAT(e.message(), HasSubstr("'yes'"));
  e = error_of([&] { p.number("broken", 0.0); });
  EXPECT_EQ(e.where().attribute, "broken");
  EXPECT_THAT(e.message(), HasSubstr("expression '1 +'"));
  EXPECT_THAT(e.message(), HasSubstr("column"));
  EXPECT_THAT(std::string(e.what()), HasSubstr("robot.xml: robot/sensors/ranger2d@broken:"));
  e = error_of([&] { p.text("missing"); });
  EXPECT_EQ(e.where().attribute, "missing");
}

TEST(ElementParams, WorksWithoutConstants) {
  Element root = parse_xml("<plugin kind='k' gain='0.5 * 4'/>", "scene.xml");
  const ElementParams p(ParamSource{root, "scene.xml", nullptr});
  EXPECT_DOUBLE_EQ(p.number("gain"), 2);
  EXPECT_EQ(p.location(), "scene.xml: plugin");
}

TEST(ElementParams, ChoiceIsOneOfTheAllowedKeywords) {
  const ElementParams p = make(kXml);
  EXPECT_EQ(p.choice("name", {"def", "abc"}, "def"), "abc");  // trimmed
  EXPECT_EQ(p.choice("missing", {"a", "b"}, "b"), "b");
  EXPECT_EQ(p.choice("motor.missing", {"a", "b"}, "a"), "a");
  Error e = error_of([&] { (void)p.choice("name", {"x", "y", "z"}, "x"); });
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_EQ(e.where().element, "robot/sensors/ranger2d");
  EXPECT_EQ(e.where().attribute, "name");
  EXPECT_EQ(e.message(), "must be 'x', 'y' or 'z', got 'abc'");
  e = error_of([&] { (void)p.choice("bad", {"no"}, "no"); });
  EXPECT_EQ(e.message(), "must be 'no', got 'yes'");
}

}  // namespace
}  // namespace s2sim::scene
