/// \file
/// MJCF through MuJoCo's own parser and compiler (libmujoco, docs/models/import.md, "MJCF"):
/// `mj_loadXML`, then the compiled `mjModel` is read, so that defaults, classes, `<include>`,
/// degrees, inertias from geoms and every other compiler rule are MuJoCo's.

#include "scene/import_model.hpp"

#include "scene/attributes.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace s2sim::scene::detail {
namespace {

namespace fs = std::filesystem;

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};

Pose pose_of(const mjtNum* pos, const mjtNum* quat) {
  return Pose{Vec3{pos[0], pos[1], pos[2]}, to_matrix(Quat{quat[0], quat[1], quat[2], quat[3]})};
}

Mat3 transpose(const Mat3& a) {
  Mat3 t;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      t.m[i][j] = a.m[j][i];
  return t;
}

std::string name_of(const mjModel* m, mjtObj type, int id, const char* fallback) {
  const char* n = mj_id2name(m, type, id);
  return n && *n ? std::string(n) : std::string(fallback) + std::to_string(id);
}

/// MuJoCo's joint equalities that are linear, joint1 = polycoef[0] + polycoef[1]·joint2 (in
/// the joints' values from their reference qpos0, S2Sim's axis values), as exact couplings;
/// every other equality warned about.
void read_joint_equalities(const mjModel* m, const std::string& display, ImportedModel& model) {
  int unapplied = 0;
  for (int e = 0; e < m->neq; ++e) {
    const mjtNum* poly = m->eq_data + mjNEQDATA * e;
    const bool linear = poly[2] == 0 && poly[3] == 0 && poly[4] == 0;
    if (m->eq_type[e] != mjEQ_JOINT || m->eq_obj2id[e] < 0 || !linear || !m->eq_active[e]) {
      if (m->eq_type[e] == mjEQ_JOINT)
        model.warnings.push_back(
            display + ": equality '" + name_of(m, mjOBJ_EQUALITY, e, "equality") + "' on joint '" +
            name_of(m, mjOBJ_JOINT, m->eq_obj1id[e], "joint") + "' is not applied (" +
            (m->eq_obj2id[e] < 0 ? "no joint2: the joint held at a constant"
             : !linear           ? "a polycoef beyond the linear term"
                                 : "inactive") +
            "); S2Sim couples joint1 = c0 + c1·joint2 only");
      else
        ++unapplied;
      continue;
    }
    model.couplings.push_back(
        {name_of(m, mjOBJ_JOINT, m->eq_obj1id[e], "joint"),
         name_of(m, mjOBJ_JOINT, m->eq_obj2id[e], "joint"), poly[1], poly[0],
         Location{display, "equality '" + name_of(m, mjOBJ_EQUALITY, e, "equality") + "'",
                  "polycoef"}});
  }
  if (unapplied > 0)
    model.warnings.push_back(display + ": " + std::to_string(unapplied) +
                             " equality constraints (other than joint equalities) are not applied");
}

}  // namespace

ImportedModel read_mjcf(const fs::path& file, const std::string& display,
                        const std::vector<fs::path>& /*search_path*/, Settings* settings) {
  ImportedModel model;
  model.file = file;
  model.display = display;
  char error[1000] = "";
  std::unique_ptr<mjModel, ModelDeleter> owned(
      mj_loadXML(file.string().c_str(), nullptr, error, sizeof error));
  if (!owned) {
    std::string message = error;
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
      message.pop_back();
    for (char& c : message)
      if (c == '\n') c = ' ';
    throw Error(ErrorKind::scene, Location{display, "mujoco", ""}, "MuJoCo: " + message);
  }
  const mjModel* m = owned.get();
  // The model's name is the first of the names (`<mujoco model>`).
  model.name = m->nnames > 0 && m->names[0] ? std::string(m->names) : file.stem().string();
  auto body_at = [&](int b) {
    return Location{display, "body '" + name_of(m, mjOBJ_BODY, b, "body") + "'", ""};
  };
  auto joint_at = [&](int j) {
    return Location{display, "joint '" + name_of(m, mjOBJ_JOINT, j, "joint") + "'", ""};
  };

  const Vec3 gravity{m->opt.gravity[0], m->opt.gravity[1], m->opt.gravity[2]};
  if (norm(gravity - Vec3{0, 0, -kGravity_m_s2}) > 1e-12)
    model.warnings.push_back(display + ": option gravity (" + format_number(gravity.x) + ", " +
                             format_number(gravity.y) + ", " + format_number(gravity.z) +
                             ") is not applied; S2Sim's gravity is 9.81 m/s² down");
  if (settings) {
    settings->physics_step_s = m->opt.timestep;
  } else if (m->opt.timestep != 1e-3) {
    model.warnings.push_back(display + ": option timestep " + format_number(m->opt.timestep) +
                             " s is not applied inside a scene (the scene's step is)");
  }

  // Bodies 1..nbody-1 are links; 0 is the world. Poses from the parent down (parents first).
  std::vector<Pose> world(static_cast<std::size_t>(m->nbody));
  for (int b = 1; b < m->nbody; ++b) {
    const int parent = m->body_parentid[b];
    world[static_cast<std::size_t>(b)] = world[static_cast<std::size_t>(parent)] *
                                         pose_of(m->body_pos + 3 * b, m->body_quat + 4 * b);
    ImportedLink l;
    l.name = name_of(m, mjOBJ_BODY, b, "body");
    l.where = body_at(b);
    l.inertia_where = l.where;
    l.pose = world[static_cast<std::size_t>(b)];
    l.has_inertial = true;
    l.mass_kg = m->body_mass[b];
    const Pose inertial = pose_of(m->body_ipos + 3 * b, m->body_iquat + 4 * b);
    const mjtNum* d = m->body_inertia + 3 * b;
    const Mat3 principal{{{d[0], 0, 0}, {0, d[1], 0}, {0, 0, d[2]}}};
    l.com_m = inertial.position;
    l.inertia_kg_m2 = inertial.rotation * principal * transpose(inertial.rotation);
    model.links.push_back(std::move(l));
  }
  auto link = [](int body) { return body - 1; };  // -1: the world

  for (int g = 0; g < m->ngeom; ++g) {
    // contype = conaffinity = 0: a visual geom (MJCF's usual way of writing them).
    if (m->geom_contype[g] == 0 && m->geom_conaffinity[g] == 0) continue;
    const int b = m->geom_bodyid[g];
    const mjtNum* s = m->geom_size + 3 * g;
    const std::string gname = name_of(m, mjOBJ_GEOM, g, "geom");
    Geom geom;
    geom.id = gname;
    geom.pose = pose_of(m->geom_pos + 3 * g, m->geom_quat + 4 * g);
    geom.where = Location{display, "geom '" + gname + "'", ""};
    const float* rgba =
        m->geom_matid[g] >= 0 ? m->mat_rgba + 4 * m->geom_matid[g] : m->geom_rgba + 4 * g;
    geom.visual.color = Color{rgba[0], rgba[1], rgba[2], rgba[3]};
    // MuJoCo's sliding friction (its default is 1); torsional and rolling are not modelled.
    geom.surface.explicit_surface = true;
    geom.surface.mu = m->geom_friction[3 * g];
    switch (m->geom_type[g]) {
      case mjGEOM_BOX:
        geom.shape.type = ShapeType::box;
        geom.shape.size_m = Vec3{2 * s[0], 2 * s[1], 2 * s[2]};
        break;
      case mjGEOM_SPHERE:
        geom.shape.type = ShapeType::sphere;
        geom.shape.radius_m = s[0];
        break;
      case mjGEOM_CYLINDER:
        geom.shape.type = ShapeType::cylinder;
        geom.shape.radius_m = s[0];
        geom.shape.length_m = 2 * s[1];
        break;
      case mjGEOM_CAPSULE:
        geom.shape.type = ShapeType::cylinder;
        geom.shape.radius_m = s[0];
        geom.shape.length_m = 2 * (s[1] + s[0]);
        model.warnings.push_back(geom.where.str() +
                                 ": a capsule collides as the cylinder around it");
        break;
      case mjGEOM_ELLIPSOID:
        geom.shape.type = ShapeType::box;
        geom.shape.size_m = Vec3{2 * s[0], 2 * s[1], 2 * s[2]};
        model.warnings.push_back(geom.where.str() + ": an ellipsoid collides as its bounding box");
        break;
      case mjGEOM_MESH: {
        const int mesh = m->geom_dataid[g];
        const float* v = m->mesh_vert + 3 * m->mesh_vertadr[mesh];
        std::vector<Vec3> vertices;
        for (int k = 0; k < m->mesh_vertnum[mesh]; ++k)
          vertices.push_back(Vec3{v[3 * k], v[3 * k + 1], v[3 * k + 2]});
        if (vertices.empty()) continue;
        const Geom primitive = geom;
        geom =
            hull_geom(model, vertices, geom.pose, name_of(m, mjOBJ_MESH, mesh, "mesh"), geom.where);
        geom.id = gname;
        geom.visual.color = primitive.visual.color;
        geom.surface = primitive.surface;
        break;
      }
      case mjGEOM_PLANE:
        if (b == 0) {
          const Pose p = geom.pose;
          const bool floor =
              std::abs(p.position.z) < 1e-12 && std::abs(p.rotation.m[2][2] - 1) < 1e-12;
          if (!floor)
            model.warnings.push_back(geom.where.str() +
                                     ": a plane other than the floor z = 0 is not loaded");
          continue;  // the scene's floor
        }
        [[fallthrough]];
      default:
        model.warnings.push_back(geom.where.str() +
                                 ": this geom type is not supported; it does not collide");
        continue;
    }
    if (b == 0) {
      model.world_geoms.push_back(std::move(geom));
    } else {
      model.links[static_cast<std::size_t>(link(b))].geoms.push_back(std::move(geom));
    }
  }

  // Joints: a body with several has them in series, the first at the parent (MuJoCo applies a
  // body's joints in order, each about its axis as the ones before have turned it).
  std::vector<int> actuator_of(static_cast<std::size_t>(m->njnt), -1);
  for (int u = 0; u < m->nu; ++u)
    if (m->actuator_trntype[u] == mjTRN_JOINT)
      actuator_of[static_cast<std::size_t>(m->actuator_trnid[2 * u])] = u;
  auto imported_joint = [&](int b, int j) {
    ImportedJoint ij;
    ij.child = link(b);
    ij.parent = link(m->body_parentid[b]);
    ij.name = name_of(m, mjOBJ_JOINT, j, "joint");
    ij.where = joint_at(j);
    const Pose& frame = world[static_cast<std::size_t>(b)];
    ij.anchor_m = frame * Vec3{m->jnt_pos[3 * j], m->jnt_pos[3 * j + 1], m->jnt_pos[3 * j + 2]};
    ij.axis =
        frame.rotation * Vec3{m->jnt_axis[3 * j], m->jnt_axis[3 * j + 1], m->jnt_axis[3 * j + 2]};
    const int dof = m->jnt_dofadr[j];
    switch (m->jnt_type[j]) {
      case mjJNT_FREE:
        ij.type = ImportedJointType::floating;
        break;
      case mjJNT_BALL:
        ij.type = ImportedJointType::ball;
        break;
      case mjJNT_SLIDE:
        ij.type = ImportedJointType::prismatic;
        break;
      default:
        ij.type = m->jnt_limited[j] ? ImportedJointType::revolute : ImportedJointType::continuous;
        break;
    }
    if (m->jnt_limited[j]) {
      ij.limited = true;
      ij.lower = m->jnt_range[2 * j];
      ij.upper = m->jnt_range[2 * j + 1];
    }
    ij.damping = m->dof_damping[dof];
    ij.friction = m->dof_frictionloss[dof];
    if (m->jnt_type[j] == mjJNT_HINGE || m->jnt_type[j] == mjJNT_SLIDE) {
      ij.spring_stiffness = m->jnt_stiffness[j];
      ij.spring_reference = m->qpos_spring[m->jnt_qposadr[j]];
    }
    if (m->dof_armature[dof] != 0)
      model.warnings.push_back(ij.where.str() + ": armature " +
                               format_number(m->dof_armature[dof]) + " is not applied");
    if (const int u = actuator_of[static_cast<std::size_t>(j)]; u >= 0) {
      ij.actuated = true;
      const double gear = m->actuator_gear[6 * u];
      const bool motor =
          m->actuator_gainprm[mjNGAIN * u] == 1 && m->actuator_biasprm[mjNBIAS * u + 1] == 0 &&
          m->actuator_biasprm[mjNBIAS * u + 2] == 0 && m->actuator_dyntype[u] == mjDYN_NONE;
      const std::string aname = name_of(m, mjOBJ_ACTUATOR, u, "actuator");
      if (!motor)
        model.warnings.push_back(display + ": actuator '" + aname +
                                 "' is not a <motor>: its gains are not applied, the joint gets a "
                                 "torque input");
      double limit = -1;
      if (m->actuator_forcelimited[u]) {
        limit = std::max(std::abs(m->actuator_forcerange[2 * u]),
                         std::abs(m->actuator_forcerange[2 * u + 1]));
      } else if (m->actuator_ctrllimited[u] && motor) {
        limit = std::abs(gear) * std::max(std::abs(m->actuator_ctrlrange[2 * u]),
                                          std::abs(m->actuator_ctrlrange[2 * u + 1]));
      }
      if (limit >= 0) ij.effort_limit = limit;
    }
    return ij;
  };
  for (int b = 1; b < m->nbody; ++b) {
    const int count = m->body_jntnum[b];
    if (count == 0) {
      ImportedJoint ij;
      ij.child = link(b);
      ij.parent = link(m->body_parentid[b]);
      ij.type = ImportedJointType::fixed;  // MuJoCo welds a body without joints to its parent
      ij.name = name_of(m, mjOBJ_BODY, b, "body") + "_weld";
      ij.where = body_at(b);
      model.joints.push_back(std::move(ij));
      continue;
    }
    std::vector<ImportedJoint> series;
    for (int k = 0; k < count; ++k)
      series.push_back(imported_joint(b, m->body_jntadr[b] + k));
    add_joints_in_series(model, std::move(series));
  }
  for (int u = 0; u < m->nu; ++u)
    if (m->actuator_trntype[u] != mjTRN_JOINT)
      model.warnings.push_back(display + ": actuator '" +
                               name_of(m, mjOBJ_ACTUATOR, u, "actuator") +
                               "' does not act on a joint; ignored");
  for (int c = 0; c < m->ncam; ++c) {
    // MuJoCo's camera looks along its -Z with +Y up; S2Sim's camera sensor frame along +X
    // with +Z up. Columns: the sensor's X, Y, Z in the camera frame: -Z, -X, +Y.
    const std::string cname = name_of(m, mjOBJ_CAMERA, c, "camera");
    const Location where{display, "camera '" + cname + "'", ""};
    const int b = m->cam_bodyid[c];
    if (b == 0 || m->cam_mode[c] != mjCAMLIGHT_FIXED) {
      model.warnings.push_back(where.str() +
                               (b == 0 ? ": a camera fixed to the world" : ": a tracking camera") +
                               " is not imported (cameras ride on a body)");
      continue;
    }
    Sensor s;
    s.kind = "camera";
    s.id = s.name = cname;
    s.where = where;
    const Pose cam = pose_of(m->cam_pos + 3 * c, m->cam_quat + 4 * c);
    const Mat3 sensor_in_camera{{{0, -1, 0}, {0, 0, 1}, {-1, 0, 0}}};
    s.pose = Pose{cam.position, cam.rotation * sensor_in_camera};
    Element params;
    params.name = "camera";
    params.path = where.element;
    Element fov;
    fov.name = "fov";
    fov.path = params.path + "/fov";
    fov.attributes = {{"vertical", format_number(m->cam_fovy[c])}};
    params.children.push_back(std::move(fov));
    s.params = ParamSource{std::move(params), display, std::make_shared<const ConstantTable>()};
    model.sensors.push_back({link(b), std::move(s)});
  }
  if (m->nsensor > 0)
    model.warnings.push_back(display + ": " + std::to_string(m->nsensor) +
                             " sensors are not imported");
  read_joint_equalities(m, display, model);
  if (m->ntendon > 0)
    model.warnings.push_back(display + ": " + std::to_string(m->ntendon) +
                             " tendons are not applied");
  return model;
}

}  // namespace s2sim::scene::detail
