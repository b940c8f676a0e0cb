// Scene loader features on small hand-written SimTwo folders (tests/kernel/scene/fixtures).

#include "scene/element_params.hpp"
#include "scene_test_util.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "common/temp_dir.hpp"

namespace s2sim::scene {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using namespace testing;

constexpr double kDeg = kPi / 180;

Mat3 Rx(double deg) {
  const double c = std::cos(deg * kDeg), s = std::sin(deg * kDeg);
  return Mat3{{{1, 0, 0}, {0, c, -s}, {0, s, c}}};
}
Mat3 Ry(double deg) {
  const double c = std::cos(deg * kDeg), s = std::sin(deg * kDeg);
  return Mat3{{{c, 0, s}, {0, 1, 0}, {-s, 0, c}}};
}
Mat3 Rz(double deg) {
  const double c = std::cos(deg * kDeg), s = std::sin(deg * kDeg);
  return Mat3{{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
}

// ---------------------------------------------------------------------------------------
// Scopes (§2.2)

TEST(SceneLoader, ScopesOfDefines) {
  const Scene s = load_scene(fixture("scopes"));
  ASSERT_EQ(s.robots.size(), 3u);
  EXPECT_EQ(s.robots[0].id, "first");
  EXPECT_EQ(s.robots[1].id, "second");  // <ID value> accepted for robots
  EXPECT_EQ(s.robots[2].id, "robot2");  // default robot<N>

  // Scene constants reach robot files; the scene robot's <const> beats the file's <arg>.
  const Body& a = body(s, 0, "A");
  EXPECT_DOUBLE_EQ(a.mass_kg, 2);
  EXPECT_TRUE(near_vec(a.geoms[0].shape.size_m, {0.5, 0.2, 0.3}, 1e-15));
  // The scene robot's define leaked to the next robot; robot_a's own `private` did not.
  const Body& b = body(s, 1, "B");
  EXPECT_DOUBLE_EQ(b.mass_kg, 7);
  EXPECT_DOUBLE_EQ(b.geoms[0].shape.size_m.x, 0.5);
  // Obstacle-file defines leak into G; the things element's defines go into G too.
  EXPECT_DOUBLE_EQ(s.obstacles.at(0).shape.size_m.x, 0.7);
  const Body& t = body(s, -1, "T");
  EXPECT_DOUBLE_EQ(t.mass_kg, 0.7);
  EXPECT_TRUE(near_vec(t.geoms[0].shape.size_m, {0.25, 0.25, 0.4}, 1e-15));
  const Body& c = body(s, 2, "C");
  EXPECT_DOUBLE_EQ(c.mass_kg, 2.7);  // <noconst> ignored
  EXPECT_DOUBLE_EQ(c.geoms[0].shape.radius_m, 0.25);

  EXPECT_EQ(s.globals.find("BASE_MASS"), 2);
  EXPECT_EQ(s.globals.find("box_len"), 0.5);
  EXPECT_EQ(s.globals.find("obst_size"), 0.7);
  EXPECT_EQ(s.globals.find("thing_size"), 0.25);
  EXPECT_FALSE(s.globals.find("private"));
  EXPECT_FALSE(s.globals.find("width"));
  EXPECT_FALSE(s.globals.find("thing_local"));
}

TEST(SceneLoader, ThingsFileWithDefinesBesideThings) {
  const Scene s = load_scene(fixture("things_defines"));
  // Under a root of another name: L = 0.3 from the file, H = 0.1 from the scene.
  const Body& wrapped = body(s, -1, "wrapped");
  EXPECT_TRUE(near_vec(wrapped.geoms[0].shape.size_m, {0.3, 0.15, 0.1}, 1e-15));
  // At the top of the file, beside <things>.
  const Body& flat = body(s, -1, "flat");
  EXPECT_TRUE(near_vec(flat.geoms[0].shape.size_m, {0.4, 0.1, 0.1}, 1e-15));
  // The file's constants stay in its copy of G.
  EXPECT_FALSE(s.globals.find("L"));
  EXPECT_FALSE(s.globals.find("W"));
  // Each departure from SimTwo (which reads only a root <things>) is a located warning.
  EXPECT_THAT(s.warnings, ElementsAre(HasSubstr("wrapped.xml: root/defines: <defines> beside"),
                                      HasSubstr("flat.xml: defines: <defines> beside"),
                                      HasSubstr("flat.xml: notes: <notes> beside <things> "
                                                "ignored")));
}

TEST(SceneLoader, LoadOptionsConstantsLeadTheSceneDefines) {
  LoadOptions options;
  options.constants = {{"width", 0.3}};
  const Scene s = load_scene(fixture("scopes") / "scene.xml", options);
  const Body& a = body(s, 0, "A");
  EXPECT_DOUBLE_EQ(a.geoms[0].shape.size_m.y, 0.3);  // pre-set beats the robot's <arg>
}

// An outside constant that would change nothing is refused: one that no <arg> declares (a
// misspelt name was silently ignored), and one that a <const> overwrites.
TEST(SceneLoader, AnOutsideConstantThatNoArgTakesIsAUsageErrorWithDidYouMean) {
  LoadOptions misspelt;
  misspelt.constants = {{"widht", 0.3}};
  try {
    (void)load_scene(fixture("scopes") / "scene.xml", misspelt);
    ADD_FAILURE() << "a misspelt constant loaded";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::usage);
    EXPECT_THAT(e.what(), HasSubstr("unknown constant (--define, defines=) 'widht'"));
    EXPECT_THAT(e.what(), HasSubstr("did you mean 'width'"));
  }
  LoadOptions overwritten;
  overwritten.constants = {{"base_mass", 5}};  // the scene's <const> overwrites it
  try {
    (void)load_scene(fixture("scopes") / "scene.xml", overwritten);
    ADD_FAILURE() << "a constant that a <const> overwrites loaded";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::usage);
    EXPECT_THAT(e.what(), HasSubstr("'base_mass' given from outside (--define, defines=) is a "
                                    "<const>"));
  }
}

// ---------------------------------------------------------------------------------------
// Rotations (§9.2)

TEST(SceneLoader, SolidRotationIsRzRyRx) {
  const Scene s = load_scene(fixture("rotations"));
  const Vec3 y{0, 1, 0}, z{0, 0, 1};
  EXPECT_TRUE(near_vec(body(s, 0, "Rx").pose.rotation * y, {0, 0, 1}));
  EXPECT_TRUE(near_vec(body(s, 0, "Ry").pose.rotation * z, {1, 0, 0}));
  EXPECT_TRUE(near_vec(body(s, 0, "Rz").pose.rotation * Vec3{1, 0, 0}, {0, 1, 0}));
  // x then z about fixed axes: z -> -y -> +x (the other order would give -y).
  EXPECT_TRUE(near_vec(body(s, 0, "Rxz").pose.rotation * z, {1, 0, 0}));
  EXPECT_TRUE(near_mat(body(s, 0, "R3").pose.rotation, Rz(60) * Ry(45) * Rx(30), 1e-12));
  EXPECT_TRUE(near_vec(body(s, 0, "R3").pose.position, {4, 0, 0}));
}

TEST(SceneLoader, SensorRotationIsRxRyRzWithTheBeamAlongX) {
  const Scene s = load_scene(fixture("rotations"));
  auto beam = [&](const std::string& id) { return sensor(s, id).pose.rotation.column(0); };
  EXPECT_TRUE(near_vec(beam("down"), {0, 0, -1}));
  EXPECT_TRUE(near_vec(beam("left"), {0, 1, 0}));
  EXPECT_TRUE(near_vec(beam("back_down"), {-0.5, 0, -std::sqrt(3.0) / 2}, 1e-12));
  // yaw first, then roll about X: +x -> +y -> +z (the solid order would give +y).
  EXPECT_TRUE(near_vec(beam("combo"), {0, 0, 1}));
  // SimTwo's ray matrix Rx·Ry·Rz·Ry(90°) applied to the ray's +Z is our beam.
  const Mat3 ode = Rx(30) * Ry(45) * Rz(60) * Ry(90);
  EXPECT_TRUE(near_vec(beam("R3"), ode * Vec3{0, 0, 1}, 1e-12));
  EXPECT_TRUE(near_mat(sensor(s, "R3").pose.rotation, Rx(30) * Ry(45) * Rz(60), 1e-12));
}

TEST(SceneLoader, MotherRelativeSolid) {
  const Scene s = load_scene(fixture("mother"));
  const Body& c = body(s, 0, "C");
  EXPECT_TRUE(near_vec(c.pose.position, {1, 1, 0.5}));
  EXPECT_TRUE(near_mat(c.pose.rotation, Rz(90) * Rx(90), 1e-12));
}

// ---------------------------------------------------------------------------------------
// Shells (§4.6), merged physically

Mat3 diag(double a, double b, double c) {
  return Mat3{{{a, 0, 0}, {0, b, 0}, {0, 0, c}}};
}
Mat3 plus(const Mat3& a, const Mat3& b) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r.m[i][j] = a.m[i][j] + b.m[i][j];
  return r;
}
Mat3 steiner(double m, Vec3 d) {  // m (|d|² E - d dᵀ)
  const double v[3] = {d.x, d.y, d.z};
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r.m[i][j] = m * ((i == j ? dot(d, d) : 0) - v[i] * v[j]);
  return r;
}

TEST(SceneLoader, MassiveShellsMergePhysically) {
  const Scene s = load_scene(fixture("shells"));
  const Body& b = body(s, 0, "Body");
  EXPECT_TRUE(near_vec(b.pose.position, {0, 0, 1}));  // the body frame does not move
  EXPECT_DOUBLE_EQ(b.mass_kg, 3.5);

  // Hand computation: box 2 kg 0.2×0.4×0.1 at the origin; sphere 1 kg r 0.05 at (0.3, 0, 0);
  // cylinder 0.5 kg r 0.05 L 0.2 at (0, 0.1, -0.1) with its axis turned onto -Y.
  const Vec3 com = (Vec3{0.3, 0, 0} * 1 + Vec3{0, 0.1, -0.1} * 0.5) / 3.5;
  EXPECT_TRUE(near_vec(b.com_m, com, 1e-15));
  const Mat3 box = diag(2 * (0.16 + 0.01) / 12, 2 * (0.04 + 0.01) / 12, 2 * (0.04 + 0.16) / 12);
  const Mat3 ball = diag(0.4 * 0.0025, 0.4 * 0.0025, 0.4 * 0.0025);
  const double side = 0.5 * (3 * 0.0025 + 0.04) / 12, axial = 0.5 * 0.0025 / 2;
  const Mat3 can = diag(side, axial, side);  // axis along Y after rot x = 90
  Mat3 expected =
      plus(plus(box, steiner(2, -com)), plus(plus(ball, steiner(1, Vec3{0.3, 0, 0} - com)),
                                             plus(can, steiner(0.5, Vec3{0, 0.1, -0.1} - com))));
  EXPECT_TRUE(near_mat(b.inertia_kg_m2, expected, 1e-15));
  EXPECT_NE(b.inertia_kg_m2.m[1][2], 0);  // the off-centre can gives products of inertia

  ASSERT_EQ(b.geoms.size(), 5u);
  EXPECT_EQ(b.geoms[1].id, "Ball");
  EXPECT_TRUE(b.geoms[1].is_shell);
  EXPECT_TRUE(near_vec(b.geoms[1].pose.position, {0.3, 0, 0}));
  const Geom& can_geom = b.geoms[2];
  EXPECT_EQ(can_geom.shape.type, ShapeType::cylinder);
  EXPECT_DOUBLE_EQ(can_geom.shape.radius_m, 0.05);  // size x; `radius` ignored
  EXPECT_DOUBLE_EQ(can_geom.shape.length_m, 0.2);
  EXPECT_TRUE(can_geom.surface.explicit_surface);
  EXPECT_DOUBLE_EQ(can_geom.surface.mu, 0.3);
  // A massless shell after massive ones stays where written (body frame unchanged).
  EXPECT_TRUE(near_vec(b.geoms[3].pose.position, {0, 0, 0.2}));
  EXPECT_DOUBLE_EQ(b.geoms[3].visual.color.a, 0);
  const Geom& cam = b.geoms[4];
  ASSERT_TRUE(cam.camera.has_value());
  EXPECT_DOUBLE_EQ(cam.camera->focal_length, 30);
  EXPECT_EQ(cam.camera->decimation, 2);
  EXPECT_EQ(cam.camera->width_px, 640);
  EXPECT_EQ(cam.camera->height_px, 480);
  EXPECT_TRUE(near_mat(cam.pose.rotation, Rz(90) * Rx(120), 1e-12));
  EXPECT_FALSE(b.geoms[1].camera.has_value());
}

// ---------------------------------------------------------------------------------------
// Wheels (§4.8)

TEST(SceneLoader, WheelsGenerator) {
  const Scene s = load_scene(fixture("wheels"));
  const Robot& r = s.robots.at(0);
  ASSERT_EQ(r.bodies.size(), 4u);
  ASSERT_EQ(r.joints.size(), 3u);
  const Body& right = body(s, 0, "Tyre -90");
  const Body& left = body(s, 0, "Tyre 90");
  const Body& caster = body(s, 0, "Tyre 180");
  EXPECT_TRUE(near_vec(right.pose.position, {0, -0.15, 0.05}));
  EXPECT_TRUE(near_vec(left.pose.position, {0.01, 0.17, 0.08}));  // offset added
  EXPECT_TRUE(near_vec(caster.pose.position, {-0.15, 0, 0.05}));
  // The cylinder axis (local Z) points radially outward.
  EXPECT_TRUE(near_vec(right.pose.rotation.column(2), {0, -1, 0}));
  EXPECT_TRUE(near_vec(left.pose.rotation.column(2), {0, 1, 0}));
  EXPECT_TRUE(near_vec(caster.pose.rotation.column(2), {-1, 0, 0}));
  for (const Body* t : {&right, &left, &caster}) {
    EXPECT_EQ(t->kind, SolidKind::tyre);
    EXPECT_DOUBLE_EQ(t->mass_kg, 0.5);
    EXPECT_DOUBLE_EQ(t->geoms[0].shape.radius_m, 0.05);
    EXPECT_DOUBLE_EQ(t->geoms[0].shape.length_m, 0.02);
    EXPECT_DOUBLE_EQ(t->drag.stokes, 0);
    EXPECT_DOUBLE_EQ(t->drag.roll, 0);
    EXPECT_TRUE(t->geoms[0].surface.explicit_surface);
    EXPECT_DOUBLE_EQ(t->geoms[0].surface.mu2, 0.001);
    EXPECT_DOUBLE_EQ(t->geoms[0].surface.softness, 0.001);
    EXPECT_DOUBLE_EQ(t->geoms[0].visual.color.r, 1);  // colour applied to the tyre
    EXPECT_DOUBLE_EQ(t->inertia_kg_m2.m[2][2], 0.5 * 0.05 * 0.05 / 2);
  }
  EXPECT_DOUBLE_EQ(right.geoms[0].surface.mu, 1);
  EXPECT_DOUBLE_EQ(caster.geoms[0].surface.mu, 0.7);
  EXPECT_EQ(caster.geoms[0].friction, FrictionKind::omni);
  EXPECT_EQ(right.geoms[0].friction, FrictionKind::isotropic);

  const Joint& w1 = joint(s, 0, "W1");
  const Joint& l = joint(s, 0, "Left");
  const Joint& w3 = joint(s, 0, "W3");
  EXPECT_EQ(w1.body1, body_index(s, 0, "Tyre -90"));
  EXPECT_EQ(w1.body2, r.main_body);
  EXPECT_TRUE(near_vec(w1.anchor_m, right.pose.position));
  EXPECT_TRUE(near_vec(l.anchor_m, {0.01, 0.17, 0.08}));
  EXPECT_TRUE(near_vec(w1.axis1, {0, 1, 0}));
  EXPECT_TRUE(near_vec(l.axis1, {0, -1, 0}));
  EXPECT_TRUE(near_vec(w3.axis1, {1, 0, 0}));
  EXPECT_FALSE(w1.limits1.active);
  // Drive train: the wheels' <default> elements as written, the wheel's own over them; what
  // is not written is left to the plugin's defaults.
  const ElementParams d1(w1.drive1), d3(w3.drive1);
  EXPECT_DOUBLE_EQ(d1.number("motor.ri"), 0.3);
  EXPECT_DOUBLE_EQ(d1.number("motor.vmax"), 12);
  EXPECT_FALSE(d1.has("motor.ki"));
  EXPECT_DOUBLE_EQ(d1.number("gear.ratio"), 12);
  EXPECT_DOUBLE_EQ(d1.number("controller.kp"), 0.2);
  EXPECT_FALSE(d1.has("controller.kf"));
  EXPECT_FALSE(d1.has("controller.period"));
  EXPECT_TRUE(d1.boolean("controller.active", false));
  EXPECT_TRUE(d1.boolean("motor.active", true));
  EXPECT_FALSE(d3.boolean("motor.active", true));
  EXPECT_TRUE(w1.from_wheels);
}

// ---------------------------------------------------------------------------------------
// Articulations (§4.9, §4.10)

TEST(SceneLoader, JointTypesConnectionsAndLimits) {
  const Scene s = load_scene(fixture("joints"));
  const Robot& r = s.robots.at(0);
  ASSERT_EQ(r.joints.size(), 6u);

  const Joint& h = joint(s, 0, "H");
  EXPECT_EQ(h.type, JointType::hinge);
  EXPECT_EQ(h.body1, r.bodies[2]);  // the LAST solid named Arm
  EXPECT_EQ(h.body2, r.main_body);
  EXPECT_TRUE(near_vec(h.anchor_m, {1, 0, 0.25}));
  EXPECT_TRUE(near_vec(h.axis1, {0, 1, 0}));  // normalised
  EXPECT_TRUE(h.limits1.active);
  EXPECT_DOUBLE_EQ(h.limits1.min, -90 * kDeg);
  EXPECT_DOUBLE_EQ(h.limits1.max, 45 * kDeg);
  EXPECT_EQ(h.description, "elbow");
  EXPECT_FALSE(h.from_wheels);

  const Joint& sl = joint(s, 0, "S");
  EXPECT_EQ(sl.type, JointType::slider);
  EXPECT_EQ(sl.body1, body_index(s, 0, "Slide"));  // B1 was the world: swapped
  EXPECT_EQ(sl.body2, -1);
  EXPECT_TRUE(sl.limits1.active);
  EXPECT_DOUBLE_EQ(sl.limits1.min, -0.5);  // metres
  EXPECT_DOUBLE_EQ(sl.limits1.max, 0.5);
  EXPECT_DOUBLE_EQ(ElementParams(sl.drive1).number("spring.k"), 100);
  EXPECT_DOUBLE_EQ(ElementParams(sl.drive1).number("spring.zeropos"), 0.2);  // as written

  const Joint& u = joint(s, 0, "Uni");
  EXPECT_EQ(u.type, JointType::universal);
  EXPECT_EQ(u.body1, body_index(s, 0, "U"));  // S1/S2 accepted
  EXPECT_TRUE(near_vec(u.axis1, {1, 0, 0}));
  EXPECT_TRUE(near_vec(u.axis2, {0, 1, 0}));
  EXPECT_FALSE(u.wrap1);
  EXPECT_TRUE(u.wrap2);
  EXPECT_FALSE(u.limits1.active);  // ±360° never engages
  EXPECT_TRUE(u.limits2.active);
  EXPECT_DOUBLE_EQ(u.limits2.min, -30 * kDeg);
  EXPECT_DOUBLE_EQ(u.limits2.max, 30 * kDeg);
  const ElementParams u1(u.drive1), u2(u.drive2);
  EXPECT_DOUBLE_EQ(u1.number("encoder.ppr"), 700.8);  // as written (the plugin rounds)
  // Axis 2: the <default> axis-1 values (not <default>'s motor2), then the joint's *2.
  EXPECT_DOUBLE_EQ(u2.number("motor.ri"), 5);
  EXPECT_DOUBLE_EQ(u2.number("motor.vmax"), 6);
  EXPECT_DOUBLE_EQ(u2.number("controller.kp"), 7);
  EXPECT_FALSE(u2.has("controller.mode"));  // no mode: reset (quirk 7b), pidspeed
  EXPECT_FALSE(u2.has("encoder.ppr"));
  EXPECT_DOUBLE_EQ(u1.number("motor.ri"), 2);

  const Joint& ball = joint(s, 0, "B");
  EXPECT_EQ(ball.type, JointType::ball);
  EXPECT_EQ(ball.body1, body_index(s, 0, "Ball"));
  EXPECT_EQ(ball.body2, -1);  // B2='0'
  EXPECT_TRUE(near_vec(ball.anchor_m, {4, 0, 0}));

  const Joint& fixed = s.joints[static_cast<std::size_t>(r.joints[4])];
  EXPECT_EQ(fixed.type, JointType::fixed);
  EXPECT_EQ(fixed.id, "joint5");  // no <ID>: a generated one
  EXPECT_EQ(fixed.body1, body_index(s, 0, "Glued"));

  const Joint& rel = joint(s, 0, "R");
  EXPECT_TRUE(near_vec(rel.anchor_m, {0, 3, 0}));  // (0,2,0) + Rz(90)·(1,0,0)
  EXPECT_TRUE(near_vec(rel.axis1, {0, 1, 0}));
  EXPECT_TRUE(rel.limits1.active);  // one side inside (-180°, 180°)
  EXPECT_EQ(rel.limits1.min, -std::numeric_limits<double>::infinity());
  EXPECT_DOUBLE_EQ(rel.limits1.max, 170 * kDeg);
  EXPECT_FALSE(ElementParams(rel.drive1).has("controller.mode"));  // quirk 7b: pidspeed
  EXPECT_DOUBLE_EQ(ElementParams(rel.drive1).number("controller.kp"), 2);
}

TEST(SceneLoader, JointDefaultCapture) {
  const Scene s = load_scene(fixture("joints"));
  const Joint& h = joint(s, 0, "H");
  const ElementParams d(h.drive1);
  EXPECT_DOUBLE_EQ(d.number("motor.ri"), 2);
  EXPECT_DOUBLE_EQ(d.number("motor.vmax"), 6);
  EXPECT_FALSE(d.has("motor.ki"));  // the plugin's default
  EXPECT_FALSE(d.has("gear.ratio"));
  EXPECT_EQ(d.text("controller.mode"), "pidposition");
  EXPECT_DOUBLE_EQ(d.number("controller.kp"), 5);
  EXPECT_FALSE(d.has("controller.kf"));
  EXPECT_DOUBLE_EQ(d.number("controller.period"), 20);  // ms, as written
  EXPECT_FALSE(d.has("controller.active"));
  EXPECT_FALSE(d.has_element("friction"));
  EXPECT_DOUBLE_EQ(d.number("spring.k"), 3);
  EXPECT_DOUBLE_EQ(d.number("spring.zeropos"), 10);  // degrees, as written
  // An inherited attribute is located where it is written: in the <default>.
  EXPECT_EQ(d.where("spring.k").element, "robot/articulations/default/spring");
  EXPECT_DOUBLE_EQ(h.draw.radius_m, 0.01);
  EXPECT_DOUBLE_EQ(h.draw.color.r, 1);  // rgb24 0000FF is red (BGR)
  EXPECT_DOUBLE_EQ(h.draw.color.b, 0);
  EXPECT_DOUBLE_EQ(ElementParams(h.drive2).number("motor.ri"),
                   2);  // <default><motor2> not captured
}

// ---------------------------------------------------------------------------------------
// Robot placement (§9.3)

TEST(SceneLoader, RobotPlacementWithYaw) {
  const Scene s = load_scene(fixture("placement"));
  ASSERT_EQ(s.robots.size(), 2u);
  EXPECT_EQ(s.robots[1].id, "robot1");
  const Body& main = body(s, 0, "Main");
  const Body& second = body(s, 0, "Second");
  // P0 = (1, 0, 0.5), t = (1, 2, 0), yaw 90° about the vertical through P0 (x, y ignored).
  EXPECT_TRUE(near_vec(main.pose.position, {2, 2, 0.5}));
  EXPECT_TRUE(near_vec(second.pose.position, {2, 3, 0.5}));
  EXPECT_TRUE(near_mat(main.pose.rotation, Rz(90), 1e-12));
  EXPECT_TRUE(near_mat(second.pose.rotation, Rz(90), 1e-12));
  const Joint& hinge = joint(s, 0, "hinge");
  EXPECT_TRUE(near_vec(hinge.anchor_m, {2, 2.5, 0.5}));
  EXPECT_TRUE(near_vec(hinge.axis1, {0, 1, 0}));
  // A joint to the world follows the same transform (quirk 18 fixed).
  const Joint& rail = joint(s, 0, "rail");
  EXPECT_EQ(rail.body2, -1);
  EXPECT_TRUE(near_vec(rail.anchor_m, {2, 3, 0}));
  EXPECT_TRUE(near_vec(rail.axis1, {-1, 0, 0}));
  // Sensors stay in their body frame.
  EXPECT_TRUE(near_vec(sensor(s, "ir").pose.position, {0.1, 0, 0}));
  EXPECT_EQ(sensor(s, "ir").body, body_index(s, 0, "Second"));

  // The unplaced copy keeps the file coordinates.
  EXPECT_TRUE(near_vec(body(s, 1, "Main").pose.position, {1, 0, 0.5}));
  EXPECT_TRUE(near_vec(joint(s, 1, "rail").axis1, {0, 1, 0}));
}

// ---------------------------------------------------------------------------------------
// Obstacles (§5)

TEST(SceneLoader, ObstacleOffsetsPrefixesAndRadii) {
  const Scene s = load_scene(fixture("obstacle_offset"));
  ASSERT_EQ(s.obstacles.size(), 6u);
  const Geom& box = s.obstacles[0];
  EXPECT_EQ(box.id, "W.box");
  EXPECT_TRUE(near_vec(box.pose.position, {1, 3, 0}));  // R_off·pos + p_off
  EXPECT_TRUE(near_mat(box.pose.rotation, Rz(180), 1e-12));
  EXPECT_TRUE(near_vec(box.shape.size_m, {1, 0.5, 0.2}));
  EXPECT_DOUBLE_EQ(box.visual.color.g, 1);
  EXPECT_TRUE(box.surface.explicit_surface);
  const Geom& cyl = s.obstacles[1];
  EXPECT_EQ(cyl.id, "W.Obstacle at (0, 1, 0)");
  EXPECT_DOUBLE_EQ(cyl.shape.radius_m, 0.3);  // max(<radius value>, size x)
  EXPECT_DOUBLE_EQ(cyl.shape.length_m, 0.4);
  EXPECT_TRUE(near_vec(cyl.pose.position, {0, 2, 0}));
  EXPECT_EQ(s.obstacles[2].id, "W.ball");
  EXPECT_DOUBLE_EQ(s.obstacles[2].shape.radius_m, 0.25);

  // Offset rot x = 90 with a local rot z = 90: R_off·R_local (quirk 17 fixed).
  const Geom& box2 = s.obstacles[3];
  EXPECT_EQ(box2.id, "box");
  EXPECT_TRUE(near_vec(box2.pose.position, {1, 0, 0}));
  EXPECT_TRUE(near_mat(box2.pose.rotation, Rx(90) * Rz(90), 1e-12));
  EXPECT_TRUE(near_vec(s.obstacles[4].pose.position, {0, 0, 1}));
}

// ---------------------------------------------------------------------------------------
// Tracks (§7)

void expect_vertices(const TrackPolygon& t, std::vector<std::pair<double, double>> expected) {
  ASSERT_EQ(t.vertices.size(), expected.size()) << t.tag;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(t.vertices[i].first, expected[i].first, 1e-12) << t.tag << " vertex " << i;
    EXPECT_NEAR(t.vertices[i].second, expected[i].second, 1e-12) << t.tag << " vertex " << i;
  }
}

TEST(SceneLoader, TrackLinesWithRepeatAndClones) {
  const Scene s = load_scene(fixture("tracks"));
  ASSERT_EQ(s.tracks.size(), 13u);
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(s.tracks[static_cast<std::size_t>(i)].tag, "black");
    EXPECT_DOUBLE_EQ(s.tracks[static_cast<std::size_t>(i)].z_m, 0.001);
  }
  const Color red = s.tracks[0].color;  // rgb24 0000FF is red
  EXPECT_DOUBLE_EQ(red.r, 1);
  EXPECT_DOUBLE_EQ(red.g, 0);
  EXPECT_DOUBLE_EQ(red.b, 0);
  EXPECT_DOUBLE_EQ(red.a, 0.5);
  // Repetition 0: the line, then hflip, vflip, hvflip; width 0.1 to the left.
  expect_vertices(s.tracks[0], {{1, 2}, {2, 2}, {2, 2.1}, {1, 2.1}});
  expect_vertices(s.tracks[1], {{1, -2}, {2, -2}, {2, -1.9}, {1, -1.9}});
  expect_vertices(s.tracks[2], {{-1, 2.1}, {-2, 2.1}, {-2, 2}, {-1, 2}});
  expect_vertices(s.tracks[3], {{-1, -2}, {-2, -2}, {-2, -2.1}, {-1, -2.1}});
  // Repetition 1: start shifted by (0, 0.5), angle by 90°.
  expect_vertices(s.tracks[4], {{1, 2.5}, {1, 3.5}, {0.9, 3.5}, {0.9, 2.5}});
  expect_vertices(s.tracks[7], {{-1, -2.5}, {-1, -3.5}, {-0.9, -3.5}, {-0.9, -2.5}});
}

TEST(SceneLoader, TrackArcsAndPolygons) {
  const Scene s = load_scene(fixture("tracks"));
  ASSERT_EQ(s.tracks.size(), 13u);
  const double c30 = std::sqrt(3.0) / 2;
  const TrackPolygon& ring = s.tracks[8];
  EXPECT_EQ(ring.tag, "white");
  EXPECT_DOUBLE_EQ(ring.z_m, 0.01);
  EXPECT_NEAR(ring.color.r, 0x80 / 255.0, 1e-12);  // default 808080
  expect_vertices(ring, {{0.5, 0},
                         {0.5 * c30, 0.25},
                         {0.25, 0.5 * c30},
                         {0, 0.5},
                         {0, 0.4},
                         {0.2, 0.4 * c30},
                         {0.4 * c30, 0.2},
                         {0.4, 0}});
  // `steps` accepted; 0..100 every 45° with the last point clamped; inner 0: a pie slice.
  const double c100 = std::cos(100 * kDeg), s100 = std::sin(100 * kDeg);
  expect_vertices(s.tracks[9],
                  {{1, 0}, {std::sqrt(0.5), std::sqrt(0.5)}, {0, 1}, {c100, s100}, {0, 0}});
  // Default step 15°: -90..90 is 13 points plus the centre; hvflip mirrors through the origin.
  const TrackPolygon& half = s.tracks[10];
  ASSERT_EQ(half.vertices.size(), 14u);
  EXPECT_NEAR(half.vertices[0].first, 1, 1e-12);
  EXPECT_NEAR(half.vertices[0].second, -1, 1e-12);
  EXPECT_NEAR(half.vertices[1].first, 1 + std::cos(-75 * kDeg), 1e-12);
  EXPECT_NEAR(half.vertices[13].first, 1, 1e-12);
  const TrackPolygon& flipped = s.tracks[11];
  ASSERT_EQ(flipped.vertices.size(), 14u);
  for (std::size_t i = 0; i < 14; ++i) {
    EXPECT_NEAR(flipped.vertices[i].first, -half.vertices[i].first, 1e-12);
    EXPECT_NEAR(flipped.vertices[i].second, -half.vertices[i].second, 1e-12);
  }
  const TrackPolygon& poly = s.tracks[12];
  EXPECT_EQ(poly.tag, "poly");
  EXPECT_DOUBLE_EQ(poly.z_m, 0.002);
  EXPECT_DOUBLE_EQ(poly.color.g, 1);
  expect_vertices(poly, {{0, 0}, {1, 0}, {1, 1}});
}

// ---------------------------------------------------------------------------------------
// S2Sim extensions: <plugin>, <s2sim>

TEST(SceneLoader, PluginElements) {
  const Scene s = load_scene(fixture("plugins"));
  ASSERT_EQ(s.plugins.size(), 3u);
  const PluginInstance& log = s.plugins[0];
  EXPECT_EQ(log.kind, "logger");
  EXPECT_EQ(log.id, "log");
  EXPECT_EQ(log.robot, -1);
  EXPECT_EQ(log.params.file, "scene.xml");
  EXPECT_EQ(log.where.element, "scene/plugin[1]");
  EXPECT_EQ(s.plugins[1].id, "logger2");  // default <kind><n>

  // The constants are a snapshot of the scope where the element stands.
  const ElementParams p(log.params);
  EXPECT_DOUBLE_EQ(p.number("rate.hz"), 20);
  EXPECT_EQ(p.text("file.name"), "out.csv");

  const PluginInstance& ctl = s.plugins[2];
  EXPECT_EQ(ctl.kind, "pid");
  EXPECT_EQ(ctl.id, "ctl");
  EXPECT_EQ(ctl.robot, 0);
  EXPECT_EQ(ctl.params.file, "bot.xml");
  EXPECT_THAT(s.robots[0].plugins, ElementsAre(2));
  const ElementParams q(ctl.params);
  EXPECT_DOUBLE_EQ(q.number("gains.kp"), 6);  // robot-file k = 3 times the scene's gain = 2
  EXPECT_EQ(s.globals.find("gain"), 1000);
}

TEST(SceneLoader, S2SimSettingsOverrideTheIni) {
  const Scene s = load_scene(fixture("s2sim_settings"));
  const Settings& st = s.settings;
  EXPECT_EQ(st.source, "config_Params.ini + scene.xml <s2sim>");  // config_Params.ini wins
  EXPECT_DOUBLE_EQ(st.physics_step_s, 0.25e-3);
  EXPECT_EQ(st.substeps, 4);
  EXPECT_DOUBLE_EQ(st.control_period_s, 0.02);
  EXPECT_DOUBLE_EQ(st.default_friction, 0.8);
  EXPECT_DOUBLE_EQ(st.contact_recovery_speed_m_s, 0.2);
  EXPECT_EQ(st.script_udp_address, "0.0.0.0");
  EXPECT_EQ(st.script_udp_port, 9900);
  EXPECT_DOUBLE_EQ(st.erp, 0.3);
  EXPECT_DOUBLE_EQ(st.cfm, 1e-4);
  EXPECT_TRUE(near_vec(st.wind_m_s, {1, -2, 0.5}));
  EXPECT_TRUE(st.ir_noise);
}

// A SimTwo file (no <s2sim>) follows SimTwo's control semantics, a scene with an
// <s2sim> element S2Sim's (docs/format.md §6).
TEST(SceneLoader, ControlSemanticsAreSimTwosUnlessTheSceneHasAnS2SimElement) {
  EXPECT_EQ(load_scene(fixture("joints")).settings.control_semantics, ControlSemantics::simtwo);
  EXPECT_EQ(load_scene(fixture("s2sim_settings")).settings.control_semantics,
            ControlSemantics::s2sim);
}

TEST(SceneLoader, SettingsDefaultsWithoutIni) {
  const Scene s = load_scene(fixture("joints"));
  EXPECT_EQ(s.settings.source, "defaults");
  EXPECT_DOUBLE_EQ(s.settings.physics_step_s, 1e-3);
  EXPECT_DOUBLE_EQ(s.settings.control_period_s, 0.04);
  EXPECT_DOUBLE_EQ(s.settings.default_friction, 0.95);
  EXPECT_DOUBLE_EQ(s.settings.contact_recovery_speed_m_s, 0.3);
  EXPECT_EQ(s.settings.script_udp_address, "127.0.0.1");
  EXPECT_EQ(s.settings.script_udp_port, 9808);
  EXPECT_EQ(s.settings.substeps, 1);
}

// ---------------------------------------------------------------------------------------
// Sensors (§4.11)

TEST(SceneLoader, RobotAndSceneSensors) {
  const Scene s = load_scene(fixture("sensors"));
  ASSERT_EQ(s.sensors.size(), 4u);
  const Robot& r = s.robots.at(0);
  EXPECT_THAT(r.sensors, ElementsAre(0, 1, 2));

  const Sensor& ir = s.sensors[0];
  EXPECT_EQ(ir.id, "n");  // name wins over value
  EXPECT_EQ(ir.body, r.main_body);
  EXPECT_DOUBLE_EQ(ir.beam.length_m, 0.5);  // beams merge
  EXPECT_EQ(ir.beam.rays, 3);
  EXPECT_DOUBLE_EQ(ir.beam.angle_rad, 90 * kDeg);
  EXPECT_DOUBLE_EQ(ir.beam.initial_width_m, 0.01);
  EXPECT_FALSE(ir.noise.present);
  EXPECT_DOUBLE_EQ(ir.color.b, 1);
  EXPECT_EQ(ir.params.element.name, "IRSharp");
  EXPECT_EQ(ir.params.constants->find("len"), 0.5);

  // absolute_coords: given in the robot frame, stored in the Arm frame (Arm at (1,0,0.1), z 90°).
  const Sensor& ranger = s.sensors[1];
  EXPECT_EQ(ranger.id, "r");
  EXPECT_EQ(ranger.body, body_index(s, 0, "Arm"));
  EXPECT_TRUE(ranger.absolute_coords);
  EXPECT_TRUE(near_vec(ranger.pose.position, {1, 0, 0}));
  EXPECT_TRUE(near_mat(ranger.pose.rotation, Mat3::identity(), 1e-12));
  EXPECT_TRUE(ranger.noise.present);
  EXPECT_DOUBLE_EQ(ranger.noise.stdev, 0.1);
  EXPECT_DOUBLE_EQ(ranger.noise.gain, 2);
  EXPECT_THAT(ranger.tags, ElementsAre("a", "b"));
  EXPECT_DOUBLE_EQ(ranger.period_s, 0.05);

  const Sensor& grab = s.sensors[2];
  EXPECT_TRUE(grab.is_tool);
  EXPECT_EQ(grab.kind, "solenoid");
  EXPECT_DOUBLE_EQ(grab.force.fmax_N, 10);
  EXPECT_DOUBLE_EQ(grab.force.k2, 0.5);

  const Sensor& gun = s.sensors[3];
  EXPECT_EQ(gun.id, "gun");
  EXPECT_TRUE(gun.is_tool);
  EXPECT_EQ(gun.robot, -1);
  EXPECT_EQ(gun.body, -1);
  EXPECT_TRUE(near_vec(gun.pose.position, {1, 2, 3}));  // world, not moved
  EXPECT_EQ(gun.params.file, "tools.xml");
  EXPECT_DOUBLE_EQ(ElementParams(gun.params).number("paint_rate.value"), 0.02);
}

// ---------------------------------------------------------------------------------------
// SimTwo tolerance: BOM, text before the declaration, odd comments, Windows paths, quirks

TEST(SceneLoader, QuirksAndWarnings) {
  const Scene s = load_scene(fixture("quirks"));
  ASSERT_EQ(s.robots.size(), 1u);
  EXPECT_EQ(s.robots[0].file.filename(), "q.xml");  // `sub\q.xml`
  // The solid without <ID value> is not created, with a warning.
  EXPECT_EQ(s.robots[0].bodies.size(), 10u);
  EXPECT_TRUE(has_warning(s, "sub/q.xml: robot/solids/cuboid[2]"));
  EXPECT_TRUE(has_warning(s, "missing.png"));
  EXPECT_TRUE(has_warning(s, "<nshells>"));
  EXPECT_TRUE(has_warning(s, "<nsomething>"));
  EXPECT_TRUE(has_warning(s, "missing.xml"));
  EXPECT_TRUE(has_warning(s, "reusing 't.xml'"));
  EXPECT_EQ(s.tracks.size(), 2u);  // the second <track> reused t.xml

  const Body& main = body(s, 0, "Main");
  EXPECT_TRUE(main.geoms[0].visual.texture.empty());
  const Mesh& mesh = main.geoms[0].visual.mesh;
  EXPECT_EQ(mesh.file, fixture("quirks") / "sub" / "mesh.stl");  // scene-folder relative
  EXPECT_DOUBLE_EQ(mesh.scale, 0.001);
  EXPECT_TRUE(near_vec(mesh.offset_m, {0.1, 0.2, 0.3}));
  EXPECT_FALSE(mesh.shadow);

  // Quirk 6: the cylinder radius is `radius` when it differs from 1, else size x.
  EXPECT_DOUBLE_EQ(body(s, 0, "CylR").geoms[0].shape.radius_m, 0.05);
  EXPECT_DOUBLE_EQ(body(s, 0, "CylX").geoms[0].shape.radius_m, 0.3);
  EXPECT_DOUBLE_EQ(body(s, 0, "CylV").geoms[0].shape.radius_m, 0.07);
  EXPECT_DOUBLE_EQ(body(s, 0, "CylV").inertia_kg_m2.m[2][2], 0.07 * 0.07 / 2);

  // Omni/mecanum: mu 1, mu2 0.001 unless <surface> gives them.
  const Geom& omni = body(s, 0, "Omni").geoms[0];
  EXPECT_EQ(omni.friction, FrictionKind::omni);
  EXPECT_TRUE(omni.surface.explicit_surface);
  EXPECT_DOUBLE_EQ(omni.surface.mu, 1);
  EXPECT_DOUBLE_EQ(omni.surface.mu2, 0.001);
  const Geom& mec = body(s, 0, "Mec").geoms[0];
  EXPECT_EQ(mec.friction, FrictionKind::mecanum_left);
  EXPECT_DOUBLE_EQ(mec.surface.mu, 0.6);
  EXPECT_DOUBLE_EQ(mec.surface.mu2, 0.001);
  const Geom& plain = body(s, 0, "Plain").geoms[0];
  EXPECT_FALSE(plain.surface.explicit_surface);  // mu2 alone is no surface
  EXPECT_EQ(plain.friction, FrictionKind::isotropic);

  const Body& p = body(s, 0, "Props");
  const Geom& g = p.geoms[0];
  EXPECT_DOUBLE_EQ(p.mass_kg, 2);
  EXPECT_TRUE(near_mat(p.inertia_kg_m2, Mat3{{{0.1, 0.01, 0}, {0.01, 0.2, 0}, {0, 0, 0.3}}}));
  EXPECT_DOUBLE_EQ(g.visual.color.r, 1);
  EXPECT_DOUBLE_EQ(g.visual.color.g, 0);
  EXPECT_DOUBLE_EQ(g.visual.color.b, 128 / 255.0);  // absent channel: 128
  EXPECT_DOUBLE_EQ(g.visual.color.a, 0.5);
  EXPECT_DOUBLE_EQ(p.drag.coefficient, 0.3);
  EXPECT_DOUBLE_EQ(p.drag.stokes, 0.01);
  EXPECT_DOUBLE_EQ(p.drag.roll, 0.02);
  EXPECT_DOUBLE_EQ(p.buoyancy.mass_kg, -1);
  EXPECT_TRUE(near_vec(p.buoyancy.point_m, {0.1, 0, 0}));
  EXPECT_FALSE(p.gravity);
  EXPECT_TRUE(g.material.metallic);
  EXPECT_TRUE(g.material.ferromagnetic);
  EXPECT_TRUE(g.material.rfid_tag);
  EXPECT_TRUE(g.visual.canvas);
  EXPECT_EQ(g.visual.canvas_width_px, 64);
  EXPECT_EQ(g.visual.canvas_height_px, 32);
  EXPECT_TRUE(g.visual.liquid);
  EXPECT_TRUE(g.visual.painting_target);
  EXPECT_DOUBLE_EQ(g.surface.mu, 0.9);
  EXPECT_DOUBLE_EQ(g.surface.mu2, 0.1);
  EXPECT_DOUBLE_EQ(g.surface.softness, 0.01);
  EXPECT_DOUBLE_EQ(g.surface.bounce, 0.5);
  EXPECT_DOUBLE_EQ(g.surface.bounce_threshold_m_s, 0.2);
  EXPECT_EQ(body(s, 0, "Prop").kind, SolidKind::propeller);
  EXPECT_DOUBLE_EQ(body(s, 0, "Prop").thrust_coefficient, 0.1);
  EXPECT_DOUBLE_EQ(body(s, 0, "Prop2").thrust_coefficient, 0.5);
  EXPECT_EQ(main.where.file, "sub/q.xml");
  EXPECT_EQ(main.where.element, "robot/solids/cuboid[1]");
}

}  // namespace
}  // namespace s2sim::scene

namespace s2sim::scene {
namespace {

// A script file name longer than the system allows (a fuzzed scene) was an exception of the
// file system library, reported as a refused resource (exit 1); it is a located scene error.
TEST(SceneLoader, AnOverLongScriptFileNameIsALocatedSceneError) {
  const std::filesystem::path dir = s2sim::test::process_temp_dir() / "long_script_name";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "scene.xml") << "<?xml version='1.0'?><scene><s2sim><script file='" +
                                          std::string(5000, 'c') + ".pas'/></s2sim></scene>";
  const Error e = load_error(dir / "scene.xml");
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_THAT(e.what(), HasSubstr("scene/s2sim/script@file: cannot read the script file"));
  EXPECT_THAT(e.what(), HasSubstr("File name too long"));
}

}  // namespace
}  // namespace s2sim::scene
