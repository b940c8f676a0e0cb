/// \file
/// URDF through urdfdom (docs/models/import.md, "URDF"). urdfdom reads the model; the file is
/// also read as an element tree, for what urdfdom does not keep (`<transmission>`, the
/// `<s2sim>` extension) and so that every message names the element it is about.

#include "scene/import_model.hpp"

#include "scene/attributes.hpp"
#include "scene/xml.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

namespace s2sim::scene::detail {
namespace {

namespace fs = std::filesystem;

/// urdfdom reports through console_bridge's process-wide handler: captured while it parses.
class CapturedLog final : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR)
      errors += (errors.empty() ? "" : "; ") + text;
  }
  std::string errors;
};

std::mutex& console_mutex() {
  static std::mutex m;
  return m;
}

Pose to_pose(const urdf::Pose& p) {
  const Quat q{p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z};
  return Pose{Vec3{p.position.x, p.position.y, p.position.z}, to_matrix(q)};
}

Mat3 transpose(const Mat3& a) {
  Mat3 t;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      t.m[i][j] = a.m[j][i];
  return t;
}

/// The `name`d child elements of `root` by their `name` attribute.
std::map<std::string, const Element*> by_name(const Element& root, const std::string& name) {
  std::map<std::string, const Element*> out;
  for (const Element& c : root.children)
    if (c.name == name)
      if (const std::string* n = c.attribute("name")) out.emplace(*n, &c);
  return out;
}

/// The k-th child named `name` of `el`, or `el` itself.
const Element& nth_child(const Element& el, const std::string& name, std::size_t k) {
  std::size_t seen = 0;
  for (const Element& c : el.children)
    if (c.name == name && seen++ == k) return c;
  return el;
}

const char* kJointTypes[] = {"revolute", "continuous", "prismatic", "fixed", "floating", "planar"};

}  // namespace

ImportedModel read_urdf(const fs::path& file, const std::string& display,
                        const std::vector<fs::path>& search_path) {
  ImportedModel model;
  model.file = file;
  model.display = display;
  const Element root = read_xml_file(file, display);
  if (root.name != "robot")
    throw Error(ErrorKind::scene, Location{display, root.path, ""},
                "expected a URDF <robot>, found <" + root.name + ">");
  auto at = [&](const Element& el, const std::string& attribute = {}) {
    return Location{display, el.path, attribute};
  };
  // urdfdom says only "unknown joint type" with no name: checked here first, located.
  for (const Element& c : root.children) {
    if (c.name != "joint") continue;
    const std::string* type = c.attribute("type");
    const std::string* name = c.attribute("name");
    const std::string jname = name ? *name : std::string("?");
    if (!type) throw Error(ErrorKind::scene, at(c, "type"), "joint '" + jname + "' has no type");
    bool known = false;
    for (const char* t : kJointTypes)
      known = known || *type == t;
    if (!known)
      throw Error(ErrorKind::scene, at(c, "type"),
                  "joint '" + jname + "': unknown joint type '" + *type +
                      "' (expected revolute, continuous, prismatic, fixed, floating or planar)");
  }

  urdf::ModelInterfaceSharedPtr urdf;
  // What urdfdom said of parts it dropped while it still read the model (a <collision> whose
  // mesh scale is one number, an empty <geometry>): a dropped collision is an error below.
  std::string urdfdom_errors;
  {
    std::ifstream in(file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    const std::lock_guard<std::mutex> lock(console_mutex());
    CapturedLog log;
    console_bridge::OutputHandler* previous = console_bridge::getOutputHandler();
    console_bridge::useOutputHandler(&log);
    try {
      urdf = urdf::parseURDF(text.str());
    } catch (const std::exception& e) {
      log.errors += (log.errors.empty() ? "" : "; ") + std::string(e.what());
    }
    console_bridge::useOutputHandler(previous);
    if (!urdf)
      throw Error(ErrorKind::scene, at(root),
                  "urdfdom cannot read the model: " +
                      (log.errors.empty() ? std::string("(no reason given)") : log.errors));
    urdfdom_errors = log.errors;
  }
  model.name = urdf->getName();

  const auto link_elements = by_name(root, "link");
  const auto joint_elements = by_name(root, "joint");
  auto link_el = [&](const std::string& name) -> const Element& {
    const auto it = link_elements.find(name);
    return it != link_elements.end() ? *it->second : root;
  };
  auto joint_el = [&](const std::string& name) -> const Element& {
    const auto it = joint_elements.find(name);
    return it != joint_elements.end() ? *it->second : root;
  };

  // Links in document order; a root link named `world` is the world (ROS's convention).
  const urdf::LinkConstSharedPtr urdf_root = urdf->getRoot();
  const bool world_root = urdf_root && urdf_root->name == "world";
  std::map<std::string, int> index;
  for (const Element& c : root.children) {
    if (c.name != "link") continue;
    const std::string* name = c.attribute("name");
    if (!name || (world_root && *name == "world") || index.count(*name)) continue;
    index.emplace(*name, static_cast<int>(model.links.size()));
    ImportedLink l;
    l.name = *name;
    l.where = at(c);
    model.links.push_back(std::move(l));
  }

  // Link poses from the root down (each child: parent · joint origin).
  std::vector<std::pair<urdf::LinkConstSharedPtr, Pose>> stack{{urdf_root, Pose{}}};
  while (!stack.empty()) {
    auto [link, pose] = stack.back();
    stack.pop_back();
    if (auto it = index.find(link->name); it != index.end())
      model.links[static_cast<std::size_t>(it->second)].pose = pose;
    for (const urdf::JointSharedPtr& j : link->child_joints) {
      urdf::LinkConstSharedPtr child = urdf->getLink(j->child_link_name);
      if (child) stack.emplace_back(child, pose * to_pose(j->parent_to_joint_origin_transform));
    }
  }

  std::set<std::string> transmitted;
  bool has_transmissions = false;
  std::map<std::string, std::vector<Element>> extensions;
  bool warned_gazebo = false;
  for (const Element& c : root.children) {
    if (c.name == "transmission") {
      has_transmissions = true;
      for (const Element& j : c.children)
        if (j.name == "joint")
          if (const std::string* n = j.attribute("name")) transmitted.insert(*n);
    } else if (c.name == "s2sim") {
      for (const Element& j : c.children) {
        const std::string* n = j.attribute("name");
        if (j.name != "joint" || !n || !joint_elements.count(*n))
          throw Error(ErrorKind::scene, at(j, "name"),
                      "an <s2sim> extension holds <joint name='...'> elements naming joints of "
                      "this robot");
        extensions[*n] = j.children;
      }
    } else if (c.name == "gazebo" && !warned_gazebo) {
      warned_gazebo = true;
      model.warnings.push_back(at(c).str() + ": <gazebo> extension elements are ignored");
    }
  }

  bool dropped_visuals = false;
  for (ImportedLink& l : model.links) {
    const urdf::LinkConstSharedPtr link = urdf->getLink(l.name);
    const Element& el = link_el(l.name);
    auto written = [&](const char* name) {
      return static_cast<std::size_t>(
          std::count_if(el.children.begin(), el.children.end(),
                        [&](const Element& c) { return c.name == name; }));
    };
    if (written("collision") != link->collision_array.size())
      throw Error(ErrorKind::scene, at(el),
                  "link '" + l.name + "': urdfdom could not read " +
                      std::to_string(written("collision") - link->collision_array.size()) +
                      " of its <collision> elements and would drop them: " +
                      (urdfdom_errors.empty() ? std::string("(no reason given)") : urdfdom_errors));
    dropped_visuals = dropped_visuals || written("visual") != link->visual_array.size();
    if (link->inertial) {
      const urdf::Inertial& in = *link->inertial;
      const Element& inertial = nth_child(el, "inertial", 0);
      l.inertia_where = at(nth_child(inertial, "inertia", 0));
      l.has_inertial = true;
      l.mass_kg = in.mass;
      const Pose frame = to_pose(in.origin);
      l.com_m = frame.position;
      const Mat3 principal{
          {{in.ixx, in.ixy, in.ixz}, {in.ixy, in.iyy, in.iyz}, {in.ixz, in.iyz, in.izz}}};
      l.inertia_kg_m2 = frame.rotation * principal * transpose(frame.rotation);
      if (!(in.mass > 0)) l.inertia_where = at(nth_child(inertial, "mass", 0), "value");
    } else {
      l.inertia_where = l.where;
    }
    Color color;
    bool has_color = false;
    for (const urdf::VisualSharedPtr& v : link->visual_array)
      if (v && v->material && !has_color) {
        const urdf::Color& c = v->material->color;
        color = Color{c.r, c.g, c.b, c.a};
        has_color = true;
      }
    for (std::size_t k = 0; k < link->collision_array.size(); ++k) {
      const urdf::CollisionSharedPtr& c = link->collision_array[k];
      if (!c || !c->geometry) continue;
      const Element& cel = nth_child(el, "collision", k);
      const Pose pose = to_pose(c->origin);
      Geom g;
      g.pose = pose;
      g.where = at(cel);
      switch (c->geometry->type) {
        case urdf::Geometry::BOX: {
          const auto& b = static_cast<const urdf::Box&>(*c->geometry);
          g.shape.type = ShapeType::box;
          g.shape.size_m = Vec3{b.dim.x, b.dim.y, b.dim.z};
          break;
        }
        case urdf::Geometry::CYLINDER: {
          const auto& cy = static_cast<const urdf::Cylinder&>(*c->geometry);
          g.shape.type = ShapeType::cylinder;
          g.shape.radius_m = cy.radius;
          g.shape.length_m = cy.length;
          break;
        }
        case urdf::Geometry::SPHERE: {
          g.shape.type = ShapeType::sphere;
          g.shape.radius_m = static_cast<const urdf::Sphere&>(*c->geometry).radius;
          break;
        }
        case urdf::Geometry::MESH: {
          const auto& m = static_cast<const urdf::Mesh&>(*c->geometry);
          const Element& mesh_el = nth_child(nth_child(cel, "geometry", 0), "mesh", 0);
          const Location where = at(mesh_el, "filename");
          const fs::path mesh =
              resolve_model_uri(m.filename, file.parent_path(), search_path, where);
          g = mesh_geom(model, mesh, Vec3{m.scale.x, m.scale.y, m.scale.z}, pose, where);
          break;
        }
      }
      const double extent =
          g.shape.type == ShapeType::box || g.shape.type == ShapeType::convex
              ? std::min({g.shape.size_m.x, g.shape.size_m.y, g.shape.size_m.z})
              : (g.shape.type == ShapeType::cylinder ? std::min(g.shape.radius_m, g.shape.length_m)
                                                     : g.shape.radius_m);
      if (!(extent > 0) || !std::isfinite(extent))
        throw Error(ErrorKind::scene, g.where,
                    "link '" + l.name + "': collision geometry needs positive sizes");
      g.id = l.name;
      if (link->collision_array.size() > 1) g.id.append("/").append(std::to_string(k + 1));
      if (has_color) g.visual.color = color;
      l.geoms.push_back(std::move(g));
    }
    // Visual geometry: drawn instead of the collision geometry; a missing visual mesh is a
    // warning, since it changes no physics.
    for (std::size_t k = 0; k < link->visual_array.size(); ++k) {
      const urdf::VisualSharedPtr& v = link->visual_array[k];
      if (!v || !v->geometry) continue;
      const Element& vel = nth_child(el, "visual", k);
      Geom g;
      g.id = l.name + "/visual";
      g.pose = to_pose(v->origin);
      g.where = at(vel);
      g.visual.color = v->material ? Color{v->material->color.r, v->material->color.g,
                                           v->material->color.b, v->material->color.a}
                                   : (has_color ? color : g.visual.color);
      switch (v->geometry->type) {
        case urdf::Geometry::BOX: {
          const auto& b = static_cast<const urdf::Box&>(*v->geometry);
          g.shape.size_m = Vec3{b.dim.x, b.dim.y, b.dim.z};
          break;
        }
        case urdf::Geometry::CYLINDER: {
          const auto& cy = static_cast<const urdf::Cylinder&>(*v->geometry);
          g.shape.type = ShapeType::cylinder;
          g.shape.radius_m = cy.radius;
          g.shape.length_m = cy.length;
          break;
        }
        case urdf::Geometry::SPHERE:
          g.shape.type = ShapeType::sphere;
          g.shape.radius_m = static_cast<const urdf::Sphere&>(*v->geometry).radius;
          break;
        case urdf::Geometry::MESH: {
          const auto& m = static_cast<const urdf::Mesh&>(*v->geometry);
          const Location where =
              at(nth_child(nth_child(vel, "geometry", 0), "mesh", 0), "filename");
          try {
            g.visual.mesh.file =
                resolve_model_uri(m.filename, file.parent_path(), search_path, where);
          } catch (const Error& e) {
            model.warnings.push_back(std::string(e.what()) + " (a visual mesh: not drawn)");
            continue;
          }
          g.visual.mesh.scale = m.scale.x;
          break;
        }
      }
      l.visuals.push_back(std::move(g));
    }
  }

  if (dropped_visuals)
    model.warnings.push_back(at(root).str() + ": urdfdom dropped visual elements it could not " +
                             "read (they are not drawn): " + urdfdom_errors);
  for (const Element& c : root.children) {
    if (c.name != "joint") continue;
    const std::string* name = c.attribute("name");
    if (!name) continue;
    const urdf::JointConstSharedPtr j = urdf->getJoint(*name);
    if (!j) continue;
    ImportedJoint ij;
    ij.name = *name;
    ij.where = at(joint_el(*name));
    const auto child = index.find(j->child_link_name);
    if (child == index.end())
      throw Error(ErrorKind::scene, ij.where,
                  "joint '" + ij.name + "': the child link cannot be the world");
    ij.child = child->second;
    const auto parent = index.find(j->parent_link_name);
    ij.parent = parent == index.end() ? -1 : parent->second;
    switch (j->type) {
      case urdf::Joint::REVOLUTE:
        ij.type = ImportedJointType::revolute;
        break;
      case urdf::Joint::CONTINUOUS:
        ij.type = ImportedJointType::continuous;
        break;
      case urdf::Joint::PRISMATIC:
        ij.type = ImportedJointType::prismatic;
        break;
      case urdf::Joint::FLOATING:
        ij.type = ImportedJointType::floating;
        break;
      case urdf::Joint::PLANAR:
        ij.type = ImportedJointType::continuous;  // three joints in series, below
        break;
      default:
        ij.type = ImportedJointType::fixed;
        break;
    }
    const Pose& frame = model.links[static_cast<std::size_t>(ij.child)].pose;
    ij.anchor_m = frame.position;
    const Vec3 axis{j->axis.x, j->axis.y, j->axis.z};
    const double len = norm(axis);
    const bool planar = j->type == urdf::Joint::PLANAR;
    const bool moving = ij.type == ImportedJointType::revolute ||
                        ij.type == ImportedJointType::continuous ||
                        ij.type == ImportedJointType::prismatic;
    if (moving && !(len > 1e-12))
      throw Error(ErrorKind::scene, at(nth_child(joint_el(*name), "axis", 0), "xyz"),
                  "joint '" + ij.name + "': the axis is the zero vector");
    if (len > 1e-12) ij.axis = frame.rotation * (axis / len);
    if (j->limits && planar) {
      model.warnings.push_back(ij.where.str() + ": joint '" + ij.name +
                               "': the limits of a planar joint are not applied");
    } else if (j->limits && moving) {
      ij.limited = ij.type != ImportedJointType::continuous;
      ij.lower = j->limits->lower;
      ij.upper = j->limits->upper;
      if (j->limits->effort > 0) ij.effort_limit = j->limits->effort;
      if (j->limits->velocity > 0) ij.velocity_limit = j->limits->velocity;
    }
    if (j->dynamics) {
      ij.damping = j->dynamics->damping;
      ij.friction = j->dynamics->friction;
      if (ij.damping < 0 || ij.friction < 0 || !std::isfinite(ij.damping) ||
          !std::isfinite(ij.friction))
        throw Error(ErrorKind::scene, at(nth_child(joint_el(*name), "dynamics", 0)),
                    "joint '" + ij.name + "': damping and friction must be >= 0, got " +
                        format_number(ij.damping) + " and " + format_number(ij.friction));
    }
    if (j->mimic)  // urdfdom's defaults: multiplier 1, offset 0
      model.couplings.push_back({ij.name, j->mimic->joint_name, j->mimic->multiplier,
                                 j->mimic->offset,
                                 at(nth_child(joint_el(*name), "mimic", 0), "joint")});
    if (j->safety)
      model.warnings.push_back(ij.where.str() + ": joint '" + ij.name +
                               "': <safety_controller> is not applied");
    ij.actuated = moving && (has_transmissions ? transmitted.count(ij.name) > 0
                                               : ij.effort_limit.has_value());
    if (j->mimic) {  // its leader's input moves it
      if (has_transmissions && transmitted.count(ij.name) > 0)
        model.warnings.push_back(ij.where.str() + ": joint '" + ij.name + "' mimics '" +
                                 j->mimic->joint_name +
                                 "': its transmission is not applied (the joint has no effort "
                                 "input of its own)");
      ij.actuated = false;
    }
    if (auto e = extensions.find(ij.name); e != extensions.end()) ij.s2sim_drive = e->second;
    if (planar) {
      add_joints_in_series(model, planar_joints(ij, frame.rotation * Vec3{1, 0, 0}));
      continue;
    }
    model.joints.push_back(std::move(ij));
  }
  return model;
}

}  // namespace s2sim::scene::detail
