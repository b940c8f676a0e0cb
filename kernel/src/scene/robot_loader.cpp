/// \file
/// Robot files (simtwo-format.md §4): built in the robot frame section by section, then
/// placed in the world (§9.3) with one transform for bodies, anchors and axes, including
/// joints to the world (S2Sim fixes quirk 18).

#include "scene/loading.hpp"
#include "scene/rotation.hpp"
#include "scene/xml.hpp"

namespace s2sim::scene::detail {

void place_robot(Scene& scene, Robot& rb, const Vec3& offset, double yaw_deg) {
  const Vec3 p0 = rb.main_body >= 0
                      ? scene.bodies[static_cast<std::size_t>(rb.main_body)].pose.position
                      : Vec3{};
  rb.origin_m = p0;
  rb.offset_m = offset;
  rb.yaw_rad = deg_to_rad(yaw_deg);
  const Mat3 rz = rot_z_deg(yaw_deg);
  auto move = [&](const Vec3& p) { return p0 + offset + rz * (p - p0); };
  for (int b : rb.bodies) {
    Pose& pose = scene.bodies[static_cast<std::size_t>(b)].pose;
    pose = Pose{move(pose.position), rz * pose.rotation};
  }
  for (int j : rb.joints) {
    Joint& joint = scene.joints[static_cast<std::size_t>(j)];
    joint.anchor_m = move(joint.anchor_m);
    joint.axis1 = rz * joint.axis1;
    joint.axis2 = rz * joint.axis2;
  }
  // Sensors and geoms are in body frames and follow their bodies.
}

void load_robot_file(LoadContext& ctx, const std::filesystem::path& file,
                     const ConstantTable& globals, const RobotPlacement& placement) {
  Scene& scene = ctx.scene;
  const std::string display = ctx.display(file);
  const Element root = read_xml_file(file, display);
  if (root.name != "robot")
    throw Error(ErrorKind::scene, Location{display, root.path, ""},
                "expected a <robot> file, found <" + root.name + ">");

  ConstantTable scope = globals;  // robot-file defines stay in the file (§2.2)
  const Reader r(display, scope);
  Robot robot;
  robot.id = placement.id;
  robot.file = file;
  robot.where = placement.where;
  scene.robots.push_back(std::move(robot));
  const int index = static_cast<int>(scene.robots.size() - 1);
  auto rb = [&]() -> Robot& { return scene.robots[static_cast<std::size_t>(index)]; };

  for (const Element& el : root.children) {
    const std::string& n = el.name;
    if (n == "kind") {
      rb().kind = r.text(el, "value", rb().kind);
    } else if (n == "defines") {
      apply_defines(el, r, scope);
    } else if (n == "solids") {
      for (const Element& c : el.children) {
        if (c.name == "defines") {
          apply_defines(c, r, scope);
        } else if (is_solid_element(c.name)) {
          if (auto body = load_solid(ctx, r, c, index, rb().bodies)) {
            rb().bodies.push_back(*body);
            if (rb().main_body < 0) rb().main_body = *body;  // the first solid
          }
        }
      }
    } else if (n == "wheels") {
      load_wheels(ctx, r, el, index);
    } else if (n == "shells") {
      load_shells(ctx, r, el, index);
    } else if (n == "articulations") {
      load_articulations(ctx, r, el, index);
    } else if (n == "sensors" || n == "tools") {
      load_sensors(ctx, r, el, index, n == "tools");
    } else if (n == "plugin") {
      load_plugin(ctx, r, el, index);
    } else {
      // SimTwo files disable sections by renaming them (<nshells>): harmless, but say so.
      ctx.warn(r.at(el), "unknown robot element <" + n + "> ignored");
    }
  }
  if (rb().main_body < 0) ctx.warn(r.at(root), "robot '" + rb().id + "' has no solid");
  place_robot(scene, rb(), placement.offset_m, placement.yaw_deg);
}

}  // namespace s2sim::scene::detail
