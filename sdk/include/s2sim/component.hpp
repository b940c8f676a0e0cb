#pragma once
/// \file
/// The component interface shared by the four plugin kinds (body, actuator, sensor,
/// controller) and the two contexts the kernel hands a component: `ConfigureContext` once at
/// load, `StepContext` on every tick of its schedule.
///
/// A component keeps no mutable state in its own members: it declares state slots with
/// `ConfigureContext::declare_state` and reads and writes them through `StepContext::state`.
/// The kernel owns that memory, so a simulation's whole state is copyable and `reset()` is
/// exact. `update()` must not allocate; it may throw `s2sim::Error` to stop the run.

#include <s2sim/error.hpp>
#include <s2sim/image.hpp>
#include <s2sim/math.hpp>
#include <s2sim/params.hpp>
#include <s2sim/random.hpp>
#include <s2sim/schedule.hpp>
#include <s2sim/sensor.hpp>
#include <s2sim/span.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace s2sim {

/// A rigid body of the scene; index 0 is the world (ground), which never moves.
struct BodyHandle {
  std::int32_t index = -1;
  constexpr bool valid() const { return index >= 0; }
};
/// One degree of freedom of a joint (a Universal joint has two).
struct AxisHandle {
  std::int32_t index = -1;
  constexpr bool valid() const { return index >= 0; }
};
/// A joint of the scene (any type, Fixed and Ball included), for its reaction load.
struct JointHandle {
  std::int32_t index = -1;
  constexpr bool valid() const { return index >= 0; }
};
/// A signal the component publishes (a reading, a motor current...).
struct SignalHandle {
  std::int32_t index = -1;
};
/// An input: a value set from outside (`--set`, a controller, a script, a remote client).
struct InputHandle {
  std::int32_t index = -1;
};
/// A block of `count` doubles of the component's state.
struct StateHandle {
  std::int32_t offset = -1;
  std::int32_t count = 0;
};

/// The four kinds of plugin component. Each kind has its own place in a tick (see `Stage`).
enum class Category : std::uint32_t { body = 1, actuator = 2, sensor = 3, controller = 4 };

/// Where in a tick a component runs. Inside one tick the stages run in this order, then the
/// physics advances by one tick; inside one stage components run in scene order.
enum class Stage : std::uint8_t {
  sense = 0,          ///< sensors sample the state at the start of the tick
  control = 1,        ///< high-level controllers (script, remote, C++), kDefaultControlPeriod_s
  motor_control = 2,  ///< motor controllers (PID), 10 ms by default
  actuate = 3,        ///< actuators and special bodies apply forces for the coming tick
};

/// Material flags of a collision surface (SimTwo's `<metallic/>`, `<ferromagnetic/>`,
/// `<rfidtag/>`), for proximity sensors.
enum MaterialFlag : std::uint32_t {
  material_metallic = 1u << 0,
  material_ferromagnetic = 1u << 1,
  material_rfid_tag = 1u << 2,
  material_canvas = 1u << 3,  ///< a paintable `<canvas>` face (for `pentip`)
};

/// One contact of the last physics step between two bodies.
struct ContactInfo {
  BodyHandle body_a;   ///< a moving body (never the world)
  BodyHandle body_b;   ///< the other body; index 0 for the ground, a wall or an obstacle
  Vec3 point_m;        ///< world frame, on body_a's surface
  Vec3 normal;         ///< world unit vector from body_b toward body_a
  Vec3 force_N;        ///< total force on body_a at point_m (body_b gets the opposite)
  double depth_m = 0;  ///< penetration along the normal
};

/// What a ray cast met first.
struct RayHit {
  bool hit = false;
  double distance_m = 0;       ///< from the ray origin along its unit direction
  Vec3 point_m;                ///< world frame
  Vec3 normal;                 ///< world unit surface normal, facing the ray
  BodyHandle body;             ///< index 0 for the ground, a wall or an obstacle
  std::uint32_t material = 0;  ///< MaterialFlag bits of the surface hit
};

/// What the scene loader resolved for a scene sensor element (`<IRSharp>`, `<ranger2d>`...,
/// robot or world-fixed): see `ConfigureContext::sensor_spec()`.
struct SensorSpec {
  std::string kind;  ///< element name
  BodyHandle body;   ///< the body it is attached to; index 0 for a world-fixed sensor
  Pose pose;         ///< sensor frame in the body frame (world frame for a world-fixed sensor);
                     ///< the beam points along the frame's +X
  SensorBeam beam;
  SensorNoise noise;
  double period_s = kDefaultSensorPeriod_s;  ///< measurement period
  SimTwoSensorFields simtwo;                 ///< what only SimTwo's elements give
};

/// A flat floor polygon of the scene's tracks (simtwo-format.md §7), x/y vertices in order.
struct FloorPolygon {
  std::string tag;
  double z_m = 0;
  std::vector<double> x_m, y_m;
};

/// A painting target of the scene (SimTwo's `<painting_target/>` on a solid, thing or obstacle
/// that has a `<mesh>`): the mesh's triangles as they stand in its body's frame, for a spray
/// gun to paint and a script to query (docs/models/sensors.md, "Spray painting").
struct PaintingTarget {
  std::string id;   ///< the solid's, thing's or obstacle's ID as written
  BodyHandle body;  ///< the body it moves with; index 0 for an obstacle (world frame)
  /// Three vertices per triangle, in the order the mesh file winds them (the front face is
  /// the one they turn anticlockwise on): the file's vertices times the mesh scale, placed as
  /// the viewer draws them (the geom's pose and the mesh offset), in the body frame.
  std::vector<Vec3> vertices_m;
};

/// The primitive of a thing added at run time (SimTwo's `AddThingBox`, `AddThingSphere`,
/// `AddThingCylinder`).
enum class ThingShape : std::uint8_t { box = 0, sphere = 1, cylinder = 2 };

/// A free body to add while running (`StepContext::request_add_thing`,
/// `Simulation::add_thing`). Sizes as SimTwo's `GetThingSize` gives them: a box its edges
/// x, y, z; a sphere its radius in x (y and z ignored); a cylinder its radius in x and its
/// length in z, its axis along the body's Z. Uniform density; the default surface.
struct ThingSpec {
  ThingShape shape = ThingShape::box;
  Vec3 size_m{0.1, 0.1, 0.1};
  double mass_kg = 1;
  Pose pose;                        ///< body frame in the world; added at rest
  double rgb[3] = {0.5, 0.5, 0.5};  ///< 0..1
  /// Held where it is put, like a scene obstacle (SimTwo's `AddOBstacleBox`): it does not
  /// fall nor yield, and is moved only by placing it.
  bool fixed = false;
};

/// A velocity-dependent force on an axis for one tick (StepContext::apply_axis_drive):
/// f(v) = clamp(force − damping·(v − v_tick), min_force, max_force), v_tick the axis velocity
/// the component read.
struct AxisDrive {
  std::int32_t axis = -1;
  double force = 0;    ///< N·m or N, at the velocity read this tick
  double damping = 0;  ///< −df/dv >= 0, N·m·s/rad or N·s/m
  double min_force = 0, max_force = 0;
};

/// A signal's or input's full name and unit (ConfigureContext::signal_names, input_names).
struct NamedUnit {
  std::string name;
  std::string unit;
};

/// Reads any signal of the simulation (a body's pose field, an axis position, an input, a
/// component's published value...) from `update()`: the kernel's reader and the signal's
/// index, resolved once by `ConfigureContext::signal_reader`. Read it with
/// `StepContext::signal(reader)`.
struct SignalReader {
  double (*read)(const void* kernel, std::int32_t index) = nullptr;
  const void* kernel = nullptr;
  std::int32_t index = -1;
};

namespace detail {
/// Raw views of the kernel's per-tick buffers. Filled by the kernel; plugins use them only
/// through `StepContext`. Its layout is part of the plugin ABI.
struct WorldView {
  // Time.
  double time_s = 0;
  std::int64_t tick = 0;
  double tick_s = 0;  ///< length of one tick (the physics step)

  // Bodies, `body_count` of each (the world at index 0).
  std::int32_t body_count = 0;
  const Pose* body_pose = nullptr;       ///< body frame in world
  const Twist* body_twist = nullptr;     ///< world frame
  Wrench* body_wrench = nullptr;         ///< accumulated for the coming tick
  const double* body_mass_kg = nullptr;  ///< as it stands (a mass set while running counts)

  // Axes, `axis_count` of each.
  std::int32_t axis_count = 0;
  const double* axis_position = nullptr;  ///< rad or m
  const double* axis_velocity = nullptr;  ///< rad/s or m/s
  double* axis_force = nullptr;           ///< N·m or N, accumulated for the coming tick
  /// Coulomb friction bound (N·m or N) accumulated for the coming tick; the kernel applies it
  /// implicitly as a brake (stick-slip, no chatter).
  double* axis_friction = nullptr;
  /// Velocity-dependent axis forces for the coming tick, integrated implicitly by the kernel:
  /// `axis_drive_capacity` slots, `*axis_drive_count` used.
  AxisDrive* axis_drives = nullptr;
  std::int32_t* axis_drive_count = nullptr;
  std::int32_t axis_drive_capacity = 0;

  // Joints, `joint_count`: the load body2 exerts on body1 through the joint, world frame,
  // torque about the joint anchor carried by body1, from the last physics step. Zeros until
  // some component looked a joint up with `ConfigureContext::joint()`.
  std::int32_t joint_count = 0;
  const Wrench* joint_reaction = nullptr;

  // Contacts of the last physics step.
  const ContactInfo* contacts = nullptr;
  const std::int32_t* contact_count = nullptr;

  // Inputs, published signals, state (doubles) and random streams (four words per component).
  std::int32_t input_count = 0;
  double* inputs = nullptr;
  // Each input's valid range, bounds included, and its full name (StepContext::set_input).
  const double* input_min = nullptr;
  const double* input_max = nullptr;
  const char* const* input_names = nullptr;
  std::int32_t signal_count = 0;
  double* signals = nullptr;
  std::int32_t state_count = 0;
  double* state = nullptr;
  std::uint64_t* random_state = nullptr;

  // Callbacks into the kernel, each given back its own first argument.
  const void* kernel = nullptr;
  /// Casts a ray against every collision shape except `ignore_body`'s (-1 = none).
  RayHit (*cast_ray)(const void* kernel, const Vec3& origin_m, const Vec3& direction,
                     double max_distance_m, std::int32_t ignore_body) = nullptr;
  /// Re-placements, moves and velocities asked for during the tick, applied after the stage
  /// that asked, before the physics (`StepContext::request_place`, `request_move`,
  /// `request_velocity`).
  const void* placer = nullptr;
  void (*request_place)(const void* placer, std::int32_t body, const Pose& pose) = nullptr;
  void (*request_move)(const void* placer, std::int32_t body, const Pose& pose) = nullptr;
  void (*request_velocity)(const void* placer, std::int32_t body, const Twist& twist) = nullptr;
  /// What components show the people watching (`StepContext::log_line`, `set_hud_text`,
  /// `add_trail_point`...); `what` is a `detail::Annotation`.
  /// Things added and deleted during the tick (`StepContext::request_add_thing`,
  /// `request_delete_thing`), applied with the re-placements. `request_add_thing` returns the
  /// body the thing will be; both throw s2sim::Error for a request they refuse.
  std::int32_t (*request_add_thing)(const void* placer, const ThingSpec& spec, const char* id,
                                    std::size_t id_size) = nullptr;
  void (*request_delete_thing)(const void* placer, std::int32_t body) = nullptr;
  void (*request_delete_obstacle)(const void* placer, std::int32_t obstacle) = nullptr;
  void (*request_resize)(const void* placer, std::int32_t body, const Vec3& size_m) = nullptr;
  void (*request_surface)(const void* placer, std::int32_t body, double mu, double mu2) = nullptr;
  /// `com_m` and `inertia_kg_m2` may be null: kept, and scaled with the mass.
  void (*request_mass)(const void* placer, std::int32_t body, double mass_kg, const Vec3* com_m,
                       const Mat3* inertia_kg_m2) = nullptr;
  const void* annotator = nullptr;
  void (*annotate)(const void* annotator, std::int32_t component, std::int32_t what,
                   std::int32_t id, const char* text, std::size_t text_size,
                   const double* values) = nullptr;

  // Images, `image_count` (ConfigureContext::declare_image).
  std::int32_t image_count = 0;
  Image* images = nullptr;
  /// Draws the scene as it stands into the images given (any may be null), each of the
  /// shot's size: rgb8, float32 depth along the optical axis, uint16 body ids. Throws
  /// s2sim::Error when the simulation has no renderer or it fails.
  const void* renderer = nullptr;
  void (*render_camera)(const void* renderer, const CameraShot& shot, Image* rgb, Image* depth,
                        Image* body_ids) = nullptr;
};

/// The kinds of `WorldView::annotate` calls; new kinds may be added without an ABI change (a
/// kernel ignores a kind it does not know).
enum class Annotation : std::int32_t {
  log_line = 0,     ///< text: one line for the log
  hud_text = 1,     ///< text: the component's HUD text (replaces the previous one)
  trail_point = 2,  ///< id: trail, values: x, y, z in metres (world frame)
  clear_trail = 3,  ///< id: trail
  xy_point = 4,     ///< id: series, values: x, y
  clear_xy = 5,     ///< id: series
  body_color = 6,   ///< id: body, values: red, green, blue in 0..1
  /// id: body (0: the scene's obstacles), values: its geom's index (the obstacle's), red,
  /// green, blue in 0..1
  shape_color = 7,
  sensor_color = 8,  ///< text: the sensor's signal prefix, values: red, green, blue in 0..1
  /// id: the body it burns on (0: the world), values: burning (0 or 1), position x, y, z (in
  /// that body's frame), scale x, y, z
  fire = 9,
  /// id: body, text: the mesh file, a NUL, the shadow mesh file (may be empty), values:
  /// scale, casts shadows (0 or 1)
  body_mesh = 10,
  /// values: height z in metres (world), red, green, blue, opacity in 0..1
  liquid_surface = 11,
};

#if defined(__GNUC__)
#define S2SIM_DETAIL_COLD __attribute__((cold, noinline))
#else
#define S2SIM_DETAIL_COLD
#endif

/// Throws the error of a handle that does not name one of the `count` things of its kind.
/// Formats with snprintf: std::to_string would give every plugin a unique symbol of
/// libstdc++'s, which keeps its library from ever being unloaded.
[[noreturn]] S2SIM_DETAIL_COLD inline void throw_invalid_handle(const char* accessor,
                                                                const char* kind,
                                                                std::int64_t index,
                                                                std::int64_t count) {
  char detail[96];
  if (count > 0)
    std::snprintf(detail, sizeof detail, "index %lld, valid 0 to %lld",
                  static_cast<long long>(index), static_cast<long long>(count - 1));
  else
    std::snprintf(detail, sizeof detail, "index %lld, none exist", static_cast<long long>(index));
  throw Error(ErrorKind::runtime, std::string("StepContext::") + accessor + ": invalid " + kind +
                                      " handle (" + detail +
                                      "): get handles from the ConfigureContext in configure()");
}

/// Throws the error of a value outside an input's valid range, naming the input.
[[noreturn]] S2SIM_DETAIL_COLD inline void throw_input_out_of_range(const char* name, double value,
                                                                    double min, double max) {
  char detail[128];
  std::snprintf(detail, sizeof detail, "%.17g is outside its range [%.17g, %.17g]", value, min,
                max);
  throw Error(ErrorKind::runtime,
              std::string("set_input: input '") + (name ? name : "?") + "': " + detail);
}

/// `index` when 0 <= index < count, else throws naming the accessor: one unsigned compare on
/// the good path.
inline std::int32_t checked(std::int32_t index, std::int32_t count, const char* accessor,
                            const char* kind) {
  if (static_cast<std::uint32_t>(index) >= static_cast<std::uint32_t>(count))
    throw_invalid_handle(accessor, kind, index, count);
  return index;
}
}  // namespace detail

/// What a component sees on each tick of its schedule. Every accessor is inline and reads the
/// kernel's arrays directly: no virtual call, no lookup by name, no allocation. Every handle
/// is checked (one compare): a handle that is default-constructed or out of range throws
/// `s2sim::Error` naming the accessor and the index, which stops the run with the component's
/// name.
class StepContext {
 public:
  StepContext(detail::WorldView* world, std::int32_t component_index, std::int64_t period_ticks)
      : w_(world), component_(component_index), period_ticks_(period_ticks) {}

  // --- time ---

  /// Simulated time at the start of this tick, seconds.
  double time_s() const { return w_->time_s; }
  /// Index of this tick on the grid (time = tick * tick_s).
  std::int64_t tick() const { return w_->tick; }
  /// Length of one physics tick, seconds.
  double tick_s() const { return w_->tick_s; }
  /// The component's period, seconds: the time since its previous update.
  double period_s() const { return static_cast<double>(period_ticks_) * w_->tick_s; }

  // --- bodies ---

  /// Pose of a body frame in the world at the start of the tick.
  const Pose& body_pose(BodyHandle b) const { return w_->body_pose[body(b, "body_pose")]; }
  /// Velocity of a body (world frame) at the start of the tick.
  const Twist& body_twist(BodyHandle b) const { return w_->body_twist[body(b, "body_twist")]; }
  /// Mass of a body, kg, as it stands (0 for the world; `request_mass` changes it).
  double body_mass_kg(BodyHandle b) const { return w_->body_mass_kg[body(b, "body_mass_kg")]; }
  /// Applies `force_N` (world frame) at `point_m` (world frame) for the coming tick.
  void apply_force(BodyHandle b, const Vec3& force_N, const Vec3& point_m) {
    const std::int32_t i = body(b, "apply_force");
    Wrench& wr = w_->body_wrench[i];
    wr.force_N += force_N;
    wr.torque_Nm += cross(point_m - w_->body_pose[i].position, force_N);
  }
  /// Applies a pure torque (world frame) for the coming tick.
  void apply_torque(BodyHandle b, const Vec3& torque_Nm) {
    w_->body_wrench[body(b, "apply_torque")].torque_Nm += torque_Nm;
  }

  // --- axes ---

  /// Joint position of an axis (rad, or m for a slider).
  double axis_position(AxisHandle a) const { return w_->axis_position[axis(a, "axis_position")]; }
  /// Joint velocity of an axis (rad/s, or m/s).
  double axis_velocity(AxisHandle a) const { return w_->axis_velocity[axis(a, "axis_velocity")]; }
  /// Adds a generalised force (N·m, or N) on an axis for the coming tick; positive drives the
  /// axis position up.
  void apply_axis_force(AxisHandle a, double force) {
    w_->axis_force[axis(a, "apply_axis_force")] += force;
  }
  /// Adds Coulomb friction of at most `max_force` (N·m, or N; >= 0) on an axis for the coming
  /// tick. The kernel solves it at velocity level after the other forces: an axis whose load
  /// stays below the bound stands still (true stick, no creep), otherwise it slides against
  /// the full bound.
  void apply_axis_friction(AxisHandle a, double max_force) {
    w_->axis_friction[axis(a, "apply_axis_friction")] += max_force;
  }
  /// Applies a force on an axis for the coming tick that falls as the axis speeds up, as a
  /// motor's back-EMF or a viscous friction does: with v the axis velocity during the tick,
  ///   f(v) = clamp(force − damping·(v − axis_velocity()), min_force, max_force),
  /// `force` being its value at the velocity read now, `damping` = −df/dv >= 0 (N·m·s/rad or
  /// N·s/m), and the bounds a saturation (a motor's current limit). The kernel integrates it
  /// implicitly, (M + h·C)·Δu = h·f, with the bounds as a box: stable and free of
  /// step-to-step ringing at any step and on any inertia, where the same force applied with
  /// `apply_axis_force` rings once h·damping/inertia exceeds 1 and diverges past 2. Several
  /// drives on one axis add up, each within its own bounds. The axis's `torque` signal reports
  /// what was applied (docs/models/multibody.md).
  void apply_axis_drive(AxisHandle a, double force, double damping,
                        double min_force = -std::numeric_limits<double>::infinity(),
                        double max_force = std::numeric_limits<double>::infinity()) {
    const std::int32_t i = axis(a, "apply_axis_drive");
    if (*w_->axis_drive_count < w_->axis_drive_capacity) {
      w_->axis_drives[(*w_->axis_drive_count)++] =
          AxisDrive{i, force, damping, min_force, max_force};
    } else {  // more drives than the kernel reserved: applied explicitly
      w_->axis_force[i] += force < min_force ? min_force : force > max_force ? max_force : force;
    }
  }

  // --- joints ---

  /// The load body2 exerts on body1 through a joint (ODE's body1/body2 of `<connect>`), in
  /// the world frame, the torque about the joint anchor as carried by body1, over the last
  /// physics step: constraint and drive loads together (what an F/T cell in the joint reads).
  /// The joint must have been looked up with `ConfigureContext::joint()`.
  const Wrench& joint_reaction(JointHandle j) const {
    return w_->joint_reaction[detail::checked(j.index, w_->joint_count, "joint_reaction", "joint")];
  }

  // --- contacts and rays ---

  /// Number of contacts found in the last physics step.
  int contact_count() const { return *w_->contact_count; }
  /// A contact of the last physics step, 0 <= i < contact_count().
  const ContactInfo& contact(int i) const {
    return w_->contacts[detail::checked(i, *w_->contact_count, "contact", "contact")];
  }
  /// The first collision surface along a ray from `origin_m` in the unit `direction`, within
  /// `max_distance_m`; the shapes of `ignore` (for example the sensor's own body) are skipped.
  RayHit cast_ray(const Vec3& origin_m, const Vec3& direction, double max_distance_m,
                  BodyHandle ignore = {}) const {
    return w_->cast_ray(w_->kernel, origin_m, direction, max_distance_m, ignore.index);
  }

  // --- images ---

  /// An image as it stands (its last frame); declared by this component or looked up with
  /// `ConfigureContext::image`.
  const Image& image(ImageHandle h) const {
    return w_->images[detail::checked(h.index, w_->image_count, "image", "image")];
  }
  /// Starts a new frame of an image this component writes (one it declared, or an image the
  /// kernel keeps for a writer such as a SimTwo canvas): counts the frame, stamps it with this
  /// tick's time, and returns it to fill in place.
  Image& begin_image(ImageHandle h) {
    Image& image = w_->images[detail::checked(h.index, w_->image_count, "begin_image", "image")];
    ++image.frame;
    image.time_s = w_->time_s;
    return image;
  }
  /// Draws the scene as the other sensors see it this tick, from `shot`, into any of three
  /// images of the shot's size (null: not wanted): rgb8 colour; float32 depth in metres
  /// along the optical axis (+infinity where nothing is within `far_m`); uint16 body ids,
  /// the simulation's body index (0: the world's floor and obstacles, kNoBodyId: the sky).
  /// Throws s2sim::Error when the simulation has no renderer (s2sim-run, s2sim-view and the
  /// Python module give it one) or it fails. Start each image's frame first (begin_image).
  void render_camera(const CameraShot& shot, Image* rgb, Image* depth, Image* body_ids) {
    if (w_->render_camera == nullptr)
      throw Error(ErrorKind::runtime, "StepContext::render_camera: not available here");
    w_->render_camera(w_->renderer, shot, rgb, depth, body_ids);
  }

  // --- moving bodies by hand ---

  /// Asks the kernel to move a body that hangs freely from the world (a thing, or a robot's
  /// root body, which carries its whole robot) to `pose` in the world frame, at rest, once the
  /// current stage has run: SimTwo's `SetRobotPos`, `SetThingPos`. A body jointed to
  /// something else cannot be placed: the kernel then stops with a runtime error naming it.
  /// Does not allocate.
  void request_place(BodyHandle b, const Pose& pose) {
    w_->request_place(w_->placer, body(b, "request_place"), pose);
  }
  /// Asks the kernel to move any body to `pose` (world frame) once the current stage has run,
  /// its speeds kept (SimTwo's `SetSolidPos`, `SetSolidRotationMat`): a thing or a robot's
  /// root body goes exactly there, carrying what is jointed to it; a jointed body goes as
  /// close as its joint allows (its joint coordinates fitted: a hinge keeps only the rotation
  /// about its axis), its children following. Applied after `request_place`; a later request
  /// for the same body replaces an earlier one. Does not allocate.
  void request_move(BodyHandle b, const Pose& pose) {
    w_->request_move(w_->placer, body(b, "request_move"), pose);
  }
  /// Asks the kernel to set a body's velocity (world frame, of the body origin) once the
  /// current stage has run, as closely as its joint allows, the same way (SimTwo's
  /// `SetSolidLinearVel`, `SetSolidAngularVel`); applied after the moves. Does not allocate.
  void request_velocity(BodyHandle b, const Twist& twist) {
    w_->request_velocity(w_->placer, body(b, "request_velocity"), twist);
  }

  // --- things added and deleted while running ---

  /// Adds a free body (SimTwo's `AddThingBox`...) after this stage, before the physics: one
  /// of the spare bodies the scene keeps for that (`<s2sim><runtime_things count>`,
  /// docs/format.md). Returns the body it will be; throws `s2sim::Error` when every spare body
  /// is in use or the spec is not a valid body (non-finite, mass or a size not positive).
  BodyHandle request_add_thing(const ThingSpec& spec, std::string_view id) {
    if (w_->request_add_thing == nullptr)
      throw Error(ErrorKind::runtime, "StepContext::request_add_thing: not available here");
    return BodyHandle{w_->request_add_thing(w_->placer, spec, id.data(), id.size())};
  }
  /// Removes a thing (a scene thing or one added at run time) after this stage: it no longer
  /// moves, touches, is hit by rays nor is drawn, until a reset. Throws for another body.
  void request_delete_thing(BodyHandle b) {
    if (w_->request_delete_thing == nullptr)
      throw Error(ErrorKind::runtime, "StepContext::request_delete_thing: not available here");
    w_->request_delete_thing(w_->placer, body(b, "request_delete_thing"));
  }
  /// Removes the scene's obstacle `index` (in the scene's order; SimTwo's `DeleteObstacle`)
  /// after this stage, until a reset. Throws for an index out of range.
  void request_delete_obstacle(int index) {
    if (w_->request_delete_obstacle == nullptr)
      throw Error(ErrorKind::runtime, "StepContext::request_delete_obstacle: not available here");
    w_->request_delete_obstacle(w_->placer, index);
  }
  /// Resizes a body's own primitive after this stage (SimTwo's `SetSolidSize`: a box its edges,
  /// a cylinder radius x and length z, a sphere radius x), its mass as loaded. Throws for a
  /// size that is not one.
  void request_resize(BodyHandle b, const Vec3& size_m) {
    if (w_->request_resize == nullptr)
      throw Error(ErrorKind::runtime, "StepContext::request_resize: not available here");
    w_->request_resize(w_->placer, body(b, "request_resize"), size_m);
  }
  /// Sets the friction of a body's own primitive after this stage (`SetSolidSurfaceFriction`):
  /// mu >= 0 explicit, mu < 0 the scene's default; mu2 across an anisotropic surface.
  void request_surface(BodyHandle b, double mu, double mu2) {
    if (w_->request_surface == nullptr)
      throw Error(ErrorKind::runtime, "StepContext::request_surface: not available here");
    w_->request_surface(w_->placer, body(b, "request_surface"), mu, mu2);
  }

  /// Gives a body a new mass after this stage (SimTwo's `SetSolidMass`): its inertia scaled by
  /// the mass's ratio, its centre of mass kept; a snapshot holds it, a reset restores the
  /// scene's. Throws for a mass that is not positive or beyond 1e9 kg.
  void request_mass(BodyHandle b, double mass_kg) {
    if (w_->request_mass == nullptr)
      throw Error(ErrorKind::runtime, "StepContext::request_mass: not available here");
    w_->request_mass(w_->placer, body(b, "request_mass"), mass_kg, nullptr, nullptr);
  }
  /// The same with its centre of mass (body frame) and its inertia about it (body axes); throws
  /// for an inertia that is not physical (not symmetric, a negative principal moment, or
  /// moments that violate A + B >= C).
  void request_mass_properties(BodyHandle b, double mass_kg, const Vec3& com_m,
                               const Mat3& inertia_kg_m2) {
    if (w_->request_mass == nullptr)
      throw Error(ErrorKind::runtime, "StepContext::request_mass_properties: not available here");
    w_->request_mass(w_->placer, body(b, "request_mass_properties"), mass_kg, &com_m,
                     &inertia_kg_m2);
  }

  // --- what the people watching see (not part of the simulation's state) ---

  /// Publishes one line of text: the viewer's Log window shows it with the simulated time and
  /// the component's path. A reset forgets it, a snapshot does not hold it; the kernel keeps
  /// the last 1000 lines. Copies the text, so it may allocate: call it on events, not every
  /// tick.
  void log_line(std::string_view text) { annotate(detail::Annotation::log_line, 0, text); }
  /// Sets the component's head-up text, drawn over the 3-D view's top-left corner until set
  /// again; lines separated by '\n', empty to clear it.
  void set_hud_text(std::string_view text) { annotate(detail::Annotation::hud_text, 0, text); }
  /// Appends a world point to the component's trail `trail`, drawn as a polyline in the 3-D
  /// view; the kernel keeps the latest 10 000 points of each trail.
  void add_trail_point(int trail, const Vec3& point_m) {
    const double xyz[3] = {point_m.x, point_m.y, point_m.z};
    annotate(detail::Annotation::trail_point, trail, {}, xyz);
  }
  /// Removes every point of trail `trail`.
  void clear_trail(int trail) { annotate(detail::Annotation::clear_trail, trail, {}); }
  /// Appends a point (x, y) to the component's XY series `series`, which the viewer's chart
  /// can plot; the kernel keeps the latest 10 000 points of each series.
  void add_xy_point(int series, double x, double y) {
    const double xy[2] = {x, y};
    annotate(detail::Annotation::xy_point, series, {}, xy);
  }
  /// Removes every point of XY series `series`.
  void clear_xy_series(int series) { annotate(detail::Annotation::clear_xy, series, {}); }
  /// Paints a body's solid (not its shells) in the 3-D view (SimTwo's `SetSolidColor`): red,
  /// green, blue in 0..1, opaque, until painted again. A reset restores the scene's colours.
  void set_body_color(BodyHandle b, double red, double green, double blue) {
    const double rgb[3] = {red, green, blue};
    annotate(detail::Annotation::body_color, body(b, "set_body_color"), {}, rgb);
  }

  /// Paints one geom of a body (SimTwo's `SetShellColor`: `geom` 1 is its first shell, 0 its
  /// own primitive) or, on body 0, the scene's obstacle `geom` (`SetObstacleColor`), until
  /// painted again or a reset.
  void set_shape_color(BodyHandle b, int geom, double red, double green, double blue) {
    const double values[4] = {static_cast<double>(geom), red, green, blue};
    annotate(detail::Annotation::shape_color, body(b, "set_shape_color"), {}, values);
  }
  /// Paints a scene sensor, named by its signal prefix (`robots/<robot>/sensors/<id>`; SimTwo's
  /// `SetSensorColor`), until painted again or a reset.
  void set_sensor_color(std::string_view sensor, double red, double green, double blue) {
    const double rgb[3] = {red, green, blue};
    annotate(detail::Annotation::sensor_color, 0, sensor, rgb);
  }

  /// The scene's fire effect (SimTwo's `StartFire`, `SetFirePosition`, `SetFireScale`,
  /// `StartSolidFire`): flames drawn at `position_m` in body `on`'s frame (the world's for body
  /// 0), `scale` times their size, while `burning`. One fire per simulation; a reset puts it
  /// out.
  void set_fire(bool burning, BodyHandle on, const Vec3& position_m, const Vec3& scale) {
    const double values[7] = {
        burning ? 1.0 : 0.0, position_m.x, position_m.y, position_m.z, scale.x, scale.y, scale.z};
    annotate(detail::Annotation::fire, body(on, "set_fire"), {}, values);
  }

  /// Draws a body's solid as the triangle mesh in `file` (STL, OBJ, 3DS, PLY... as scenes'
  /// `<mesh>`), its vertices times `scale` in the body frame, in the solid's colour, instead of
  /// its primitive (SimTwo's `MeshThing`); `shadow_file`, when not empty, is a coarser mesh
  /// drawn for its shadow and when it is small on screen. Only the picture changes: collision,
  /// mass and rays keep the primitive. Until set again, the body is taken by another thing
  /// added while running, or a reset. The viewer reads the files: one it cannot read is a
  /// warning in its Log and the primitive stays. Copies the names, so it may allocate. Throws
  /// for an empty file name or a scale that is not finite and positive.
  void set_body_mesh(BodyHandle b, std::string_view file, double scale, bool casts_shadow,
                     std::string_view shadow_file = {}) {
    if (file.empty() || !(scale > 0 && scale < std::numeric_limits<double>::infinity()))
      throw Error(ErrorKind::usage,
                  "StepContext::set_body_mesh: needs a file name and a finite scale > 0");
    std::string text(file);
    text += '\0';
    text.append(shadow_file.data(), shadow_file.size());
    const double values[2] = {scale, casts_shadow ? 1.0 : 0.0};
    annotate(detail::Annotation::body_mesh, body(b, "set_body_mesh"), text, values);
  }

  /// Shows the horizontal surface of a liquid at height `z_m` (world frame), drawn as a
  /// translucent plane over the floor in red, green, blue and `opacity` (0..1), so that a
  /// floating body is seen on its water. One surface per component, until shown again or a
  /// reset (publish it from initialize()); components showing the same height share one plane.
  /// Only the picture: the physics is the component's own. Throws for a z that is not finite.
  void show_liquid_surface(double z_m, double red, double green, double blue, double opacity) {
    if (!(std::abs(z_m) < std::numeric_limits<double>::infinity()))
      throw Error(ErrorKind::usage, "StepContext::show_liquid_surface: z must be finite");
    const double values[5] = {z_m, red, green, blue, opacity};
    annotate(detail::Annotation::liquid_surface, 0, {}, values);
  }

  // --- inputs and signals ---

  /// Current value of an input.
  double input(InputHandle i) const {
    return w_->inputs[detail::checked(i.index, w_->input_count, "input", "input")];
  }
  /// Sets an input (controllers set the references that motor controllers read). Throws
  /// naming the input for a value outside its valid range (ConfigureContext::declare_input;
  /// NaN is outside every range).
  void set_input(InputHandle i, double v) {
    const std::int32_t k = detail::checked(i.index, w_->input_count, "set_input", "input");
    if (!input_accepts_at(k, v))
      detail::throw_input_out_of_range(w_->input_names ? w_->input_names[k] : nullptr, v,
                                       w_->input_min[k], w_->input_max[k]);
    w_->inputs[k] = v;
  }
  /// Whether `v` lies in the input's valid range: what set_input would take (a link to a
  /// program outside drops and counts the rest).
  bool input_accepts(InputHandle i, double v) const {
    return input_accepts_at(detail::checked(i.index, w_->input_count, "input_accepts", "input"), v);
  }
  /// Publishes a signal value; it holds until published again.
  void publish(SignalHandle s, double v) {
    w_->signals[detail::checked(s.index, w_->signal_count, "publish", "signal")] = v;
  }
  /// The current value of a signal a component publishes (found with
  /// `ConfigureContext::published_signal`): how a controller reads a sensor. Sensors run
  /// first in a tick, so a controller sees the readings of the same tick.
  double signal(SignalHandle s) const {
    return w_->signals[detail::checked(s.index, w_->signal_count, "signal", "signal")];
  }
  /// The current value of any signal: kernel signals such as a body's `x` read the state at
  /// the start of this tick, published and input values as they stand now.
  double signal(const SignalReader& r) const {
    if (r.read == nullptr) detail::throw_invalid_handle("signal", "signal reader", r.index, 0);
    return r.read(r.kernel, r.index);
  }

  // --- the component's own state and random stream ---

  /// The component's state block: `h.count` doubles.
  Span<double> state(StateHandle h) {
    if (h.offset < 0 || h.count < 0 || h.offset > w_->state_count - h.count)
      detail::throw_invalid_handle("state", "state", h.offset, w_->state_count);
    return Span<double>(w_->state + h.offset, static_cast<std::size_t>(h.count));
  }
  /// The component's own random stream.
  RandomStream random() { return RandomStream(w_->random_state + 4 * component_); }

 private:
  std::int32_t body(BodyHandle b, const char* accessor) const {
    return detail::checked(b.index, w_->body_count, accessor, "body");
  }
  std::int32_t axis(AxisHandle a, const char* accessor) const {
    return detail::checked(a.index, w_->axis_count, accessor, "axis");
  }
  void annotate(detail::Annotation what, std::int32_t id, std::string_view text,
                const double* values = nullptr) {
    if (w_->annotate != nullptr)
      w_->annotate(w_->annotator, component_, static_cast<std::int32_t>(what), id, text.data(),
                   text.size(), values);
  }

  bool input_accepts_at(std::int32_t k, double v) const {
    return w_->input_min == nullptr || (v >= w_->input_min[k] && v <= w_->input_max[k]);
  }

  detail::WorldView* w_;
  std::int32_t component_;
  std::int64_t period_ticks_;
};

/// What a component sees once, at load: its parameters, the bodies, axes and joints it may
/// use, and the declarations of its signals, inputs, state and schedule. Every lookup throws
/// `s2sim::Error` with the component's location when the name is unknown.
class ConfigureContext {
 public:
  virtual ~ConfigureContext() = default;

  // --- the component and its run ---

  /// The component's XML element.
  virtual const Params& params() const = 0;
  /// Its instance ID as written in the scene.
  virtual std::string_view id() const = 0;
  /// The owning robot's ID, empty for a scene-level component.
  virtual std::string_view robot() const = 0;
  /// Length of one physics tick, seconds.
  virtual double tick_s() const = 0;
  /// The run's seed (SimulationOptions::seed), for a component that seeds a generator it does
  /// not own (a compiled script's RTL random numbers); 1 outside the kernel.
  virtual std::uint64_t seed() const { return 1; }

  // --- bodies ---

  /// A body by name: a solid ID of the owning robot, `world`, or a full path
  /// `robots/<robot>/solids/<solid>` or `things/<thing>`.
  virtual BodyHandle body(std::string_view name) = 0;
  /// Number of bodies, the world (index 0) included.
  virtual int body_count() const = 0;
  /// The scene ID of a body as written (a solid, tyre or thing ID); empty for the world.
  virtual std::string body_id(BodyHandle b) const = 0;
  /// Mass of a body as loaded, kg (0 for the world); StepContext::body_mass_kg reads it as it
  /// stands while running.
  virtual double body_mass_kg(BodyHandle b) const = 0;

  // --- axes ---

  /// An axis by name: a joint ID of the owning robot (`<joint>:2` for a Universal joint's
  /// second axis) or a full path `robots/<robot>/axes/<axis>`.
  virtual AxisHandle axis(std::string_view name) = 0;
  /// Whether the axis is linear (a slider, metres) rather than rotational (radians).
  virtual bool axis_is_linear(AxisHandle a) const = 0;
  /// The signal prefix of an axis, `robots/<robot>/axes/<axis>`.
  virtual std::string axis_prefix(AxisHandle a) const = 0;
  /// Adds `inertia` to the axis's own inertia, as MuJoCo's joint "armature": kg·m² on a
  /// rotational axis, e.g. a motor's rotor inertia reflected through its gear, N²·J_rotor.
  /// Declarations on one axis add up. The kernel carries it on a hinge or Universal axis as a
  /// massless disk on the axis fixed to the joint's child body (axial `inertia`, half of it
  /// across): exact for the spin of the axis while the parent does not turn about it
  /// (docs/models/multibody.md). A slider or a loop-closing axis does not carry it (a
  /// load-time warning says so). Throws for a negative or non-finite value.
  virtual void add_axis_inertia(AxisHandle axis, double inertia) = 0;

  // --- joints ---

  /// A joint by name: a joint ID of the owning robot or a full path
  /// `robots/<robot>/joints/<joint>` (`world/joints/<joint>` for a scene-level joint). Asks the
  /// kernel to compute the joint's reaction load on every physics step, read with
  /// `StepContext::joint_reaction()` (joints nobody looks up cost nothing). A joint that
  /// closes a kinematic loop is realised by constraints: its reaction reads zero and the scene
  /// gets a load-time warning.
  virtual JointHandle joint(std::string_view name) = 0;
  /// A joint's body1 (`which` = 1) or body2 (`which` = 2) as `<connect B1 B2>` gives them;
  /// index 0 for the world.
  virtual BodyHandle joint_body(JointHandle j, int which) const = 0;

  // --- scene sensors and the floor ---

  /// For a component made for a scene sensor element (`<IRSharp>`...): what the loader
  /// resolved (body, pose in the body frame, merged beam, noise, period, SimTwo's tags...),
  /// its beam, noise and period checked by the rules of s2sim/sensor.hpp. nullptr for a
  /// component placed with `<plugin>`. Valid until configure() returns: copy what you need.
  virtual const SensorSpec* sensor_spec() const = 0;
  /// A copy of every floor polygon of the scene's tracks, in scene order.
  virtual std::vector<FloorPolygon> floor_polygons() const = 0;
  /// A copy of every painting target: the scene's things first, then the robots' solids and
  /// shells, then the obstacles, each in scene order (SimTwo's routines number the targets
  /// among its things in this order). The kernel reads each mesh file once, at the first call;
  /// one it cannot read throws naming the file and the element. None outside the kernel.
  virtual std::vector<PaintingTarget> painting_targets() const { return {}; }

  // --- the component's signals and inputs ---

  /// The prefix of its signals: `robots/<robot>/<kind>s/<id>` or `<kind>s/<id>` at scene level.
  virtual std::string_view signal_prefix() const = 0;
  /// Declares a signal `<signal_prefix>/<name>` with its unit ("m", "rad/s", "A", "1"...).
  virtual SignalHandle declare_signal(std::string_view name, std::string_view unit) = 0;
  /// Declares a signal by its full name (for example an axis's `.../current`).
  virtual SignalHandle declare_signal_at(std::string_view full_name, std::string_view unit) = 0;
  /// Declares, or joins when another component declared it already, the input
  /// `<signal_prefix>/<name>`; `initial` is its value at reset. `valid` is the range a value
  /// must lie in (StepContext::set_input, Simulation::set_input, remote links); a side left
  /// unbounded takes the unit's sanity bound (docs/plugins.md, "Input ranges"), and joining
  /// components narrow it to what all of them accept. Throws naming the input when `initial`
  /// lies outside.
  virtual InputHandle declare_input(std::string_view name, std::string_view unit, double initial,
                                    const Range& valid = {}) = 0;
  /// Same with a full name, e.g. `robots/r/axes/left/ref_speed`.
  virtual InputHandle declare_input_at(std::string_view full_name, std::string_view unit,
                                       double initial, const Range& valid = {}) = 0;

  // --- other components' signals and inputs ---
  // A `<plugin>` of category controller is configured after every other component (sensors,
  // other plugins, the drive train), so it sees all of them; scene sensors are configured
  // before `<plugin>` components, in scene order. The name lists serve links to programs
  // outside the simulation (the `remote` and `serial` controllers).

  /// A signal published by a component configured before this one, by its full name (e.g.
  /// `robots/r/sensors/ir0/value`), to read with `StepContext::signal()`. Throws when there is
  /// none.
  virtual SignalHandle published_signal(std::string_view full_name) const = 0;
  /// A reader of any signal by full name. Throws naming close names when unknown.
  virtual SignalReader signal_reader(std::string_view full_name) const = 0;
  /// An input that exists already, by full name, to set with `StepContext::set_input` (unlike
  /// `declare_input_at`, it never creates one). Throws naming close names when unknown.
  virtual InputHandle input(std::string_view full_name) = 0;
  /// Every signal declared so far whose full name matches the glob `pattern` (`*` any run of
  /// characters, `?` one), in declaration order: the kernel's (time, bodies, axes), inputs,
  /// and the published signals of the components configured before this one.
  virtual std::vector<NamedUnit> signal_names(std::string_view pattern) const = 0;
  /// Every input declared so far whose full name matches the glob `pattern`.
  virtual std::vector<NamedUnit> input_names(std::string_view pattern) const = 0;

  // --- images ---

  /// Declares the image `<signal_prefix>/<name>`, `width_px` × `height_px` pixels of `format`,
  /// zero until the first frame. Throws naming the image for a size outside 1..kMaxImageSide_px
  /// or past kMaxImagePixels, or a name declared already.
  virtual ImageHandle declare_image(std::string_view name, int width_px, int height_px,
                                    PixelFormat format) = 0;
  /// An image declared by a component configured before this one, by its full name (e.g.
  /// `robots/r/sensors/cam/rgb`), to read with `StepContext::image`. Throws naming close names
  /// when there is none.
  virtual ImageHandle image(std::string_view full_name) const = 0;

  // --- state and schedule ---

  /// Declares `count` doubles of state set to `initial` at reset.
  virtual StateHandle declare_state(std::string_view name, int count, double initial) = 0;
  /// Runs `update()` in `stage` every `period_s` from `phase_s`; both must be whole multiples
  /// of the tick. Without a call the component runs every tick in its kind's default stage.
  virtual void set_schedule(Stage stage, double period_s, double phase_s = 0.0) = 0;
  /// Declares that `update()` touches nothing but what this context resolved: the bodies,
  /// axes and joints it looked up (`body`, `joint_body`, `axis`, `joint`), the inputs it
  /// declared or looked up, the published signals and signal readers it resolved, and its own
  /// signals, state and random stream; that it casts no ray, requests no place, move or
  /// velocity, publishes no annotation (log line, HUD text, trail, XY point, colour), and
  /// shares no data with other instances (no static variable). It may read the last step's
  /// contacts on the bodies it looked up (with several threads it is given its part's, which
  /// hold all of those, and maybe others). The components that touch one another through
  /// inputs and signals are then grouped with the bodies and axes they touch; with several
  /// threads (SimulationOptions::threads) and every component of the scene local, each group
  /// runs on the thread that steps its bodies, at the same time as the others, with the
  /// serial run's results (docs/scheduling.md, "Components in parts"). A local component that
  /// casts a ray, requests a move or annotates stops the simulation with an error naming it,
  /// at any number of threads. Its parts may then also run ahead of the calling thread and go
  /// back (docs/scheduling.md, "Running ahead"): an `update()` may run again for a tick it ran
  /// already, after its state was restored, so all it carries from tick to tick is in its
  /// declared state, as a snapshot requires of every component.
  virtual void declare_local() {}

  // --- checking the scene's input ---

  /// A load-time warning about the component's input that it tolerates (SimTwo accepts it),
  /// located by the kernel at the component's element and listed with the scene's warnings
  /// (the runner prints them, the viewer's log shows them). For input that would change
  /// physics silently, throw instead.
  virtual void warn(std::string_view message) = 0;
  /// Asks the kernel to refuse the scene, rather than warn, when the component's `<plugin>`
  /// element holds an attribute the component did not read: for a kind whose misspelt
  /// parameter would silently leave a physical default in place (`cD` for `cd`). The error
  /// names the file, the element and the attribute, with the closest names it did read.
  virtual void refuse_unread_attributes() {}
};

/// Base of every plugin component.
class Component {
 public:
  virtual ~Component() = default;
  /// Reads parameters, resolves names to handles, declares what it needs. May throw to refuse
  /// the scene; the message should say which parameter is wrong (Params does this for you).
  virtual void configure(ConfigureContext& ctx) = 0;
  /// Sets the state declared in configure() to its starting values (after `initial`s are
  /// applied). Called before the first tick and at every reset. May throw as update() does.
  virtual void initialize(StepContext& /*ctx*/) {}
  /// One update on a tick of the component's schedule. Must not allocate. May throw
  /// `s2sim::Error` (kind `runtime`) for a condition it cannot go on from, such as an input
  /// set to a value out of its range or a script's run-time error: the kernel stops the run
  /// and reports the error with the component's name and place. A `StepContext` accessor
  /// given an invalid handle throws the same way. Throwing is for failures only (it
  /// allocates).
  virtual void update(StepContext& ctx) = 0;
};

}  // namespace s2sim
