/// \file
/// SDF through sdformat (libsdformat 12, docs/models/import.md, "SDF"): a model file, or the
/// first model of a world file. Poses are resolved by sdformat into the model frame; messages
/// name the element by sdformat's XML path and line.

#include "scene/import_model.hpp"

#include "scene/attributes.hpp"
#include "scene/xml.hpp"

#include <sdf/sdf.hh>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>

namespace s2sim::scene::detail {
namespace {

namespace fs = std::filesystem;

Pose to_pose(const ignition::math::Pose3d& p) {
  const auto& q = p.Rot();
  return Pose{Vec3{p.Pos().X(), p.Pos().Y(), p.Pos().Z()},
              to_matrix(Quat{q.W(), q.X(), q.Y(), q.Z()})};
}

Mat3 transpose(const Mat3& a) {
  Mat3 t;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      t.m[i][j] = a.m[j][i];
  return t;
}

/// A located place in an SDF file: the file and line, the element's XML path.
Location sdf_at(const std::string& display, const sdf::ElementPtr& el,
                const std::string& attribute = {}) {
  if (!el) return Location{display, "", attribute};
  std::string file = display;
  if (const auto line = el->LineNumber()) file.append(":").append(std::to_string(*line));
  return Location{file, el->XmlPath(), attribute};
}

[[noreturn]] void fail_with(const std::string& display, const sdf::Errors& errors) {
  const sdf::Error& e = errors.front();
  std::string file = display;
  if (const auto line = e.LineNumber()) file.append(":").append(std::to_string(*line));
  std::string message = e.Message();
  for (std::size_t k = 1; k < errors.size() && k < 4; ++k)
    message += "; " + errors[k].Message();
  throw Error(ErrorKind::scene, Location{file, e.XmlPath().value_or(""), ""},
              "sdformat: " + message);
}

void resolve_or_fail(const std::string& display, const sdf::Errors& errors) {
  if (!errors.empty()) fail_with(display, errors);
}

bool has_descendant(const sdf::ElementPtr& el, const std::string& name) {
  for (sdf::ElementPtr c = el->GetFirstElement(); c; c = c->GetNextElement())
    if (c->GetName() == name || has_descendant(c, name)) return true;
  return false;
}

/// An SDF sensor as S2Sim's kind (docs/models/import.md, "Sensors"): `imu` → imu, `lidar`,
/// `gpu_lidar` (and their older names `ray`, `gpu_ray`) → a ranger2d scanning at once,
/// `contact` → touch, `camera`, `depth_camera`, `rgbd_camera`, `segmentation_camera` → camera;
/// the others are warned about. The pose is in the link's frame.
std::optional<Sensor> imported_sensor(ImportedModel& model, const sdf::Sensor& in,
                                      const std::string& link, const std::string& display) {
  Sensor s;
  s.where = sdf_at(display, in.Element());
  s.id = s.name = in.Name();
  ignition::math::Pose3d pose;
  resolve_or_fail(display, in.SemanticPose().Resolve(pose, link));
  s.pose = to_pose(pose);
  if (in.UpdateRate() > 0) s.period_s = 1.0 / in.UpdateRate();
  if (const SensorRuleBroken broken = check_sensor_period(s.period_s))
    throw Error(ErrorKind::scene, sdf_at(display, in.Element(), "update_rate"), broken.message);
  Element params;
  params.path = s.where.element;
  switch (in.Type()) {
    case sdf::SensorType::IMU:
      s.kind = "imu";
      break;
    case sdf::SensorType::CONTACT:
      s.kind = "touch";
      break;
    case sdf::SensorType::LIDAR:
    case sdf::SensorType::GPU_LIDAR: {
      const sdf::Lidar* lidar = in.LidarSensor();
      if (!lidar) return std::nullopt;
      s.kind = "ranger2d";
      const double lo = lidar->HorizontalScanMinAngle().Radian();
      const double hi = lidar->HorizontalScanMaxAngle().Radian();
      s.beam.length_m = lidar->RangeMax();
      s.beam.angle_rad = hi - lo;
      s.beam.rays = static_cast<int>(
          std::min<unsigned>(lidar->HorizontalScanSamples(), static_cast<unsigned>(kMaxBeamRays)));
      // S2Sim fans the rays about the frame's +X: the frame turned to the scan's middle.
      const double mid = 0.5 * (lo + hi);
      s.pose.rotation =
          s.pose.rotation *
          Mat3{{{std::cos(mid), -std::sin(mid), 0}, {std::sin(mid), std::cos(mid), 0}, {0, 0, 1}}};
      if (const SensorRuleBroken broken = check_beam(s.beam))
        throw Error(ErrorKind::scene, s.where, "lidar '" + s.name + "': " + broken.message);
      if (lidar->VerticalScanSamples() > 1)
        model.warnings.push_back(s.where.str() + ": lidar '" + s.name +
                                 "': only the horizontal scan is imported (a 2-D ranger)");
      if (lidar->RangeMin() > 0)
        model.warnings.push_back(s.where.str() + ": lidar '" + s.name +
                                 "': the minimum range is not applied");
      Element scan;
      scan.name = "scan";
      scan.path = params.path + "/scan";
      scan.attributes = {{"mode", "instant"}};
      params.children.push_back(std::move(scan));
      break;
    }
    case sdf::SensorType::CAMERA:
    case sdf::SensorType::DEPTH_CAMERA:
    case sdf::SensorType::RGBD_CAMERA:
    case sdf::SensorType::SEGMENTATION_CAMERA: {
      // Gazebo's camera looks along its frame's +X with +Z up, as S2Sim's camera sensor does.
      const sdf::Camera* camera = in.CameraSensor();
      if (!camera) return std::nullopt;
      s.kind = "camera";
      const sdf::SensorType type = in.Type();
      auto child = [&](const char* name, std::vector<std::pair<std::string, std::string>> attrs) {
        Element e;
        e.name = name;
        e.path = params.path + "/" + name;
        e.attributes = std::move(attrs);
        params.children.push_back(std::move(e));
      };
      auto number = [](double v) { return format_number(v); };
      child("frame", {{"width", std::to_string(camera->ImageWidth())},
                      {"height", std::to_string(camera->ImageHeight())}});
      child("fov", {{"horizontal", number(camera->HorizontalFov().Degree())}});
      child("clip", {{"near", number(camera->NearClip())}, {"far", number(camera->FarClip())}});
      const bool depth =
          type == sdf::SensorType::DEPTH_CAMERA || type == sdf::SensorType::RGBD_CAMERA;
      child("outputs",
            {{"rgb", type == sdf::SensorType::DEPTH_CAMERA ? "0" : "1"},
             {"depth", depth ? "1" : "0"},
             {"segmentation", type == sdf::SensorType::SEGMENTATION_CAMERA ? "1" : "0"}});
      if (type == sdf::SensorType::SEGMENTATION_CAMERA)
        model.warnings.push_back(s.where.str() + ": camera '" + s.name +
                                 "': segmentation gives body ids (S2Sim's), not Gazebo's labels");
      break;
    }
    default:
      model.warnings.push_back(s.where.str() + ": sensor '" + in.Name() + "' of type '" +
                               in.TypeStr() + "' is not imported");
      return std::nullopt;
  }
  if (has_descendant(in.Element(), "noise"))
    model.warnings.push_back(s.where.str() + ": sensor '" + s.name +
                             "': its <noise> is not imported (S2Sim's noise models differ)");
  params.name = s.kind;
  s.params = ParamSource{std::move(params), display, std::make_shared<const ConstantTable>()};
  return s;
}

/// sdformat converts `<sdf version>` with std::stoi, which throws on text that is not a
/// number: checked first, located.
void check_version(const Element& root, const std::string& display) {
  const std::string* version = root.name == "sdf" ? root.attribute("version") : nullptr;
  if (!version) return;  // sdformat's own error names it
  bool ok = !version->empty() && version->size() <= 8;
  int dots = 0;
  for (std::size_t k = 0; ok && k < version->size(); ++k) {
    const char c = (*version)[k];
    if (c == '.') {
      ok = k > 0 && k + 1 < version->size() && (*version)[k - 1] != '.';
      ++dots;
    } else {
      ok = c >= '0' && c <= '9';
    }
  }
  if (!ok || dots != 1)
    throw Error(ErrorKind::scene, Location{display, "sdf", "version"},
                "'" + *version + "' is not an SDF version (a major and a minor number, 1.9 say)");
}

/// sdformat names neither the joint nor the line of an unknown joint type: checked first on
/// the element tree, located.
void check_joint_types(const Element& el, const std::string& display) {
  static const char* const kTypes[] = {"revolute",  "revolute2", "prismatic",  "ball",   "screw",
                                       "universal", "fixed",     "continuous", "gearbox"};
  if (el.name == "joint")
    if (const std::string* type = el.attribute("type")) {
      bool known = false;
      for (const char* t : kTypes)
        known = known || *type == t;
      const std::string* name = el.attribute("name");
      if (!known)
        throw Error(ErrorKind::scene, Location{display, el.path, "type"},
                    "joint '" + (name ? *name : std::string("?")) + "': unknown joint type '" +
                        *type +
                        "' (SDF's are revolute, revolute2, prismatic, ball, screw, universal, "
                        "fixed, continuous and gearbox)");
    }
  for (const Element& c : el.children)
    check_joint_types(c, display);
}

}  // namespace

ImportedModel read_sdf(const fs::path& file, const std::string& display,
                       const std::vector<fs::path>& search_path) {
  ImportedModel model;
  model.file = file;
  model.display = display;

  const Element tree = read_xml_file(file, display);
  check_version(tree, display);
  check_joint_types(tree, display);
  sdf::ParserConfig config;
  // <include><uri>model://name</uri>: a folder `name` on the model path.
  config.SetFindCallback([&](const std::string& uri) -> std::string {
    std::string name = uri;
    if (name.compare(0, 8, "model://") == 0) name = name.substr(8);
    std::vector<fs::path> roots = search_path;
    for (fs::path up = file.parent_path(); !up.empty() && up != up.parent_path();
         up = up.parent_path())
      roots.push_back(up);
    for (const fs::path& root : roots) {
      std::error_code ec;
      if (fs::exists(root / name, ec)) return (root / name).string();
    }
    return {};
  });
  sdf::Root root;
  try {
    resolve_or_fail(display, root.Load(file.string(), config));
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {  // sdformat's own checks throw on some malformed values
    throw Error(ErrorKind::scene, Location{display, "sdf", ""},
                std::string("sdformat cannot read the file: ") + e.what());
  }
  const sdf::Model* m = root.Model();
  if (!m && root.WorldCount() > 0 && root.WorldByIndex(0)->ModelCount() > 0) {
    const sdf::World* w = root.WorldByIndex(0);
    m = w->ModelByIndex(0);
    if (w->ModelCount() > 1)
      model.warnings.push_back(display + ": the world holds " + std::to_string(w->ModelCount()) +
                               " models; only the first, '" + m->Name() + "', is loaded");
  }
  if (!m) throw Error(ErrorKind::scene, Location{display, "sdf", ""}, "no <model> in the file");
  model.name = m->Name();
  if (m->ModelCount() > 0)
    model.warnings.push_back(sdf_at(display, m->Element()).str() +
                             ": nested models are not loaded");

  std::map<std::string, int> index;
  for (uint64_t i = 0; i < m->LinkCount(); ++i) {
    const sdf::Link* link = m->LinkByIndex(i);
    ImportedLink l;
    l.name = link->Name();
    l.where = sdf_at(display, link->Element());
    ignition::math::Pose3d pose;
    resolve_or_fail(display, link->SemanticPose().Resolve(pose, "__model__"));
    l.pose = to_pose(pose);
    const auto& inertial = link->Inertial();
    l.has_inertial = true;
    sdf::ElementPtr inertial_el =
        link->Element()->HasElement("inertial") ? link->Element()->GetElement("inertial") : nullptr;
    l.inertia_where = inertial_el ? sdf_at(display, inertial_el) : l.where;
    l.mass_kg = inertial.MassMatrix().Mass();
    const Pose frame = to_pose(inertial.Pose());
    const auto d = inertial.MassMatrix().DiagonalMoments();
    const auto o = inertial.MassMatrix().OffDiagonalMoments();  // ixy, ixz, iyz
    const Mat3 in{{{d.X(), o.X(), o.Y()}, {o.X(), d.Y(), o.Z()}, {o.Y(), o.Z(), d.Z()}}};
    l.com_m = frame.position;
    l.inertia_kg_m2 = frame.rotation * in * transpose(frame.rotation);

    Color color;
    bool has_color = false;
    for (uint64_t v = 0; v < link->VisualCount() && !has_color; ++v)
      if (const sdf::Material* mat = link->VisualByIndex(v)->Material()) {
        const auto c = mat->Diffuse();
        color = Color{c.R(), c.G(), c.B(), c.A()};
        has_color = true;
      }
    for (uint64_t c = 0; c < link->CollisionCount(); ++c) {
      const sdf::Collision* col = link->CollisionByIndex(c);
      ignition::math::Pose3d cp;
      resolve_or_fail(display, col->SemanticPose().Resolve(cp, link->Name()));
      Geom g;
      g.pose = to_pose(cp);
      g.where = sdf_at(display, col->Element());
      const sdf::Geometry* geom = col->Geom();
      switch (geom->Type()) {
        case sdf::GeometryType::BOX: {
          const auto s = geom->BoxShape()->Size();
          g.shape.type = ShapeType::box;
          g.shape.size_m = Vec3{s.X(), s.Y(), s.Z()};
          break;
        }
        case sdf::GeometryType::CYLINDER:
          g.shape.type = ShapeType::cylinder;
          g.shape.radius_m = geom->CylinderShape()->Radius();
          g.shape.length_m = geom->CylinderShape()->Length();
          break;
        case sdf::GeometryType::SPHERE:
          g.shape.type = ShapeType::sphere;
          g.shape.radius_m = geom->SphereShape()->Radius();
          break;
        case sdf::GeometryType::MESH: {
          const sdf::Mesh* mesh = geom->MeshShape();
          const Location where = sdf_at(display, mesh->Element(), "uri");
          const fs::path path =
              resolve_model_uri(mesh->Uri(), file.parent_path(), search_path, where);
          const auto s = mesh->Scale();
          g = mesh_geom(model, path, Vec3{s.X(), s.Y(), s.Z()}, g.pose, where);
          break;
        }
        default:
          model.warnings.push_back(g.where.str() + ": collision '" + col->Name() +
                                   "': this geometry type is not supported; it does not collide");
          continue;
      }
      // <surface><friction><ode><mu>, <mu2>: Gazebo's friction, where the file writes it.
      sdf::ElementPtr friction = col->Element();
      for (const char* child : {"surface", "friction", "ode"})
        friction = friction && friction->HasElement(child) ? friction->GetElement(child) : nullptr;
      if (friction && friction->HasElement("mu")) {
        g.surface.explicit_surface = true;
        g.surface.mu = friction->Get<double>("mu");
        if (friction->HasElement("mu2")) g.surface.mu2 = friction->Get<double>("mu2");
        if (!(g.surface.mu >= 0) || !std::isfinite(g.surface.mu))
          throw Error(ErrorKind::scene, sdf_at(display, friction, "mu"),
                      "friction mu must be >= 0, got " + format_number(g.surface.mu));
      }
      g.id = l.name + "/" + col->Name();
      if (has_color) g.visual.color = color;
      l.geoms.push_back(std::move(g));
    }
    for (uint64_t v = 0; v < link->VisualCount(); ++v) {
      const sdf::Visual* visual = link->VisualByIndex(v);
      ignition::math::Pose3d vp;
      resolve_or_fail(display, visual->SemanticPose().Resolve(vp, link->Name()));
      Geom g;
      g.id = l.name + "/" + visual->Name();
      g.pose = to_pose(vp);
      g.where = sdf_at(display, visual->Element());
      if (const sdf::Material* mat = visual->Material()) {
        const auto c = mat->Diffuse();
        g.visual.color = Color{c.R(), c.G(), c.B(), c.A()};
      }
      const sdf::Geometry* geom = visual->Geom();
      switch (geom->Type()) {
        case sdf::GeometryType::BOX: {
          const auto size = geom->BoxShape()->Size();
          g.shape.size_m = Vec3{size.X(), size.Y(), size.Z()};
          break;
        }
        case sdf::GeometryType::CYLINDER:
          g.shape.type = ShapeType::cylinder;
          g.shape.radius_m = geom->CylinderShape()->Radius();
          g.shape.length_m = geom->CylinderShape()->Length();
          break;
        case sdf::GeometryType::SPHERE:
          g.shape.type = ShapeType::sphere;
          g.shape.radius_m = geom->SphereShape()->Radius();
          break;
        case sdf::GeometryType::MESH:
          try {
            g.visual.mesh.file =
                resolve_model_uri(geom->MeshShape()->Uri(), file.parent_path(), search_path,
                                  sdf_at(display, geom->MeshShape()->Element(), "uri"));
          } catch (const Error& e) {
            model.warnings.push_back(std::string(e.what()) + " (a visual mesh: not drawn)");
            continue;
          }
          g.visual.mesh.scale = geom->MeshShape()->Scale().X();
          break;
        default:
          continue;  // not drawn
      }
      l.visuals.push_back(std::move(g));
    }
    for (uint64_t s = 0; s < link->SensorCount(); ++s)
      if (auto sensor = imported_sensor(model, *link->SensorByIndex(s), link->Name(), display))
        model.sensors.push_back({static_cast<int>(model.links.size()), std::move(*sensor)});
    index.emplace(l.name, static_cast<int>(model.links.size()));
    model.links.push_back(std::move(l));
  }

  for (uint64_t i = 0; i < m->JointCount(); ++i) {
    const sdf::Joint* j = m->JointByIndex(i);
    ImportedJoint ij;
    ij.name = j->Name();
    ij.where = sdf_at(display, j->Element());
    std::string child_name, parent_name;
    resolve_or_fail(display, j->ResolveChildLink(child_name));
    resolve_or_fail(display, j->ResolveParentLink(parent_name));
    const auto child = index.find(child_name);
    if (child == index.end())
      throw Error(ErrorKind::scene, ij.where, "joint '" + ij.name + "': no child link");
    ij.child = child->second;
    const auto parent = index.find(parent_name);
    ij.parent = parent == index.end() ? -1 : parent->second;  // "world"
    bool two_axes = false;
    switch (j->Type()) {
      case sdf::JointType::REVOLUTE:
        ij.type = ImportedJointType::revolute;
        break;
      case sdf::JointType::CONTINUOUS:
        ij.type = ImportedJointType::continuous;
        break;
      case sdf::JointType::PRISMATIC:
        ij.type = ImportedJointType::prismatic;
        break;
      case sdf::JointType::FIXED:
        ij.type = ImportedJointType::fixed;
        break;
      case sdf::JointType::BALL:
        ij.type = ImportedJointType::ball;
        break;
      case sdf::JointType::UNIVERSAL:
      case sdf::JointType::REVOLUTE2:
        two_axes = true;
        break;
      default: {
        const std::string text = j->Element()->GetAttribute("type")
                                     ? j->Element()->GetAttribute("type")->GetAsString()
                                     : std::string("?");
        throw Error(ErrorKind::scene, sdf_at(display, j->Element(), "type"),
                    "joint '" + ij.name + "': joint type '" + text +
                        "' is not supported (expected revolute, continuous, prismatic, fixed, "
                        "ball, universal or revolute2)");
      }
    }
    ignition::math::Pose3d jp;
    resolve_or_fail(display, j->SemanticPose().Resolve(jp, "__model__"));
    ij.anchor_m = to_pose(jp).position;
    // One axis's direction, limits and dynamics (SDF's defaults: limits ±1e16, none; effort
    // and velocity -1, none).
    auto read_axis = [&](const sdf::JointAxis& axis, ImportedJoint& to) {
      ignition::math::Vector3d xyz;
      resolve_or_fail(display, axis.ResolveXyz(xyz, "__model__"));
      const Vec3 a{xyz.X(), xyz.Y(), xyz.Z()};
      if (!(norm(a) > 1e-12))
        throw Error(ErrorKind::scene, sdf_at(display, axis.Element()),
                    "joint '" + to.name + "': the axis is the zero vector");
      to.axis = a / norm(a);
      if (to.type == ImportedJointType::revolute || to.type == ImportedJointType::prismatic) {
        to.limited = axis.Lower() > -1e15 || axis.Upper() < 1e15;
        to.lower = axis.Lower() > -1e15 ? axis.Lower() : -std::numeric_limits<double>::infinity();
        to.upper = axis.Upper() < 1e15 ? axis.Upper() : std::numeric_limits<double>::infinity();
      }
      if (axis.Effort() >= 0 && std::isfinite(axis.Effort())) to.effort_limit = axis.Effort();
      if (axis.MaxVelocity() >= 0 && std::isfinite(axis.MaxVelocity()))
        to.velocity_limit = axis.MaxVelocity();
      to.damping = axis.Damping();
      to.friction = axis.Friction();
      to.spring_stiffness = axis.SpringStiffness();
      to.spring_reference = axis.SpringReference();
      if (to.damping < 0 || to.friction < 0 || to.spring_stiffness < 0)
        throw Error(ErrorKind::scene, sdf_at(display, axis.Element()),
                    "joint '" + to.name + "': damping, friction and spring stiffness must be >= 0");
      // SDF has no transmission: a joint with an effort limit gets a bounded torque input.
      to.actuated = to.effort_limit.has_value();
    };
    if (two_axes) {
      // Two hinges in series: the first axis turns with the parent, the second with the child.
      std::vector<ImportedJoint> series(2, ij);
      series[1].name = ij.name + "_axis2";
      for (std::size_t k = 0; k < 2; ++k) {
        const sdf::JointAxis* axis = j->Axis(k);
        if (!axis)
          throw Error(ErrorKind::scene, ij.where,
                      "joint '" + ij.name + "': a " + (k ? "second" : "first") + " <axis" +
                          (k ? "2" : "") + "> is required");
        series[k].type = ImportedJointType::revolute;
        read_axis(*axis, series[k]);
        if (!series[k].limited) series[k].type = ImportedJointType::continuous;
      }
      add_joints_in_series(model, std::move(series));
      continue;
    }
    if (const sdf::JointAxis* axis = j->Axis(0)) read_axis(*axis, ij);
    if (ij.type == ImportedJointType::fixed || ij.type == ImportedJointType::ball)
      ij.actuated = false;
    if (j->Axis(1))
      model.warnings.push_back(ij.where.str() + ": joint '" + ij.name +
                               "': the second axis is not applied");
    model.joints.push_back(std::move(ij));
  }
  return model;
}

}  // namespace s2sim::scene::detail
