// The three real SimTwo scenes of /work/shared/simtwo-scenes load to what SimTwo builds
// (simtwo-format.md §15). Skipped when the folder is absent.

#include "scene/element_params.hpp"
#include "scene_test_util.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace s2sim::scene {
namespace {

using ::testing::ElementsAre;
using namespace testing;

constexpr double kDeg = kPi / 180;

std::vector<std::string> body_ids(const Scene& s, const Robot& r) {
  std::vector<std::string> ids;
  for (int b : r.bodies)
    ids.push_back(s.bodies[static_cast<std::size_t>(b)].id);
  return ids;
}

TEST(SharedScenes, BaseRobotsWheelsAndSettings) {
  S2SIM_SKIP_WITHOUT_SHARED_SCENES();
  const Scene s = load_scene(shared_scene("base"));

  EXPECT_EQ(s.settings.source, "SimTwo.ini");
  EXPECT_DOUBLE_EQ(s.settings.physics_step_s, 1e-3);
  EXPECT_DOUBLE_EQ(s.settings.erp, 0.1);
  EXPECT_DOUBLE_EQ(s.settings.default_friction, 2);
  EXPECT_DOUBLE_EQ(s.settings.control_period_s, 0.04);
  EXPECT_FALSE(s.settings.ir_noise);

  ASSERT_EQ(s.robots.size(), 2u);
  const Robot& classic = s.robots[0];
  EXPECT_EQ(classic.id, "Classic");
  EXPECT_EQ(classic.kind, "wheelchair");
  EXPECT_EQ(classic.file.filename(), "Differential2.xml");
  EXPECT_THAT(body_ids(s, classic), ElementsAre("1", "Tyre -90", "Tyre 90", "Tyre 180"));
  const Body& main = s.bodies[static_cast<std::size_t>(classic.main_body)];
  EXPECT_DOUBLE_EQ(main.mass_kg, 1.8);
  EXPECT_TRUE(near_vec(main.pose.position, {0, -1, 0.08}));
  ASSERT_EQ(main.geoms.size(), 2u);  // the cuboid and the bumper shell
  EXPECT_TRUE(main.geoms[1].is_shell);
  for (int i = 1; i <= 3; ++i) {
    const Body& tyre =
        s.bodies[static_cast<std::size_t>(classic.bodies[static_cast<std::size_t>(i)])];
    EXPECT_EQ(tyre.kind, SolidKind::tyre);
    EXPECT_DOUBLE_EQ(tyre.mass_kg, 0.8);
    EXPECT_DOUBLE_EQ(tyre.geoms[0].shape.radius_m, 0.04);
    EXPECT_DOUBLE_EQ(tyre.geoms[0].shape.length_m, 0.03);
  }

  ASSERT_EQ(classic.joints.size(), 3u);
  const Joint& w1 = s.joints[static_cast<std::size_t>(classic.joints[0])];
  const Joint& w2 = s.joints[static_cast<std::size_t>(classic.joints[1])];
  const Joint& w3 = s.joints[static_cast<std::size_t>(classic.joints[2])];
  EXPECT_EQ(w1.id, "W1");
  EXPECT_EQ(w2.id, "W2");
  EXPECT_EQ(w3.id, "W3");
  for (const Joint* j : {&w1, &w2, &w3}) {
    EXPECT_EQ(j->type, JointType::hinge);
    EXPECT_TRUE(j->from_wheels);
    EXPECT_EQ(j->body2, classic.main_body);
    const ElementParams d(j->drive1);
    EXPECT_DOUBLE_EQ(d.number("gear.ratio"), 12);
    EXPECT_DOUBLE_EQ(d.number("motor.ri"), 0.3);
    EXPECT_DOUBLE_EQ(d.number("motor.vmax"), 12);
    EXPECT_EQ(d.text("controller.mode", "pidspeed"), "pidspeed");
    EXPECT_DOUBLE_EQ(d.number("controller.kp"), 0.2);
    EXPECT_DOUBLE_EQ(d.number("controller.kd"), 0.01);
    EXPECT_DOUBLE_EQ(d.number("controller.kf"), 0.05);
    EXPECT_DOUBLE_EQ(d.number("controller.period", 10), 10);
    EXPECT_TRUE(d.boolean("controller.active", false));
  }
  EXPECT_EQ(s.bodies[static_cast<std::size_t>(w1.body1)].id, "Tyre -90");
  EXPECT_TRUE(near_vec(w1.axis1, {0, 1, 0}));
  EXPECT_TRUE(near_vec(w2.axis1, {0, -1, 0}));
  EXPECT_TRUE(near_vec(w3.axis1, {1, 0, 0}));
  EXPECT_TRUE(near_vec(w1.anchor_m, {0, -1.09, 0.04}));
  EXPECT_TRUE(near_vec(w2.anchor_m, {0, -0.91, 0.04}));
  EXPECT_TRUE(near_vec(w3.anchor_m, {-0.09, -1, 0.04}));
  EXPECT_TRUE(ElementParams(w1.drive1).boolean("motor.active", true));
  EXPECT_FALSE(ElementParams(w3.drive1).boolean("motor.active", true));  // the passive caster
  EXPECT_EQ(s.bodies[static_cast<std::size_t>(w3.body1)].geoms[0].friction, FrictionKind::omni);

  const Robot& belt = s.robots[1];
  EXPECT_EQ(belt.id, "Conveyor Belt");
  ASSERT_EQ(belt.bodies.size(), 1u);
  const Body& b = s.bodies[static_cast<std::size_t>(belt.main_body)];
  EXPECT_EQ(b.kind, SolidKind::belt);
  EXPECT_DOUBLE_EQ(b.mass_kg, 20);
  EXPECT_TRUE(near_vec(b.pose.position, {1, -1, 0.1}));
  EXPECT_EQ(b.geoms.size(), 3u);
  EXPECT_EQ(b.geoms[0].visual.texture.filename(), "ConveyorBelt256.jpg");
  EXPECT_TRUE(b.geoms[0].visual.texture.is_absolute());
  EXPECT_DOUBLE_EQ(b.geoms[0].visual.texture_scale, 6);

  ASSERT_EQ(s.sensors.size(), 2u);
  EXPECT_EQ(s.sensors[0].kind, "IRSharp");
  EXPECT_EQ(s.sensors[0].robot, 0);
  EXPECT_EQ(s.sensors[1].robot, 1);
  EXPECT_TRUE(near_vec(s.sensors[1].pose.position, {0.65, -0.2, 0.15}));
  EXPECT_TRUE(near_vec(s.sensors[1].pose.rotation.column(0), {0, 1, 0}));  // z = 90: beam +Y

  ASSERT_EQ(s.things.size(), 5u);
  const Body& ball = s.bodies[static_cast<std::size_t>(s.things[0])];
  EXPECT_EQ(ball.id, "Ball");
  EXPECT_EQ(ball.robot, -1);
  EXPECT_DOUBLE_EQ(ball.mass_kg, 0.3);
  EXPECT_DOUBLE_EQ(ball.geoms[0].shape.radius_m, 0.1);
  EXPECT_TRUE(ball.geoms[0].surface.explicit_surface);
  EXPECT_DOUBLE_EQ(ball.geoms[0].surface.mu, 0.1);
  EXPECT_DOUBLE_EQ(ball.drag.stokes, 1e-4);
  const Body& c1 = s.bodies[static_cast<std::size_t>(s.things[4])];
  EXPECT_EQ(c1.id, "C1");
  EXPECT_DOUBLE_EQ(c1.geoms[0].shape.radius_m, 0.1);  // from size x
  EXPECT_DOUBLE_EQ(c1.geoms[0].shape.length_m, 0.2);

  ASSERT_EQ(s.obstacles.size(), 4u);
  EXPECT_TRUE(near_vec(s.obstacles[0].pose.position, {1.4, 2, 0}));
  EXPECT_TRUE(near_vec(s.obstacles[0].shape.size_m, {1, 2, 0.5}));
  EXPECT_TRUE(s.tracks.empty());
  EXPECT_TRUE(has_warning(s, "track.xml"));
  EXPECT_EQ(s.joints.size(), 3u);
  EXPECT_EQ(s.bodies.size(), 10u);
}

TEST(SharedScenes, DefaultBeltArgThingsSensorsAndField) {
  S2SIM_SKIP_WITHOUT_SHARED_SCENES();
  const Scene s = load_scene(shared_scene("default"));

  EXPECT_EQ(s.settings.source, "SimTwo.ini");
  EXPECT_DOUBLE_EQ(s.settings.physics_step_s, 1e-3);
  EXPECT_DOUBLE_EQ(s.settings.erp, 0.2);
  EXPECT_DOUBLE_EQ(s.settings.default_friction, 0.5);

  // Omni3.xml is missing: skipped with a warning, so the belt is robot 0.
  EXPECT_TRUE(has_warning(s, "Omni3.xml"));
  ASSERT_EQ(s.robots.size(), 1u);
  const Robot& belt = s.robots[0];
  EXPECT_EQ(belt.id, "belt");
  const Body& b = s.bodies[static_cast<std::size_t>(belt.main_body)];
  EXPECT_DOUBLE_EQ(b.mass_kg, 20);
  // <arg belt_length 1.5>; the scene's <noconst> override is ignored.
  EXPECT_DOUBLE_EQ(b.geoms[0].shape.size_m.x, 1.5);
  ASSERT_EQ(b.geoms.size(), 3u);
  EXPECT_DOUBLE_EQ(b.geoms[1].shape.size_m.x, 1.6);
  EXPECT_TRUE(near_vec(b.pose.position, {1.5, 0, 0.5}));
  const Sensor& beacon = sensor(s, "IRBeacon");
  EXPECT_EQ(beacon.robot, 0);
  EXPECT_DOUBLE_EQ(beacon.pose.position.x, 0.65);
  EXPECT_EQ(belt.sensors.size(), 1u);  // <nranger2d> is disabled

  ASSERT_EQ(s.things.size(), 6u);
  const Body& ball = s.bodies[static_cast<std::size_t>(s.things[0])];
  EXPECT_DOUBLE_EQ(ball.geoms[0].shape.radius_m, 0.1);  // scene-level ball_radius
  const Body& t1 = body(s, -1, "T1");
  EXPECT_TRUE(t1.geoms[0].visual.canvas);
  EXPECT_EQ(t1.geoms[0].visual.canvas_width_px, 128);
  EXPECT_EQ(t1.geoms[0].visual.canvas_height_px, 128);
  const Body& t3 = body(s, -1, "T3");
  EXPECT_TRUE(t3.geoms[0].material.metallic);
  EXPECT_DOUBLE_EQ(t3.geoms[0].surface.mu, 100);
  EXPECT_DOUBLE_EQ(body(s, -1, "C2").geoms[0].shape.length_m, 0.1);

  // Scene-level sensors.
  ASSERT_EQ(s.sensors.size(), 4u);
  const Sensor& ranger = sensor(s, "ranger2d");
  EXPECT_EQ(ranger.kind, "ranger2d");
  EXPECT_EQ(ranger.robot, -1);
  EXPECT_EQ(ranger.body, -1);
  EXPECT_EQ(ranger.beam.rays, 768);
  EXPECT_DOUBLE_EQ(ranger.beam.length_m, 1);
  EXPECT_NEAR(ranger.beam.angle_rad, 270 * kDeg, 1e-12);
  EXPECT_TRUE(ranger.noise.present);
  EXPECT_DOUBLE_EQ(ranger.noise.stdev, 0.002);
  EXPECT_THAT(ranger.tags, ElementsAre("00"));
  EXPECT_TRUE(near_vec(ranger.pose.position, {1, 0, 0.5}));
  EXPECT_TRUE(near_vec(ranger.pose.rotation.column(0), {0, 0, -1}));  // y = 90: down
  EXPECT_EQ(sensor(s, "Ind0").kind, "inductive");
  EXPECT_EQ(sensor(s, "Sharp80").params.file, "sensors.xml");

  EXPECT_EQ(s.obstacles.size(), 4u);
  ASSERT_EQ(s.tracks.size(), 6u);
  for (const TrackPolygon& t : s.tracks) {
    EXPECT_EQ(t.tag, "white");
    EXPECT_EQ(t.vertices.size(), 26u);  // -90..90 every 15°, outer then inner
    EXPECT_NEAR(t.color.r, 0x8F / 255.0, 1e-12);
    EXPECT_DOUBLE_EQ(t.z_m, 0.01);
  }
  EXPECT_NEAR(s.tracks[0].vertices[0].first, 0, 1e-12);
  EXPECT_NEAR(s.tracks[0].vertices[0].second, -0.5, 1e-12);
  EXPECT_NEAR(s.tracks[0].vertices[13].second, 0.45, 1e-12);  // inner edge starts at +90°

  EXPECT_EQ(s.globals.find("ball_radius"), 0.1);
  EXPECT_FALSE(s.globals.find("belt_length"));  // robot-file scope
}

TEST(SharedScenes, MotorModelDriveTrainAndIniPrecedence) {
  S2SIM_SKIP_WITHOUT_SHARED_SCENES();
  const Scene s = load_scene(shared_scene("MotorModel_V3AGM") / "scene.xml");

  // config_Params.ini (1 ms) wins over SimTwo.ini (0.5 ms).
  EXPECT_EQ(s.settings.source, "config_Params.ini");
  EXPECT_DOUBLE_EQ(s.settings.physics_step_s, 1e-3);
  EXPECT_DOUBLE_EQ(s.settings.erp, 0.4);

  // Motor.xml has a blank line and spaces before its <?xml ?> declaration.
  ASSERT_EQ(s.robots.size(), 1u);
  const Robot& r = s.robots[0];
  EXPECT_EQ(r.id, "Motor");
  EXPECT_EQ(r.kind, "MotorBoard");
  EXPECT_THAT(body_ids(s, r), ElementsAre("Base", "InertialBoard", "Motor"));
  const Body& base = body(s, 0, "Base");
  EXPECT_DOUBLE_EQ(base.mass_kg, 50);
  EXPECT_NEAR(base.geoms[0].shape.size_m.z, 0.78, 1e-12);
  EXPECT_TRUE(near_vec(base.pose.position, {0, 0.3, 0.39}, 1e-12));
  EXPECT_DOUBLE_EQ(body(s, 0, "InertialBoard").mass_kg, 2.5);
  const Body& motor = body(s, 0, "Motor");
  EXPECT_DOUBLE_EQ(motor.mass_kg, 0.15);
  EXPECT_EQ(motor.geoms[0].shape.type, ShapeType::cylinder);
  EXPECT_DOUBLE_EQ(motor.geoms[0].shape.radius_m, 0.04);  // quirk 6: size x = 2 * motor_radius
  EXPECT_DOUBLE_EQ(motor.geoms[0].shape.length_m, 0.1);
  EXPECT_TRUE(near_vec(motor.pose.rotation.column(2), {0, -1, 0}));  // rot x = 90

  ASSERT_EQ(r.joints.size(), 2u);
  const Joint& hinge = joint(s, 0, "InertialBoard");
  EXPECT_EQ(hinge.type, JointType::hinge);
  EXPECT_EQ(hinge.body1, body_index(s, 0, "Base"));
  EXPECT_EQ(hinge.body2, body_index(s, 0, "InertialBoard"));
  EXPECT_TRUE(near_vec(hinge.axis1, {0, 1, 0}));
  EXPECT_TRUE(near_vec(hinge.anchor_m, {0, 0, 0.82}, 1e-12));
  EXPECT_FALSE(hinge.limits1.active);
  const ElementParams d(hinge.drive1);
  EXPECT_DOUBLE_EQ(d.number("motor.ri"), 7.1);
  EXPECT_DOUBLE_EQ(d.number("motor.li"), 3.4e-3);
  EXPECT_DOUBLE_EQ(d.number("motor.ki"), 0.187);
  EXPECT_DOUBLE_EQ(d.number("motor.vmax"), 15);
  EXPECT_DOUBLE_EQ(d.number("motor.imax"), 10);
  EXPECT_DOUBLE_EQ(d.number("gear.ratio"), 1);
  EXPECT_DOUBLE_EQ(d.number("friction.bv"), 0.000931);
  EXPECT_DOUBLE_EQ(d.number("friction.fc"), 0.026);
  EXPECT_EQ(d.integer("encoder.ppr"), 10044);
  EXPECT_FALSE(d.boolean("controller.active", false));
  EXPECT_DOUBLE_EQ(d.number("controller.kp"), 100);
  EXPECT_DOUBLE_EQ(d.number("controller.period", 10), 10);
  EXPECT_DOUBLE_EQ(hinge.draw.radius_m, 0.005);
  EXPECT_NEAR(hinge.draw.color.g, 0x8F / 255.0, 1e-12);
  const Joint& glue = joint(s, 0, "Glue");
  EXPECT_EQ(glue.type, JointType::fixed);
  EXPECT_EQ(glue.body1, body_index(s, 0, "Base"));
  EXPECT_EQ(glue.body2, body_index(s, 0, "Motor"));

  EXPECT_EQ(s.obstacles.size(), 4u);
  EXPECT_TRUE(s.things.empty());
  EXPECT_TRUE(has_warning(s, "things.xml"));
  EXPECT_TRUE(has_warning(s, "track.xml"));
}

}  // namespace
}  // namespace s2sim::scene
