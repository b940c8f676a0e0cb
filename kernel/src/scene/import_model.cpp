/// \file
/// `add_imported_robot`: an `ImportedModel` into the scene's bodies and joints, with the
/// checks every format shares (docs/models/import.md).

#include "scene/import_model.hpp"

#include "scene/attributes.hpp"
#include "scene/mass.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

namespace s2sim::scene::detail {
namespace {

/// Round-trip text of a number: the drive train reads its parameters as written.
std::string exact_text(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

Mat3 transpose(const Mat3& a) {
  Mat3 t;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      t.m[i][j] = a.m[j][i];
  return t;
}

/// MuJoCo's rule (scene::inertia_problem).
void check_inertial(const ImportedLink& link) {
  const std::string why = inertia_problem(link.mass_kg, link.inertia_kg_m2);
  if (!why.empty())
    throw Error(ErrorKind::scene, link.inertia_where,
                "link '" + link.name + "': non-physical inertial: " + why);
}

const char* type_name(ImportedJointType t) {
  switch (t) {
    case ImportedJointType::revolute:
      return "revolute";
    case ImportedJointType::continuous:
      return "continuous";
    case ImportedJointType::prismatic:
      return "prismatic";
    case ImportedJointType::fixed:
      return "fixed";
    case ImportedJointType::floating:
      return "floating";
    case ImportedJointType::ball:
      return "ball";
  }
  return "?";
}

Element attribute_element(const std::string& name, const std::string& path,
                          std::vector<std::pair<std::string, std::string>> attributes) {
  Element e;
  e.name = name;
  e.path = path;
  e.attributes = std::move(attributes);
  return e;
}

/// The joint's drive-train elements: no motor (the formats have none), the joint's own
/// damping and Coulomb friction instead of the drive train's defaults, its spring.
ParamSource imported_drive(const ImportedJoint& j, const std::string& file, bool rotational,
                           const std::shared_ptr<const ConstantTable>& constants) {
  ParamSource p;
  p.element.name = "drive_train";
  p.element.path = j.where.element;
  p.file = file;
  p.constants = constants;
  const std::string& at = j.where.element;
  p.element.children.push_back(attribute_element("motor", at, {{"active", "0"}}));
  p.element.children.push_back(attribute_element(
      "friction", at, {{"bv", exact_text(j.damping)}, {"fc", exact_text(j.friction)}}));
  if (j.spring_stiffness != 0) {
    const double zero = rotational ? j.spring_reference * 180 / kPi : j.spring_reference;
    p.element.children.push_back(attribute_element(
        "spring", at, {{"k", exact_text(j.spring_stiffness)}, {"zeropos", exact_text(zero)}}));
  }
  for (const Element& extension : j.s2sim_drive) {
    auto& children = p.element.children;
    const auto same = std::find_if(children.begin(), children.end(),
                                   [&](const Element& c) { return c.name == extension.name; });
    if (same != children.end()) children.erase(same);
    children.push_back(extension);
  }
  return p;
}

/// The lowest z of a shape at a world pose.
double lowest_point(const Pose& pose, const Shape& shape) {
  const Mat3& r = pose.rotation;
  switch (shape.type) {
    case ShapeType::box:
      return pose.position.z -
             0.5 * (std::abs(r.m[2][0]) * shape.size_m.x + std::abs(r.m[2][1]) * shape.size_m.y +
                    std::abs(r.m[2][2]) * shape.size_m.z);
    case ShapeType::cylinder: {
      const double axial = std::abs(r.m[2][2]);
      return pose.position.z - 0.5 * shape.length_m * axial -
             shape.radius_m * std::sqrt(std::max(0.0, 1 - axial * axial));
    }
    case ShapeType::sphere:
      return pose.position.z - shape.radius_m;
    case ShapeType::convex: {
      double lowest = std::numeric_limits<double>::infinity();
      for (const Vec3& v : shape.hull->vertices)
        lowest = std::min(lowest, (pose * v).z);
      return lowest;
    }
  }
  return pose.position.z;
}

/// Each moving joint must move some inertia along its motion: the links it carries (its child
/// and everything beyond) have mass for a slider, inertia about the axis for a hinge, an
/// inertia about the anchor with no zero moment for a ball. Otherwise the mass matrix is
/// singular and the run would stop at its first step with a NaN.
void check_joints_move_inertia(const Scene& scene, const Robot& rb) {
  std::vector<std::vector<int>> carried(scene.bodies.size());  // bodies beyond each body
  for (int b : rb.bodies) {
    for (int at = b, guard = 0; at >= 0 && guard <= static_cast<int>(rb.joints.size()); ++guard) {
      carried[static_cast<std::size_t>(at)].push_back(b);
      int parent = -1;
      for (int j : rb.joints) {
        const Joint& joint = scene.joints[static_cast<std::size_t>(j)];
        if (joint.body1 == at) parent = joint.body2;
      }
      at = parent;
    }
  }
  constexpr double kLeast = 1e-12;  // kg, kg·m²
  for (int j : rb.joints) {
    const Joint& joint = scene.joints[static_cast<std::size_t>(j)];
    if (joint.type == JointType::fixed || joint.body1 < 0) continue;
    double mass = 0;
    Mat3 about_anchor{{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}};
    for (int b : carried[static_cast<std::size_t>(joint.body1)]) {
      const Body& body = scene.bodies[static_cast<std::size_t>(b)];
      if (!(body.mass_kg > 0)) continue;
      const Mat3& r = body.pose.rotation;
      const Vec3 d = body.pose * body.com_m - joint.anchor_m;
      Mat3 i = r * body.inertia_kg_m2 * transpose(r);
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) {
          const double dk = k == 0 ? d.x : k == 1 ? d.y : d.z;
          const double dl = l == 0 ? d.x : l == 1 ? d.y : d.z;
          i.m[k][l] += body.mass_kg * ((k == l ? dot(d, d) : 0) - dk * dl);
        }
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          about_anchor.m[k][l] += i.m[k][l];
      mass += body.mass_kg;
    }
    const Vec3& a = joint.axis1;
    const double moved = joint.type == JointType::slider  ? mass
                         : joint.type == JointType::hinge ? dot(a, about_anchor * a)
                                                          : symmetric_eigenvalues(about_anchor)[0];
    if (!(moved > kLeast))
      throw Error(ErrorKind::scene, joint.where,
                  "joint '" + joint.id + "' moves link '" +
                      scene.bodies[static_cast<std::size_t>(joint.body1)].id + "' and what it " +
                      "carries, which have no " +
                      (joint.type == JointType::slider ? std::string("mass")
                                                       : std::string("inertia about its axis")) +
                      " (" + format_number(moved) +
                      "): the mass matrix would be singular; give the link an inertia");
  }
}

/// The model's couplings on the robot's scene joints (named as the model's); a joint merged
/// away (fixed) or not in the model is an error at the coupling.
void add_imported_couplings(Scene& scene, const ImportedModel& model, const Robot& rb) {
  for (const ImportedCoupling& ic : model.couplings) {
    auto scene_joint = [&](const std::string& name) {
      for (int j : rb.joints)
        if (scene.joints[static_cast<std::size_t>(j)].id == name) return j;
      const bool in_model = std::any_of(model.joints.begin(), model.joints.end(),
                                        [&](const ImportedJoint& ij) { return ij.name == name; });
      throw Error(ErrorKind::scene, ic.where,
                  "joint '" + ic.follower + "' follows '" + ic.leader + "': joint '" + name +
                      (in_model ? "' does not move (a fixed or floating joint); only hinges and "
                                  "sliders can be coupled"
                                : "' is not in the model"));
    };
    JointCoupling c;
    c.follower = scene_joint(ic.follower);
    c.leader = scene_joint(ic.leader);
    c.multiplier = ic.multiplier;
    c.offset = ic.offset;
    c.where = ic.where;
    scene.couplings.push_back(c);
  }
  validate_couplings(scene);
}

}  // namespace

void add_imported_robot(LoadContext& ctx, ImportedModel model, const RobotPlacement& placement) {
  Scene& scene = ctx.scene;
  const auto n_links = model.links.size();
  for (const ImportedLink& link : model.links)
    if (link.has_inertial) check_inertial(link);

  // The joint that makes each link a child; a link is the child of at most one joint.
  std::vector<int> parent_joint(n_links, -1);
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    const ImportedJoint& joint = model.joints[j];
    auto& pj = parent_joint[static_cast<std::size_t>(joint.child)];
    if (pj >= 0)
      throw Error(ErrorKind::scene, joint.where,
                  "link '" + model.links[static_cast<std::size_t>(joint.child)].name +
                      "' is already the child of joint '" +
                      model.joints[static_cast<std::size_t>(pj)].name +
                      "' (a kinematic loop: not supported)");
    pj = static_cast<int>(j);
  }
  // Fixed joints between links merge the child into the parent's body: `owner` is the link
  // whose body a link belongs to.
  std::vector<int> owner(n_links);
  for (std::size_t l = 0; l < n_links; ++l) {
    int o = static_cast<int>(l);
    for (std::size_t guard = 0; guard <= n_links; ++guard) {
      const int pj = parent_joint[static_cast<std::size_t>(o)];
      if (pj < 0) break;
      const ImportedJoint& joint = model.joints[static_cast<std::size_t>(pj)];
      if (joint.type != ImportedJointType::fixed || joint.parent < 0) break;
      o = joint.parent;
      if (guard == n_links) throw Error(ErrorKind::scene, joint.where, "the joints form a loop");
    }
    owner[l] = o;
  }

  Robot robot;
  robot.id = placement.id;
  robot.file = model.file;
  robot.where = placement.where;
  robot.kind = "imported";
  scene.robots.push_back(std::move(robot));
  const int robot_index = static_cast<int>(scene.robots.size() - 1);
  Robot& rb = scene.robots.back();

  // One body per owner link, in link order.
  std::vector<int> body_of(n_links, -1);
  for (std::size_t l = 0; l < n_links; ++l) {
    if (owner[l] != static_cast<int>(l)) continue;
    const ImportedLink& link = model.links[l];
    Body b;
    b.id = link.name;
    b.kind = SolidKind::cuboid;
    b.robot = robot_index;
    b.pose = link.pose;
    b.mass_kg = link.mass_kg;
    b.com_m = link.com_m;
    b.inertia_kg_m2 = link.inertia_kg_m2;
    b.geoms = link.geoms;
    b.visuals = link.visuals;
    b.where = link.where;
    scene.bodies.push_back(std::move(b));
    body_of[l] = static_cast<int>(scene.bodies.size() - 1);
    rb.bodies.push_back(body_of[l]);
  }
  for (std::size_t l = 0; l < n_links; ++l) {
    if (owner[l] == static_cast<int>(l)) continue;
    const ImportedLink& link = model.links[l];
    Body& b = scene.bodies[static_cast<std::size_t>(body_of[static_cast<std::size_t>(owner[l])])];
    body_of[l] = body_of[static_cast<std::size_t>(owner[l])];
    // The link in the body frame: T = body⁻¹ · link.
    const Mat3 rt = transpose(b.pose.rotation);
    const Pose t{rt * (link.pose.position - b.pose.position), rt * link.pose.rotation};
    if (link.mass_kg > 0) {
      if (b.mass_kg > 0) {
        add_rigid_part(b, link.mass_kg, t * link.com_m,
                       t.rotation * link.inertia_kg_m2 * transpose(t.rotation));
      } else {
        b.mass_kg = link.mass_kg;
        b.com_m = t * link.com_m;
        b.inertia_kg_m2 = t.rotation * link.inertia_kg_m2 * transpose(t.rotation);
      }
    }
    for (Geom g : link.geoms) {
      g.pose = t * g.pose;
      b.geoms.push_back(std::move(g));
    }
    for (Geom g : link.visuals) {
      g.pose = t * g.pose;
      b.visuals.push_back(std::move(g));
    }
  }
  // The main body: the first link that hangs from nothing or from the world.
  for (std::size_t l = 0; l < n_links && rb.main_body < 0; ++l)
    if (parent_joint[l] < 0 || model.joints[static_cast<std::size_t>(parent_joint[l])].parent < 0)
      rb.main_body = body_of[l];

  const auto constants = std::make_shared<const ConstantTable>();
  std::vector<std::string> unapplied_velocity, unactuated_effort;
  for (const ImportedJoint& ij : model.joints) {
    const int child = body_of[static_cast<std::size_t>(ij.child)];
    const int parent = ij.parent < 0 ? -1 : body_of[static_cast<std::size_t>(ij.parent)];
    if (ij.type == ImportedJointType::fixed && parent >= 0) continue;  // merged above
    if (ij.type == ImportedJointType::floating) continue;              // a free body
    Joint j;
    j.id = ij.name;
    j.robot = robot_index;
    j.body1 = child;  // the joint variable is the child's motion relative to the parent
    j.body2 = parent;
    j.anchor_m = ij.anchor_m;
    j.axis1 = ij.axis;
    j.where = ij.where;
    const bool rotational = ij.type != ImportedJointType::prismatic;
    switch (ij.type) {
      case ImportedJointType::revolute:
      case ImportedJointType::continuous:
        j.type = JointType::hinge;
        break;
      case ImportedJointType::prismatic:
        j.type = JointType::slider;
        break;
      case ImportedJointType::ball:
        j.type = JointType::ball;
        break;
      default:
        j.type = JointType::fixed;
        break;
    }
    if (ij.limited && (j.type == JointType::hinge || j.type == JointType::slider)) {
      if (!(ij.lower <= ij.upper))
        throw Error(ErrorKind::scene, ij.where,
                    "joint '" + ij.name + "': lower limit " + format_number(ij.lower) +
                        " is above the upper limit " + format_number(ij.upper));
      constexpr double inf = std::numeric_limits<double>::infinity();
      bool beyond_pi = false;
      j.limits1.min = ij.lower;
      j.limits1.max = ij.upper;
      if (rotational && (ij.lower <= -kPi || ij.upper >= kPi)) {
        // The hinge angle lives in (-pi, pi] (format.md §7.4): a stop beyond it cannot engage.
        if (std::isfinite(ij.lower) && ij.lower <= -kPi) beyond_pi = true;
        if (std::isfinite(ij.upper) && ij.upper >= kPi) beyond_pi = true;
        if (ij.lower <= -kPi) j.limits1.min = -inf;
        if (ij.upper >= kPi) j.limits1.max = inf;
        if (beyond_pi)
          model.warnings.push_back(ij.where.str() + ": joint '" + ij.name + "': limits [" +
                                   format_number(ij.lower) + ", " + format_number(ij.upper) +
                                   "] rad reach beyond ±pi; that side is left open");
      }
      j.limits1.active = j.limits1.min > -inf || j.limits1.max < inf;
    } else if (ij.limited && j.type == JointType::ball) {
      model.warnings.push_back(ij.where.str() + ": joint '" + ij.name +
                               "': limits of a ball joint are not applied");
    }
    if (j.type == JointType::hinge || j.type == JointType::slider) {
      j.drive1 = imported_drive(ij, model.display, rotational, constants);
      j.drive2 = j.drive1;
      j.wrap1 = ij.type == ImportedJointType::continuous;
      if (ij.velocity_limit) unapplied_velocity.push_back(ij.name);
      if (ij.actuated) {
        PluginInstance pi;
        pi.kind = "joint_effort";
        pi.id = ij.name + "/effort";
        pi.robot = robot_index;
        std::vector<std::pair<std::string, std::string>> attributes = {{"kind", pi.kind},
                                                                       {"axis", ij.name}};
        if (ij.effort_limit) attributes.emplace_back("limit", exact_text(*ij.effort_limit));
        pi.params.element = attribute_element("plugin", ij.where.element, std::move(attributes));
        pi.params.file = model.display;
        pi.params.constants = constants;
        pi.where = ij.where;
        scene.plugins.push_back(std::move(pi));
        rb.plugins.push_back(static_cast<int>(scene.plugins.size() - 1));
      } else if (ij.effort_limit) {
        unactuated_effort.push_back(ij.name);
      }
    } else if (ij.damping != 0 || ij.friction != 0 || ij.spring_stiffness != 0) {
      model.warnings.push_back(ij.where.str() + ": joint '" + ij.name + "' (" + type_name(ij.type) +
                               "): damping, friction and spring apply to hinges and sliders "
                               "only; ignored");
    }
    scene.joints.push_back(std::move(j));
    rb.joints.push_back(static_cast<int>(scene.joints.size() - 1));
  }
  add_imported_couplings(scene, model, rb);
  auto joints_text = [](const std::vector<std::string>& names) {
    return "joint '" + names.front() + "'" +
           (names.size() > 1 ? " and " + std::to_string(names.size() - 1) + " more"
                             : std::string());
  };
  if (!unapplied_velocity.empty())
    model.warnings.push_back(model.display + ": velocity limits are not applied (" +
                             joints_text(unapplied_velocity) + ")");
  if (!unactuated_effort.empty())
    model.warnings.push_back(model.display + ": effort limits of joints without an actuator " +
                             "bound nothing (" + joints_text(unactuated_effort) + ")");

  // Moving bodies need a mass, or a massive body beyond them that their joint moves (as the
  // links between joints in series): a massless end link would have no dynamics.
  std::vector<bool> fixed_to_world(scene.bodies.size(), false);
  for (int j : rb.joints) {
    const Joint& joint = scene.joints[static_cast<std::size_t>(j)];
    if (joint.type == JointType::fixed && joint.body2 < 0)
      fixed_to_world[static_cast<std::size_t>(joint.body1)] = true;
  }
  std::vector<bool> moves_mass(n_links, false);  // the link or one beyond it has mass
  for (std::size_t l = 0; l < n_links; ++l) {
    if (!(scene.bodies[static_cast<std::size_t>(body_of[l])].mass_kg > 0)) continue;
    for (int up = static_cast<int>(l); up >= 0 && !moves_mass[static_cast<std::size_t>(up)];) {
      moves_mass[static_cast<std::size_t>(up)] = true;
      const int pj = parent_joint[static_cast<std::size_t>(up)];
      up = pj < 0 ? -1 : model.joints[static_cast<std::size_t>(pj)].parent;
    }
  }
  for (std::size_t l = 0; l < n_links; ++l) {
    if (owner[l] != static_cast<int>(l)) continue;
    const Body& b = scene.bodies[static_cast<std::size_t>(body_of[l])];
    if (fixed_to_world[static_cast<std::size_t>(body_of[l])]) continue;
    const int pj = parent_joint[l];
    const bool free =
        pj < 0 || model.joints[static_cast<std::size_t>(pj)].type == ImportedJointType::floating;
    if (!(b.mass_kg > 0) && (free || !moves_mass[l]))
      throw Error(ErrorKind::scene, model.links[l].where,
                  "link '" + model.links[l].name +
                      "' moves but has no mass (give it an <inertial>, or join it to the world "
                      "or to a massive link with a fixed joint)");
    if (!(b.mass_kg > 0)) continue;  // moves the massive links beyond it
    const auto e = symmetric_eigenvalues(b.inertia_kg_m2);
    if (free && !(e[0] > 0))
      throw Error(ErrorKind::scene, model.links[l].inertia_where,
                  "link '" + model.links[l].name +
                      "' is free and needs an inertia with positive principal moments (" +
                      inertia_text(b.inertia_kg_m2) + ")");
  }
  check_joints_move_inertia(scene, rb);
  for (ImportedSensor& is : model.sensors) {
    Sensor s = std::move(is.sensor);
    const ImportedLink& link = model.links[static_cast<std::size_t>(is.link)];
    s.robot = robot_index;
    s.body = body_of[static_cast<std::size_t>(is.link)];
    // The sensor in its body's frame: body⁻¹ · link · sensor.
    const Body& b = scene.bodies[static_cast<std::size_t>(s.body)];
    s.pose = b.pose.inverse() * link.pose * s.pose;
    for (int other : rb.sensors)
      if (scene.sensors[static_cast<std::size_t>(other)].name == s.name)
        throw Error(ErrorKind::scene, s.where,
                    "a second sensor named '" + s.name + "' in this robot (the first is at " +
                        scene.sensors[static_cast<std::size_t>(other)].where.str() + ")");
    scene.sensors.push_back(std::move(s));
    rb.sensors.push_back(static_cast<int>(scene.sensors.size() - 1));
  }
  for (std::string& w : model.warnings)
    scene.warnings.push_back(std::move(w));
  Vec3 offset = placement.offset_m;
  if (placement.rest_on_floor) {
    bool jointed_to_world = false;
    for (int j : rb.joints)
      jointed_to_world = jointed_to_world || scene.joints[static_cast<std::size_t>(j)].body2 < 0;
    double lowest = std::numeric_limits<double>::infinity();
    for (int b : rb.bodies) {
      const Body& body = scene.bodies[static_cast<std::size_t>(b)];
      for (const Geom& g : body.geoms)
        lowest = std::min(lowest, lowest_point(body.pose * g.pose, g.shape));
    }
    if (!jointed_to_world && std::isfinite(lowest)) offset.z -= lowest;
  }
  place_robot(scene, rb, offset, placement.yaw_deg);
  // The model's static geometry (MJCF's world body) moves with the placement's offset.
  for (Geom g : model.world_geoms) {
    g.pose.position += placement.offset_m;
    scene.obstacles.push_back(std::move(g));
  }
}

}  // namespace s2sim::scene::detail
