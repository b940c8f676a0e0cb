#pragma once
/// \file
/// The scene as plain data: what the loader reads from SimTwo's XML files, validated once,
/// with no Simbody in sight. The model builder turns it into a multibody system; the viewer
/// draws it. Every pose here is in the world frame at load time (robot placement applied)
/// unless the field name says otherwise. Units are SI; angles are radians.

#include <s2sim/error.hpp>
#include <s2sim/math.hpp>
#include <s2sim/schedule.hpp>
#include <s2sim/sensor.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace s2sim::scene {

/// A raw XML element kept for components that read their own parameters.
struct Element {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;  ///< in document order
  std::vector<Element> children;                                ///< in document order
  std::string path;  ///< element path in its file, e.g. `robot/solids/cuboid[2]`
  /// Per attribute, the element path it was written at when that is not `path` (attributes
  /// inherited from a `<default>`); empty when every attribute stands at `path`.
  std::vector<std::string> attribute_paths;

  /// The attribute's raw (trimmed) text, or nullptr.
  const std::string* attribute(std::string_view attr) const {
    for (const auto& [k, v] : attributes)
      if (k == attr) return &v;
    return nullptr;
  }
  /// The first child named `child`, or nullptr.
  const Element* child(std::string_view child_name) const {
    for (const auto& c : children)
      if (c.name == child_name) return &c;
    return nullptr;
  }
};

/// Constants of a `<defines>` scope. Names are case-insensitive.
class ConstantTable {
 public:
  /// `<const>`: defines or overwrites.
  void set(std::string_view name, double value);
  /// `<arg>`: defines only when absent; returns whether it defined.
  bool define_if_absent(std::string_view name, double value);
  std::optional<double> find(std::string_view name) const;
  std::size_t size() const { return entries_.size(); }
  const std::vector<std::pair<std::string, double>>& entries() const { return entries_; }

  /// The names `<defines>` declared in this table and in every table copied from it or into
  /// which it was copied (a scene's scopes share one list): what an outside value (`--define`)
  /// may name. Each as written, with whether it was an `<arg>` (which takes an outside value)
  /// or a `<const>` (which overwrites it).
  struct Declared {
    std::string name;
    bool arg = true;
  };
  /// Records a `<const>` or `<arg>` of `<defines>` (defines.cpp).
  void declare(std::string_view name, bool arg);
  const std::vector<Declared>& declared() const { return *declared_; }

 private:
  std::vector<std::pair<std::string, double>> entries_;  ///< upper-case name, value
  std::shared_ptr<std::vector<Declared>> declared_ = std::make_shared<std::vector<Declared>>();
};

/// An element and the constants in scope where it stands: what a component's Params read.
struct ParamSource {
  Element element;
  std::string file;  ///< relative to the scene folder
  std::shared_ptr<const ConstantTable> constants;
};

/// RGBA, each in 0..1.
struct Color {
  double r = 0.5, g = 0.5, b = 0.5, a = 1.0;
};

/// `convex`: the convex hull of a mesh (URDF, SDF and MJCF collision meshes).
enum class ShapeType { box, cylinder, sphere, convex };

/// A convex polytope in its geom's frame, built once at load (the hull of a mesh's vertices).
struct ConvexHull {
  struct Face {
    Vec3 normal;          ///< unit, outward
    double offset_m = 0;  ///< the face's plane: dot(normal, p) = offset_m; inside is below
  };
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside
  std::vector<Face> faces;                    ///< one per triangle
};

/// A collision shape in its own frame. Cylinders are aligned with local Z.
struct Shape {
  ShapeType type = ShapeType::box;
  Vec3 size_m{1, 1, 1};                    ///< box: full edge lengths; convex: its bounding box
  double radius_m = 0;                     ///< cylinder, sphere
  double length_m = 0;                     ///< cylinder, along local Z
  std::shared_ptr<const ConvexHull> hull;  ///< convex
};

/// SimTwo's `<surface>`. `explicit_surface` is SimTwo's "has surface" (an explicit mu >= 0,
/// an omni/mecanum kind or a `<wheels>` tyre); without it the project's default friction
/// applies.
struct Surface {
  bool explicit_surface = false;
  double mu = -1;
  double mu2 = -1;  ///< -1 when unset
  double softness = 1e-5;
  double bounce = 0;
  double bounce_threshold_m_s = 0;
};

/// Anisotropic friction of a solid (§4.3).
enum class FrictionKind { isotropic, omni, mecanum_left, mecanum_right };

struct Mesh {
  std::filesystem::path file;  ///< absolute, resolved against the scene folder; empty = none
  std::filesystem::path shadow_file;
  double scale = 1;
  Vec3 offset_m;  ///< in the body frame, after scaling
  bool shadow = true;
};

struct Visual {
  Color color;                    ///< alpha from `<transparency alpha>`
  std::filesystem::path texture;  ///< absolute; empty = none
  double texture_scale = 1;
  Mesh mesh;
  bool canvas = false;  ///< a paintable +Z face (cuboids)
  int canvas_width_px = 256;
  int canvas_height_px = 256;
  bool liquid = false;
  bool painting_target = false;
};

struct Material {
  bool metallic = false;
  bool ferromagnetic = false;
  bool rfid_tag = false;
};

/// A `<camera>` shell's optics (§4.7).
struct Camera {
  double focal_length = 50;
  int decimation = 4;
  int width_px = 320;
  int height_px = 240;
};

/// A primitive rigidly attached to a body (the solid's own primitive, a shell) or to the
/// world (an obstacle, in which case `pose` is in the world frame).
struct Geom {
  std::string id;
  Shape shape;
  Pose pose;  ///< geometry frame in its body's frame (world frame for obstacles)
  Surface surface;
  FrictionKind friction = FrictionKind::isotropic;
  Visual visual;
  Material material;
  bool is_shell = false;
  std::optional<Camera> camera;
  Location where;
};

/// The SimTwo element that made a body.
enum class SolidKind { cuboid, cylinder, sphere, belt, propeller, tyre };

struct Drag {
  double coefficient = 0;  ///< quadratic drag Cd
  double stokes = 1e-5;    ///< linear damping per step (SimTwo/ODE meaning, §4.4)
  double roll = 1e-3;      ///< angular damping per step
  bool present = false;    ///< an explicit `<drag>`: only then is the `drag` plugin attached
};

struct Buoyancy {
  double mass_kg = 0;  ///< force = mass * g; negative lifts
  Vec3 point_m;        ///< application point in the body frame
};

/// A rigid body: a robot solid, a `<wheels>` tyre or a thing.
struct Body {
  std::string id;
  SolidKind kind = SolidKind::cuboid;
  int robot = -1;  ///< owning robot, -1 for a thing
  Pose pose;       ///< body frame in the world at load
  double mass_kg = 1;
  Vec3 com_m;  ///< centre of mass in the body frame (moved by massive shells)
  Mat3 inertia_kg_m2 = {{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}};  ///< about the COM, body axes
  std::vector<Geom> geoms;  ///< geoms[0] is the solid's own primitive, then its shells
  /// Geometry drawn instead of `geoms` and never collided (an imported link's visuals);
  /// empty for SimTwo solids.
  std::vector<Geom> visuals;
  Drag drag;
  Buoyancy buoyancy;
  double thrust_coefficient = 0;  ///< propellers
  bool gravity = true;
  Location where;
};

enum class JointType { hinge, slider, universal, ball, fixed };

struct Limits {
  double min = -2 * kPi;  ///< rad (hinge/universal) or m (slider)
  double max = 2 * kPi;
  bool active = false;  ///< whether the stop engages (SimTwo: only inside (-pi, pi) for hinges)
  // When active, a rotational side that SimTwo's ODE would never reach is ±infinity.
};

struct JointDraw {
  double radius_m = -1;  ///< -1 = not drawn
  double height_m = 0.05;
  Color color;
};

/// A joint between two bodies; a body index of -1 is the world.
struct Joint {
  std::string id;
  JointType type = JointType::hinge;
  int robot = -1;
  int body1 = -1;  ///< the joint variable is body1's motion relative to body2 (ODE convention)
  int body2 = -1;
  Vec3 anchor_m;  ///< world
  Vec3 axis1;     ///< unit, world
  Vec3 axis2{0, 0, 1};
  Limits limits1, limits2;
  bool wrap1 = true, wrap2 = true;
  /// The drive-train elements of each axis (`<motor>`, `<gear>`, `<rotor>`, `<encoder>`,
  /// `<controller>`, `<friction>`, `<spring>`; a Universal joint's `motor2`... for its second
  /// axis, renamed `motor`...) as written, SimTwo's inheritance resolved attribute by attribute:
  /// `<default>` for joints and wheels, and axis 2 starting from axis 1's defaults. The kernel
  /// does not read them: the drive-train plugin does, with its defaults
  /// (docs/models/dc-motor.md). Attributes inherited from a `<default>` keep its path.
  ParamSource drive1, drive2;
  JointDraw draw;
  std::string description;
  bool from_wheels = false;  ///< made by the `<wheels>` generator
  Location where;
};

/// Two joint axes held exactly in step (URDF `<mimic>`, MJCF's linear joint equality):
/// q_follower = multiplier · q_leader + offset, in axis values (rad or m; a hinge's unwrapped
/// angle), both joints hinges or sliders of one robot (docs/models/multibody.md).
struct JointCoupling {
  int follower = -1, leader = -1;  ///< joint indices
  double multiplier = 1;
  double offset = 0;  ///< rad or m
  Location where;     ///< the element that asks for it (the follower's `<mimic>`, the equality)
};

/// Sensor beam (§4.11; several `<beam>` elements merge into one), noise and solenoid force:
/// the SDK's types, so that the loader and the sensor plugins share one set of defaults and
/// rules (s2sim/sensor.hpp).
using Beam = SensorBeam;
using Noise = SensorNoise;
using s2sim::SolenoidForce;

/// A robot or world sensor (or tool), parsed; its behaviour is a component's.
struct Sensor {
  std::string kind;  ///< element name: IRSharp, ranger2d, ...
  std::string id;    ///< `<ID>` as written, "" without one (what `GetSensorIndex` compares)
  /// The signal-path name: `id`, or without an ID the sensor's index in its list (robot
  /// sensors: the robot's, `GetSensorVal(R, i)`; scene-level ones: the world's,
  /// `GetGlobalSensorVal(i)`), so ID-less sensors do not collide.
  std::string name;
  int robot = -1;  ///< -1 for a scene-level sensor
  int body = -1;   ///< body it is attached to; -1 = world
  Pose pose;       ///< sensor frame in its body frame (world frame when body = -1); the beam
                   ///< is along the frame's +X (SimTwo's rotation of §9.2 applied)
  bool absolute_coords = false;
  bool is_tool = false;
  Beam beam;
  Noise noise;
  std::vector<std::string> tags;
  double period_s = kDefaultSensorPeriod_s;
  SolenoidForce force;
  Color color;
  ParamSource params;
  Location where;
};

/// An instance of a third-party or first-party kind placed with `<plugin>`.
struct PluginInstance {
  std::string kind;
  std::string id;
  int robot = -1;  ///< -1 for a scene-level instance
  ParamSource params;
  Location where;
};

/// A flat floor polygon with a detection tag (tracks, §7).
struct TrackPolygon {
  std::string tag;
  Color color;
  double z_m = 0;
  std::vector<std::pair<double, double>> vertices;  ///< x, y in order
  Location where;
};

struct Robot {
  std::string id;
  std::string kind;  ///< `<kind value>`, informative
  std::filesystem::path file;
  int main_body = -1;
  std::vector<int> bodies;  ///< solids then tyres, in creation order
  std::vector<int> joints;  ///< in creation order
  std::vector<int> sensors;
  std::vector<int> plugins;
  /// The shells in file order (SimTwo's shell indices): (body, index in its geoms).
  std::vector<std::pair<int, int>> shells;
  /// Placement of §9.3, kept so that a run-time re-placement (SimTwo's `SetRobotPos`) can
  /// start again from the file coordinates: a file point p is at
  /// origin_m + offset_m + Rz(yaw_rad)·(p − origin_m) in the world.
  Vec3 origin_m;       ///< P0: the main body's position in the robot file
  Vec3 offset_m;       ///< scene `<pos>`: the main body ends at origin_m + offset_m
  double yaw_rad = 0;  ///< scene `<rot_deg z>`
  Location where;
};

/// Project settings (§10.1) with S2Sim's own.
/// Whose control semantics a scene's motor controllers and motors follow (docs/format.md §6):
/// SimTwo's PID law (integral and derivative over the physics step) and its 0.5 A-per-step
/// current slew limit, for which SimTwo files' gains are tuned, or S2Sim's textbook discrete
/// PID at the controller period and no slew limit.
enum class ControlSemantics { simtwo, s2sim };

struct Settings {
  double physics_step_s = 1e-3;
  int substeps = 1;                                   ///< physics substeps per tick
  double control_period_s = kDefaultControlPeriod_s;  ///< script / high-level controller period
  double default_friction = 0.95;
  Vec3 wind_m_s;
  /// ODE's ERP: the contact stiffness is erp / (surface softness · 1 ms) (contact_force.cpp,
  /// docs/models/contact.md). ODE's global CFM is kept for reference only: each surface's
  /// softness plays its part.
  double erp = 0.4, cfm = 1e-5;
  bool ir_noise = false;
  /// The fastest speed at which contact pushes apart jointless bodies that overlap deeply
  /// (docs/models/contact.md, "Overlap recovery").
  double contact_recovery_speed_m_s = 0.3;
  /// SimTwo's four invisible wall planes x, y = ±world_wall_distance_m (§4.3 of the spec).
  bool world_walls = true;
  double world_wall_distance_m = 12;
  /// SimTwo's for a SimTwo file (no `<s2sim>` element), S2Sim's once the scene has an
  /// `<s2sim>` element; `<s2sim><control semantics>` says it explicitly.
  ControlSemantics control_semantics = ControlSemantics::simtwo;
  /// Where a SimTwo script's UDP socket listens (its UDP routines, docs/scripting.md):
  /// loopback unless `<s2sim><udp address>` says otherwise; SimTwo's port 9808.
  std::string script_udp_address = "127.0.0.1";
  int script_udp_port = 9808;
  /// Spare bodies kept for things added while running (`<s2sim><runtime_things count>`):
  /// -1 leaves it to the kernel (limits::kDefaultRuntimeThings when the scene's script adds
  /// things, none otherwise).
  int runtime_things = -1;
  std::string source;  ///< which file the values came from ("defaults" when none)
};

/// The project's SimTwo script (`control.pas`), found as SimTwo finds it
/// (docs/scripting.md): `<s2sim><script file>`, else `config_Editor.ini` `[Editor]`
/// `LastProjectName`, else the same key of `SimTwo.ini`, else `control.pas` when it exists.
struct ScriptRef {
  std::filesystem::path file;  ///< absolute
  std::string found_by;        ///< where the name came from, for messages
  /// SimTwo's control block at start is "Script" (`RGControlBlock_ItemIndex` = 1 in
  /// `config_Params.ini`, else `SimTwo.ini`), or the scene names its script with `<s2sim>`.
  bool runs_at_start = false;
};

/// A cell of SimTwo's sheet as `Global.S2Sheet` stores it: 1-based row and column, the text.
struct SheetCell {
  int row = 0, col = 0;
  std::string text;
};

struct Scene {
  std::filesystem::path folder;  ///< absolute
  std::filesystem::path file;    ///< the scene.xml, absolute
  Settings settings;
  std::vector<Robot> robots;
  std::vector<Body> bodies;  ///< robot solids, tyres and things
  std::vector<int> things;   ///< indices into bodies
  /// Indices into bodies of the spare bodies that things added while running take
  /// (`reserve_runtime_things`); they are neither in `things` nor in any robot.
  std::vector<int> runtime_things;
  std::vector<Joint> joints;
  std::vector<JointCoupling> couplings;
  std::vector<Geom> obstacles;  ///< static, poses in world
  std::vector<Sensor> sensors;
  std::vector<TrackPolygon> tracks;
  std::vector<PluginInstance> plugins;
  ConstantTable globals;
  std::optional<ScriptRef> script;    ///< the project's script, if it has one
  std::vector<SheetCell> sheet;       ///< `Global.S2Sheet`'s cells in file order
  std::vector<std::string> warnings;  ///< tolerated oddities (missing files, unknown tags)
};

/// Options of `load_scene`.
struct LoadOptions {
  /// Constants set before `scene.xml` is read, as if they led its `<defines>`.
  std::vector<std::pair<std::string, double>> constants;
  /// Folders searched first for the `package://` and `model://` URIs of URDF, SDF and MJCF
  /// robots (then S2SIM_MODEL_PATH, ROS_PACKAGE_PATH, GZ_SIM_RESOURCE_PATH).
  std::vector<std::filesystem::path> model_path;
};

/// Checks the couplings: both joints hinges or sliders of one robot, a follower other than its
/// leader and coupled once, no cycle of couplings, finite numbers. Throws a scene Error at the
/// coupling's location naming the joints and the value.
void validate_couplings(const Scene& scene);

/// Appends `count` spare bodies for things added while running (Scene::runtime_things): each
/// a free, weightless small sphere, parked apart below the world until a thing takes it.
void reserve_runtime_things(Scene& scene, int count);
/// Where spare body `k` waits: out of the world, apart from the others.
Pose runtime_thing_park_pose(int k);

/// Loads a SimTwo scene: `path` is a scene folder or its `scene.xml`; or a robot file in URDF
/// (`.urdf`), SDF (`.sdf`) or MJCF (an `.xml` whose root is `<mujoco>`), run on the default
/// floor (docs/models/import.md). Throws `s2sim::Error` (kind scene) naming file, element and
/// attribute.
Scene load_scene(const std::filesystem::path& path, const LoadOptions& options = {});

}  // namespace s2sim::scene
