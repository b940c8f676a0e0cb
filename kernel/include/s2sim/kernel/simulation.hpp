#pragma once
/// \file
/// The façade: everything the runner, the viewer, the tests and the benchmarks use to load a
/// scene, step it and read it. No Simbody type appears here.

#include <s2sim/component.hpp>
#include <s2sim/kernel/annotations.hpp>
#include <s2sim/kernel/camera_renderer.hpp>
#include <s2sim/kernel/scene.hpp>
#include <s2sim/math.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace s2sim {

/// Whether the project's SimTwo script (`control.pas`) runs (docs/scripting.md).
enum class ScriptMode {
  off,            ///< physics only (the library's default: tests and benchmarks)
  control_block,  ///< as SimTwo starts: when its control block is "Script" (the runner's default)
  always,         ///< whenever the project has a script, as SimTwo's Run
};

/// How to load a simulation. Unset optionals keep the scene's settings.
struct SimulationOptions {
  std::uint64_t seed = 1;  ///< seeds every component's random stream
  std::optional<double> physics_step_s;
  std::optional<int> substeps;
  /// Threads stepping the physics (docs/scheduling.md, "Parallel islands"): the scene's
  /// islands (robots and mechanisms not jointed to each other) are dealt into this many
  /// Simbody systems stepped at once, each with its own contact and, when every component is
  /// local, its own components ("Components in parts"). From 1 (one system, the default)
  /// to the machine's hardware threads (else s2sim::Error, usage). The results do not depend
  /// on it, bit for bit; a snapshot restores only with the same number of parts.
  int threads = 1;
  /// Simbody's realize chain for every system, also where the small-tree fast path would
  /// compute the same dynamics without it (docs/models/multibody.md, "Small-tree fast path"):
  /// for comparing the two. The results differ only by rounding.
  bool simbody_dynamics_only = false;
  /// The dynamics check (docs/models/multibody.md, "Dynamics check"): the small-tree dynamics
  /// step, and at every substep Simbody's realize chain computes the same accelerations from
  /// the same state and loads; a relative difference beyond the agreement
  /// (Simulation::DynamicsCheck::agreement) stops the run with an s2sim::Error (runtime)
  /// naming the body. The results are the unchecked run's, bit for bit;
  /// it costs Simbody's realize per substep. Ignored with simbody_dynamics_only.
  bool check_dynamics = false;
  /// The dynamics check's agreement, relative to the largest acceleration (unset: 1e-9, the
  /// check at load's).
  std::optional<double> dynamics_agreement;
  /// Plugin folders searched first, before the default ones (S2SIM_PLUGIN_PATH, then the
  /// plugin folder of the kernel's own prefix: docs/plugins.md). When two libraries provide
  /// one kind, the first on the path wins (a load warning names both).
  std::vector<std::filesystem::path> plugin_path;
  /// false: search `plugin_path` only.
  bool default_plugin_path = true;
  /// Folders searched first for the `package://` and `model://` URIs of URDF, SDF and MJCF
  /// robots, before S2SIM_MODEL_PATH, ROS_PACKAGE_PATH and GZ_SIM_RESOURCE_PATH
  /// (docs/models/import.md).
  std::vector<std::filesystem::path> model_path;
  /// Constants defined before scene.xml is read (as `--define`).
  std::vector<std::pair<std::string, double>> constants;
  /// The project's script: when it runs, and a file to use instead of the one the project
  /// names (relative to the scene folder or absolute; runs whatever `script_mode` says unless
  /// that is `off`). The script is compiled into the `pascal_script` controller plugin.
  ScriptMode script_mode = ScriptMode::off;
  std::optional<std::filesystem::path> script_file;
  /// Sheet cells set before the start, over `Global.S2Sheet`'s (the runner's --sheet): each
  /// becomes an input `sheet/<cell>` even when the file lacks it.
  std::vector<scene::SheetCell> sheet_cells;
  /// With several threads, lets step(n) run the parts ahead of each other over stretches of
  /// ticks (docs/scheduling.md, "Running ahead"; Simulation::run_ahead_counts()). The results
  /// are the same either way, bit for bit; false steps the parts tick by tick (for comparing,
  /// or for a local component that keeps state outside its declared state).
  bool run_ahead = true;
  /// Spare bodies for things added while running (add_thing; docs/format.md, "Things added
  /// while running"), over the scene's `<s2sim><runtime_things count>`. Unset: the scene's,
  /// else 32 when the script that runs adds things, else none.
  std::optional<int> runtime_things;
};

/// A thing of the scene or one added while running, as it stands (Simulation::things).
struct ThingView {
  int body = 0;          ///< kernel body index
  bool added = false;    ///< a spare body that a thing added while running holds or held
  bool present = false;  ///< false: deleted, or a spare body no thing holds
  std::string id;        ///< the scene's ID, or the one given to add_thing
  ThingSpec spec;        ///< what add_thing was given (an added thing only)
};

/// A named value with its unit, e.g. `robots/r/axes/left/speed` in `rad/s`.
struct SignalInfo {
  std::string name;
  std::string unit;
};

/// A loaded scene ready to step. Time advances on an integer tick grid (one tick = one physics
/// step); in each tick sensors sample, controllers run, motor controllers run, actuators
/// apply their loads, then the physics advances (docs/scheduling.md).
class Simulation {
 public:
  /// Loads `scene_path` (a folder or its scene.xml), builds the model, loads the plugins the
  /// scene names and configures every component. Throws s2sim::Error: kind scene for bad
  /// scene input, kind plugin for a plugin that cannot be loaded or refuses its parameters.
  static std::unique_ptr<Simulation> load(const std::filesystem::path& scene_path,
                                          const SimulationOptions& options = {});
  ~Simulation();

  const scene::Scene& scene() const;
  /// Loader and model warnings (missing files, inert sensors...).
  const std::vector<std::string>& warnings() const;

  double time_s() const;
  std::int64_t tick() const;
  double tick_s() const;

  /// Advances `ticks` ticks: bit for bit as `ticks` calls of step(1). With several threads
  /// and the components in the parts, the parts may step stretches of them each alone
  /// (run_ahead_counts()).
  void step(std::int64_t ticks = 1);
  /// Steps until time_s() >= t (rounded to the nearest tick).
  void run_until(double t_s);
  /// Per-stage timing of the tick pipeline (sense, control, motor control, actuate, then per
  /// substep collide, forces, accelerations, kick, axes, drift, project; finish), for
  /// profiling (`s2sim-bench --profile`). Off by default; turning it on starts from zero.
  void set_profiling(bool on);
  struct StageTime {
    std::string stage;
    double seconds = 0;      ///< wall time accumulated since profiling was turned on
    std::int64_t calls = 0;  ///< times the stage ran
  };
  /// Empty while profiling is off.
  std::vector<StageTime> stage_times() const;
  /// Why the components' updates run on the calling thread, stage by stage, rather than each
  /// in the part of the scene it touches, on that part's thread (docs/scheduling.md,
  /// "Components in parts"; SimulationOptions::threads > 1 and every component local,
  /// ConfigureContext::declare_local); empty when they run in the parts.
  const std::string& components_serial_reason() const;
  /// Running ahead (docs/scheduling.md, "Running ahead"): when the components run in the
  /// parts and the parts' shapes are apart, step() lets each part step a stretch of ticks on
  /// its own thread, and goes back to the stretch's start when two parts come close.
  struct RunAheadCounts {
    std::int64_t stretches = 0;  ///< stretches run ahead and kept
    std::int64_t ticks = 0;      ///< the ticks they held
    std::int64_t lost = 0;       ///< stretches gone back (run again tick by tick)
  };
  RunAheadCounts run_ahead_counts() const;
  /// The dynamics that step the scene: "tree" (the small-tree dynamics), "simbody" (Simbody's
  /// realize chain: SimulationOptions::simbody_dynamics_only, or a system the tree cannot
  /// take), "checked" (SimulationOptions::check_dynamics) or "loose" (no body has a joint:
  /// every one is integrated on its own).
  std::string dynamics() const;
  /// What the dynamics check compared so far (SimulationOptions::check_dynamics; zeros
  /// otherwise): accelerations compared, the largest relative difference and when.
  struct DynamicsCheck {
    std::int64_t compared = 0;
    double worst_relative = 0;
    double worst_time_s = 0;
    double agreement = 0;  ///< the largest relative difference allowed
    /// Substeps where the two parted on a system with loops (redundant loop rows leave the
    /// constraint forces open) and were judged after moving both onto the loops'
    /// acceleration constraints; the largest RMS loop acceleration errors, relative to the
    /// largest acceleration, of the tree's and of Simbody's accelerations there.
    std::int64_t judged_on_loops = 0;
    double worst_loop_error = 0;
    double worst_reference_loop_error = 0;
  };
  DynamicsCheck dynamics_check() const;
  /// Back to t = 0: initial configuration, inputs at their initial values, components
  /// re-initialised, random streams re-seeded. A reset run repeats the first bit for bit.
  void reset();
  /// reset() with `seed` for every component's random stream, from this reset on (later
  /// resets keep it): a new seed gives new sensor noise, the same seed the same run.
  void reset(std::uint64_t seed);
  /// The seed of the random streams: SimulationOptions::seed, or the last reset(seed)'s.
  std::uint64_t seed() const;

  // Signals: every readable value, by index (fast) or name.
  std::size_t signal_count() const;
  const SignalInfo& signal_info(std::size_t index) const;
  std::optional<std::size_t> find_signal(std::string_view name) const;
  /// Like find_signal but throws (kind usage) naming the signal and suggesting close names.
  std::size_t signal_index(std::string_view name) const;
  double signal(std::size_t index) const;
  double signal(std::string_view name) const { return signal(signal_index(name)); }
  /// Signals whose names match a glob pattern (`*` any run of characters, `?` one).
  std::vector<std::size_t> match_signals(std::string_view pattern) const;
  /// Every signal's value in index order, in one buffer that stays where it is for the
  /// Simulation's life (for views that change in place, e.g. a NumPy array over it). Kept up
  /// to date only once asked for: from the first call on, every call below that changes a
  /// value (step, run_until, reset, restore, place_body, set_input, set_axis_state) rewrites it
  /// before returning; until then it costs nothing.
  const std::vector<double>& signal_values() const;

  // Inputs: values set from outside that hold until set again.
  std::size_t input_count() const;
  const SignalInfo& input_info(std::size_t index) const;
  /// Throws (kind usage) naming the input and suggesting close names.
  std::size_t input_index(std::string_view name) const;
  void set_input(std::size_t index, double value);
  void set_input(std::string_view name, double value) { set_input(input_index(name), value); }
  double input(std::size_t index) const;
  /// Every input's value in index order; the buffer stays where it is for the Simulation's
  /// life (written by set_input, reset and restore).
  const std::vector<double>& inputs() const;

  // Bodies: index 0 is the world, scene body i is body i + 1.
  int body_count() const;
  const Pose& body_pose(int body) const;
  const Twist& body_twist(int body) const;
  /// A body's path, the prefix of its signals: `robots/<robot>/solids/<solid>`,
  /// `things/<thing>`, or `world` for body 0 (docs/signals.md).
  std::string body_path(int body) const;
  /// Every body's pose and twist by index (what body_pose and body_twist read): buffers sized
  /// at load that stay where they are for the Simulation's life, holding the current state.
  const std::vector<Pose>& body_poses() const;
  const std::vector<Twist>& body_twists() const;
  /// The first collision surface along a ray from `origin_m` in `direction` (world frame)
  /// within `max_distance_m`, skipping the geoms of body `ignore_body` (> 0): what sensors
  /// see (ground, walls, obstacles, every body), for picking and tests.
  RayHit cast_ray(const Vec3& origin_m, const Vec3& direction, double max_distance_m,
                  int ignore_body = -1) const;

  // Axes (joint degrees of freedom), in scene joint order.
  struct AxisView {
    std::string name;
    int robot;
    int joint;
    bool linear;
  };
  std::size_t axis_count() const;
  const AxisView& axis(std::size_t index) const;
  double axis_position(std::size_t index) const;
  double axis_velocity(std::size_t index) const;
  /// An axis's path, the prefix of its signals and inputs: `<robot or world>/axes/<axis>`.
  std::string axis_path(std::size_t index) const;
  /// Every axis's position and velocity in axis order (the joints' coordinates and rates):
  /// buffers that stay where they are for the Simulation's life, holding the current state.
  const std::vector<double>& axis_positions() const;
  const std::vector<double>& axis_velocities() const;
  /// Sets axis `index`'s position (rad or m) and velocity (rad/s or m/s) in the current state,
  /// the bodies it carries following (its other coordinates, and the other axes, kept); time
  /// does not change. Throws s2sim::Error (usage), changing nothing, naming the axis for a
  /// loop-closing axis (its value follows from the bodies it joins) or a non-finite value.
  void set_axis_state(std::size_t index, double position, double velocity);

  /// Contacts of the last physics substep (points, normals, forces, bodies).
  std::size_t contact_count() const;
  const ContactInfo& contact(std::size_t index) const;

  /// Kinetic and gravitational potential energy of all bodies, J (validation).
  double kinetic_energy_J() const;
  double potential_energy_J() const;

  /// A copy of the whole simulation state; restoring it continues exactly as from there. At
  /// load, every subsystem declares its state as named segments (`multibody/q`,
  /// `contact/memory`, `inputs`, ...: docs/scheduling.md, "Snapshots"); a snapshot holds
  /// them one after another in `values`, with the layout's id.
  struct Snapshot {
    /// A segment of the layout: `size` numbers, or `variable`: a count of numbers (a multiple
    /// of `unit`) first, then those numbers.
    struct Segment {
      static constexpr std::size_t variable = static_cast<std::size_t>(-1);
      std::string name;
      std::size_t size = 0;
      std::size_t unit = 1;
    };
    struct Range {
      std::size_t offset = 0, size = 0;
    };
    std::uint64_t layout = 0;       ///< hash of the segment names and sizes
    std::vector<Segment> segments;  ///< the layout, to name what differs from another one
    std::vector<double> values;     ///< the segments, in order
    /// Where segment `name` lies in `values` (a variable one: after its count). Throws
    /// s2sim::Error (usage) for a name the layout does not have.
    Range find(std::string_view name) const;
  };
  Snapshot save() const;
  /// Throws s2sim::Error (usage), changing nothing, for a snapshot of another simulation (a
  /// different layout: the message names the first segment that differs) or a malformed one.
  void restore(const Snapshot& snapshot);

  /// Moves a body that hangs freely from the world (a thing, or a robot's root body, which
  /// carries the whole robot) to `pose` in the world frame, at rest: the viewer's drag, or
  /// SimTwo's SetRobotPos. Time does not change. Throws s2sim::Error (usage) naming the body
  /// for a body jointed to something else, or for the world.
  void place_body(int body, const Pose& pose);

  /// Adds a free body at `spec.pose`, at rest, on the first spare body (SimTwo's AddThingBox,
  /// AddThingSphere, AddThingCylinder) and returns its kernel body index. It collides, falls,
  /// is hit by rays, is drawn and publishes `runtime_things/<k>/…` signals; a snapshot holds it
  /// and a reset removes it. Throws s2sim::Error (usage) when no spare body is left or the
  /// spec is not a body (non-finite, a mass or size not positive or beyond 10 km).
  int add_thing(const ThingSpec& spec, std::string_view id);
  /// Removes thing `body` (a scene thing or an added one) until a reset: it no longer moves,
  /// touches, is hit or drawn. Throws s2sim::Error (usage) for a body that is not a thing.
  void delete_thing(int body);
  /// The scene's things, then the spare bodies, as they stand now.
  const std::vector<ThingView>& things() const;
  /// Removes the scene's obstacle `index` (scene order; SimTwo's DeleteObstacle) until a
  /// reset: it touches nothing, is hit by no ray and is not drawn; a snapshot holds it. Throws
  /// s2sim::Error (usage) for an index out of range.
  void delete_obstacle(int index);
  bool obstacle_present(int index) const;
  /// Resizes body `body`'s own primitive (SimTwo's SetSolidSize, SetThingSize: a box its edges,
  /// a cylinder radius x and length z, a sphere radius x): collision, rays and the viewer take
  /// it; the mass and inertia stay as loaded (an added thing's inertia follows its new size).
  /// A snapshot holds it, a reset restores the scene's. Throws s2sim::Error (usage) for a body
  /// without a primitive, a mesh's hull, or a size not positive or beyond 10 km.
  void resize_body(int body, const Vec3& size_m);
  /// Sets the friction of body `body`'s own primitive (SetSolidSurfaceFriction,
  /// SetThingSurfaceMu): mu >= 0 an explicit coefficient, mu < 0 the scene's default; mu2 the
  /// cross coefficient of a surface that is anisotropic in the scene. Snapshot and reset as
  /// resize_body.
  void set_body_surface(int body, double mu, double mu2);
  /// The size resize_body gave body `body`, if any.
  std::optional<Vec3> resized(int body) const;
  /// A body's mass properties: its mass, its centre of mass (body frame) and its inertia
  /// about that centre (body axes).
  struct MassProperties {
    double mass_kg = 0;
    Vec3 com_m;
    Mat3 inertia_kg_m2;
    /// SimTwo's rule for a new mass alone: these with the inertia scaled by the mass's ratio,
    /// the centre of mass kept.
    MassProperties with_mass(double new_mass_kg) const;
  };
  /// Gives body `body` new mass properties while running (SimTwo's SetSolidMass, with the
  /// centre of mass and the inertia too): a jointed body's dynamics, its robot's weight, its
  /// joint stops and what contact meets follow, its coordinates and speeds kept (a jointed
  /// body costs the multibody model a rebuild: 0.4 ms for a pendulum, 1 ms for the humanoid
  /// and 7 ms for 16 robots, measured while a build ran). A snapshot holds it, a
  /// reset restores the scene's. Throws s2sim::Error (usage) for the world or an unknown
  /// body, a mass not positive or beyond 1e9 kg, a centre of mass not finite, or an inertia
  /// that is not symmetric, positive and within the triangle inequality.
  void set_body_mass(int body, const MassProperties& mass);
  /// The same with the mass alone, SimTwo's rule: the inertia scaled by the mass's ratio, the
  /// centre of mass kept.
  void set_body_mass(int body, double mass_kg);
  /// Body `body`'s mass properties as they stand now.
  MassProperties body_mass(int body) const;

  /// The images the components declared (a camera's colour, depth and segmentation, a
  /// lidar's range image...), by full name, in declaration order.
  std::vector<std::string> image_names() const;
  /// An image by its full name, read in place (valid while the simulation lives; its pixels
  /// change at the frames its component writes). Throws naming close names when unknown.
  const Image& image(std::string_view full_name) const;
  /// How the cameras are drawn: the factory is called once, at the first camera frame.
  /// Without one, a camera's first frame stops the run with an error naming it.
  void set_camera_renderer(CameraRendererFactory factory);

  /// Log lines, HUD texts, trails and XY series the components published (SDK 0.9,
  /// annotations.hpp), since the load or the last reset. Not part of the state.
  const Annotations& annotations() const;

  struct Impl;

 private:
  explicit Simulation(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// Process exit code for an error kind (0 ok, 2 scene, 3 plugin, 4 usage, 5 runtime).
int exit_code(ErrorKind kind);

/// The component whose code runs now (its configure, initialize or update), as
/// "component '<path>' (kind '<kind>') from <plugin file>", or nullptr when the kernel's own
/// code runs. Async-signal-safe (one atomic load): for a fatal-signal handler to say which
/// plugin crashed (s2sim-run does, docs/reliability.md).
const char* running_component() noexcept;

/// One thread's call into a component, as running_calls() sees it: the component (its
/// running_component() text) and the number of calls into components that thread has begun.
struct RunningCall {
  const char* component = nullptr;
  std::uint64_t call = 0;
};
/// What every thread that ever called a component runs now, into `out` (at most `capacity`):
/// how many were written. For a watchdog on another thread: the same `call` seen again long
/// after is one call that has not returned. Lock-free; any thread may call it at any time.
std::size_t running_calls(RunningCall* out, std::size_t capacity) noexcept;

/// Gives the calling thread an alternate stack for signal handlers installed with SA_ONSTACK,
/// so that a fatal-signal handler runs even when the thread's stack overflowed (the kernel's
/// own worker threads have one). Once per thread; freed when the thread ends.
void use_alternate_signal_stack() noexcept;

}  // namespace s2sim
