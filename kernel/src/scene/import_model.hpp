#pragma once
/// \file
/// Robots from URDF, SDF and MJCF (docs/models/import.md): each format's reader fills one
/// `ImportedModel` (links, joints, geoms in the formats' shared vocabulary, every value with
/// its location), and `add_imported_robot` turns it into the scene's ordinary bodies, joints,
/// drive-train elements and plugin instances, with the checks every format shares (physical
/// inertias, massless moving links, limits).

#include <s2sim/kernel/scene.hpp>

#include "scene/loading.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace s2sim::scene::detail {

/// A link: a rigid body of the format, its frame in the model frame.
struct ImportedLink {
  std::string name;
  Pose pose;  ///< link frame in the model frame
  double mass_kg = 0;
  Vec3 com_m;                                                ///< in the link frame
  Mat3 inertia_kg_m2 = {{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}};  ///< about the COM, link axes
  bool has_inertial = false;
  std::vector<Geom> geoms;    ///< collision, poses in the link frame
  std::vector<Geom> visuals;  ///< drawn only, poses in the link frame
  Location where;             ///< the link element
  Location inertia_where;     ///< the element holding the inertia values
};

enum class ImportedJointType { revolute, continuous, prismatic, fixed, floating, ball };

struct ImportedJoint {
  std::string name;
  ImportedJointType type = ImportedJointType::fixed;
  int parent = -1;  ///< link index, -1 = the world
  int child = -1;
  Vec3 anchor_m;       ///< model frame
  Vec3 axis{1, 0, 0};  ///< unit, model frame
  bool limited = false;
  double lower = 0, upper = 0;  ///< rad or m
  double damping = 0;           ///< N·m·s/rad (N·s/m)
  double friction = 0;          ///< N·m (N), Coulomb
  double spring_stiffness = 0, spring_reference = 0;
  std::optional<double> effort_limit;    ///< N·m (N)
  std::optional<double> velocity_limit;  ///< rad/s (m/s)
  bool actuated = false;  ///< a transmission or actuator drives it: it gets a torque input
  /// Drive-train elements of an `<s2sim>` extension (`motor`, `gear`, `controller`, ...),
  /// replacing the imported ones of the same name.
  std::vector<Element> s2sim_drive;
  Location where;
};

/// One joint following another, by name (URDF `<mimic>`, MJCF's linear joint equality):
/// follower = multiplier · leader + offset, resolved to scene joints by add_imported_robot.
struct ImportedCoupling {
  std::string follower, leader;
  double multiplier = 1, offset = 0;
  Location where;
};

/// A sensor of the format, already in S2Sim's terms; `sensor.pose` in its link's frame.
struct ImportedSensor {
  int link = -1;
  Sensor sensor;
};

struct ImportedModel {
  std::string name;
  std::filesystem::path file;  ///< absolute
  std::string display;         ///< how messages name the file
  std::vector<ImportedLink> links;
  std::vector<ImportedJoint> joints;
  std::vector<Geom> world_geoms;  ///< static geometry, poses in the model frame
  std::vector<ImportedSensor> sensors;
  std::vector<ImportedCoupling> couplings;
  std::vector<std::string> warnings;  ///< already located
};

/// Where `package://` and `model://` URIs are looked for: the load options' folders, then
/// S2SIM_MODEL_PATH, ROS_PACKAGE_PATH and GZ_SIM_RESOURCE_PATH (and Gazebo's older
/// IGN_GAZEBO_RESOURCE_PATH, GAZEBO_MODEL_PATH), colon-separated, in that order.
std::vector<std::filesystem::path> model_search_path(
    const std::vector<std::filesystem::path>& extra);

/// A mesh or include URI as written (`package://pkg/m.stl`, `model://m/x.dae`, `file://`,
/// a relative or absolute path) resolved to an existing file; relative paths are relative to
/// `base_dir` (the folder of the file that names it). A URI that names no existing file is an
/// error at `where` naming the URI and, for `package://` and `model://`, every folder searched.
std::filesystem::path resolve_model_uri(const std::string& uri,
                                        const std::filesystem::path& base_dir,
                                        const std::vector<std::filesystem::path>& search_path,
                                        const Location& where);

/// A mesh collision geom: the convex hull of its vertices (scaled), drawn as the mesh; the geom
/// frame is `pose` moved to the centre of the mesh's bounding box. A mesh that cannot be read
/// is an error at `where`; one without a hull (flat) collides as its bounding box, warned.
Geom mesh_geom(ImportedModel& model, const std::filesystem::path& file, const Vec3& scale,
               const Pose& pose, const Location& where);
/// The same for vertices already read (`vertices` in the mesh frame at `pose`).
Geom hull_geom(ImportedModel& model, const std::vector<Vec3>& vertices, const Pose& pose,
               const std::string& mesh_name, const Location& where);

/// Adds `joints` (each with the same `parent` and `child` links, the first at the parent) to the
/// model in series: each but the last ends at a new massless link at the child's frame, named
/// `<child>.<joint>`; a name the model already has gets `_2`, `_3`... MJCF's several joints in
/// one body, URDF's planar joint and SDF's two-axis joints are made this way.
void add_joints_in_series(ImportedModel& model, std::vector<ImportedJoint> joints);

/// URDF's planar joint as three (`<name>_x`, `<name>_y` sliding in the plane normal to
/// `planar.axis`, `<name>_rot` turning about it), to add in series: x is `in_plane_x` (the
/// joint frame's x) made normal to the axis.
std::vector<ImportedJoint> planar_joints(const ImportedJoint& planar, const Vec3& in_plane_x);

/// Adds the model to the scene as one robot, placed by `placement` (§8 of the format page).
/// Links joined by fixed joints are merged into one body (the child's mass, inertia and
/// geoms joined to the parent's by the parallel-axis theorem); a floating joint, or a root
/// link joined to nothing, leaves a free body.
void add_imported_robot(LoadContext& ctx, ImportedModel model, const RobotPlacement& placement);

/// The readers: each returns the model in its own frame. `search_path` resolves URIs.
ImportedModel read_urdf(const std::filesystem::path& file, const std::string& display,
                        const std::vector<std::filesystem::path>& search_path);
ImportedModel read_sdf(const std::filesystem::path& file, const std::string& display,
                       const std::vector<std::filesystem::path>& search_path);
ImportedModel read_mjcf(const std::filesystem::path& file, const std::string& display,
                        const std::vector<std::filesystem::path>& search_path, Settings* settings);

/// Which robot format a file is, from its extension and, for `.xml`, its root element:
/// `<mujoco>` is MJCF, `<robot>` with `<link>` children URDF, `<sdf>` SDF; empty for a SimTwo
/// file (or anything else).
std::string robot_format(const std::filesystem::path& file);

/// A lone URDF, SDF or MJCF file as a scene: the robot on the default floor, S2Sim's control
/// semantics, the format's own time step (MJCF) or the default one.
Scene load_robot_scene(const std::filesystem::path& file, const std::string& format,
                       const LoadOptions& options);

/// Reads a URDF, SDF or MJCF file (format from `robot_format`) and adds it as one robot.
void load_imported_robot(LoadContext& ctx, const std::filesystem::path& file,
                         const std::string& format, const RobotPlacement& placement);

}  // namespace s2sim::scene::detail
