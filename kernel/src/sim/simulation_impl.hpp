#pragma once
/// \file
/// Simulation's internals, shared by the kernel's sim/ files: the façade's Impl with its
/// buffers, its signal registry and its component slots. Which file does what:
/// - load.cpp: builds a Simulation from a scene (model, contact, rays, components);
/// - signals.cpp: the signal and input registry and the façade's signal/input calls;
/// - component_host.cpp: component instances and the ConfigureContext they configure through;
/// - step.cpp: what happens in a tick, in order; reset;
/// - snapshot.cpp: the state layout, save, restore and placing bodies;
/// - simulation.cpp: the remaining façade calls.

#include <s2sim/kernel/annotations.hpp>
#include <s2sim/kernel/simulation.hpp>

#include "collision/ray_caster.hpp"
#include "common/state_layout.hpp"
#include "contact/contact_world.hpp"
#include "model/multibody.hpp"
#include "model/multibody_islands.hpp"
#include "plugin/plugin_loader.hpp"
#include "scene/element_params.hpp"
#include "sim/component_parts.hpp"
#include "sim/stage_profile.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace s2sim {
namespace sim {

/// Where a readable signal's value lives.
enum class Source : std::uint8_t {
  published,  // a component's signal slot
  input,
  time,
  body_x,
  body_y,
  body_z,
  body_roll,
  body_pitch,
  body_yaw,
  body_vx,
  body_vy,
  body_vz,
  body_wx,
  body_wy,
  body_wz,
  axis_position,
  axis_velocity,
  axis_force,
  body_contact_force,
  contact_count,
};

struct SignalEntry {
  Source source;
  std::int32_t index;
};

/// One component instance: a plugin object, where it came from and its schedule.
struct ComponentSlot {
  ComponentSlot() = default;
  ComponentSlot(ComponentSlot&&) noexcept = default;
  ComponentSlot& operator=(ComponentSlot&&) noexcept = default;
  /// Destroys the component with its label marked as running, so that a crash in its
  /// destructor is reported as its own (running_component.hpp).
  ~ComponentSlot();

  plugin::ComponentPtr component;
  std::string kind;
  std::string id;
  std::string prefix;  // signal prefix
  int robot = -1;
  Category category = Category::actuator;
  Stage stage = Stage::actuate;
  std::int64_t period_ticks = 1;
  std::int64_t phase_ticks = 0;
  std::unique_ptr<scene::ElementParams> params;
  Location where;
  int sensor = -1;                 // index into scene.sensors when made for a scene sensor element
  bool plugin_element = false;     // made for a <plugin> element: its unread attributes warn
  bool strict_attributes = false;  // ...or refuse the scene (refuse_unread_attributes)
  std::string library;             // the plugin file it came from, for messages
  bool local = false;              // declared local (ConfigureContext::declare_local)
  Footprint footprint;             // what it resolved at configure
  std::string label() const { return prefix + " (kind '" + kind + "')"; }
  /// "component '<prefix>' (kind '<kind>') from <library>", made once at load: what a
  /// fatal-signal handler prints (running_component.hpp).
  std::string crash_label;
};

/// Inside a catch block around a call into a component (`call`: "configure", "update"...):
/// turns the exception in flight into a kernel-owned s2sim::Error naming the component, its
/// kind and its plugin, and throws it. A plugin's own exception object may not outlive its
/// library (its vtable is there), and a non-standard one would terminate the process.
/// `fallback` is the kind for what is not an s2sim::Error.
[[noreturn]] void rethrow_from_component(const ComponentSlot& slot, const char* call,
                                         ErrorKind fallback);

}  // namespace sim

struct Simulation::Impl {
  scene::Scene scene;
  SimulationOptions options;
  std::vector<std::string> warnings;
  double tick_s = 1e-3;
  std::int64_t tick = 0;
  /// The multibody's plan: its axes are known to the components before it is built.
  model::Topology topology;
  /// Per axis, the inertia the components declared (ConfigureContext::add_axis_inertia).
  std::vector<double> axis_inertia;
  bool joint_reactions_wanted = false;  ///< a component looked up a joint
  /// (body, input) of every conveyor belt's `belt_speed`, for contact once it is built.
  std::vector<std::pair<std::int32_t, std::int32_t>> belt_speed_inputs;
  /// One Simbody system, or several stepped in parallel (SimulationOptions::threads).
  std::unique_ptr<model::MultibodyIslands> multibody;
  std::unique_ptr<collision::ShapeTable> shapes;
  std::unique_ptr<contact::ContactWorld> contacts;
  std::vector<AxisView> axis_views;
  /// Each axis's full path (axis_prefix) to its index: components look their axes up by name,
  /// and a search that built every path per lookup grew with the square of the robot count.
  std::unordered_map<std::string, int> axis_of_path;

  // Per-tick buffers the components see through detail::WorldView.
  std::vector<Pose> poses;
  std::vector<Twist> twists;
  std::vector<double> axis_position, axis_velocity, axis_force_applied;
  std::vector<double> inputs, inputs_initial;
  std::vector<double> published;
  std::vector<double> state, state_initial;
  std::vector<std::uint64_t> random;
  detail::WorldView world;

  std::vector<SignalInfo> signal_infos;
  /// Simulation::signal_values(): every signal's value, kept up to date once asked for.
  mutable std::vector<double> signal_values;
  mutable bool signal_values_kept = false;
  /// At the end of a façade call that changed the state or an input: signal_values rewritten
  /// when it is kept.
  void changed() const;
  std::vector<sim::SignalEntry> signal_entries;
  std::unordered_map<std::string, std::size_t> signal_by_name;
  std::vector<SignalInfo> input_infos;
  std::unordered_map<std::string, std::size_t> input_by_name;
  // Each input's valid range, bounds included (WorldView::input_min/max), and its name as
  // WorldView::input_names points at it (filled once every input is declared).
  std::vector<double> input_min, input_max;
  std::vector<const char*> input_names;
  std::vector<std::int32_t> ref_torque_input;  // per axis

  std::vector<sim::ComponentSlot> components;
  std::array<std::vector<int>, 4> stage_order;
  std::vector<std::int32_t> publisher;  // per published slot, the component that declared it

  // --- components by group (component_parts.cpp) ---------------------------------------------
  sim::ComponentParts component_parts;
  /// At load, once the multibody and contact are built: component_parts, or why not.
  void plan_component_parts();
  /// The local views' copies of `world` (its time, tick and contacts change every tick).
  void sync_local_views();
  /// A group's components at the tick's start (the whole scene's on the calling thread before
  /// the physics, a part's on its thread through part_hooks): its loads cleared, its due
  /// components in stage order, then its reference torques and the check of its loads.
  /// `ahead`: the tick's distance from `tick` (running ahead; 0 otherwise).
  void run_component_group(sim::ComponentGroup& group, bool calling_thread, int ahead);
  /// After the group's physics: what its axes carried over the tick (the plain forces and the
  /// drives' implicit values).
  void record_group_axis_loads(const sim::ComponentGroup& group);
  // What a local component is refused (LocalView): each throws naming it.
  static RayHit refuse_ray(const void* local, const Vec3&, const Vec3&, double, std::int32_t);
  static void refuse_render(const void* local, const CameraShot&, Image*, Image*, Image*);
  static void refuse_place(const void* local, std::int32_t, const Pose&);
  static void refuse_move(const void* local, std::int32_t, const Pose&);
  static void refuse_velocity(const void* local, std::int32_t, const Twist&);
  static std::int32_t refuse_add_thing(const void* local, const ThingSpec&, const char*,
                                       std::size_t);
  static void refuse_delete_thing(const void* local, std::int32_t);
  static void refuse_delete_obstacle(const void* local, std::int32_t);
  static void refuse_resize(const void* local, std::int32_t, const Vec3&);
  static void refuse_mass(const void* local, std::int32_t, double, const Vec3*, const Mat3*);
  static void refuse_surface(const void* local, std::int32_t, double, double);
  static void refuse_annotation(const void* local, std::int32_t, std::int32_t, std::int32_t,
                                const char*, std::size_t, const double*);

  /// Re-placements components asked for in the current stage (StepContext::request_place),
  /// applied once the stage has run (step.cpp); reserved at load, one per body.
  std::vector<std::pair<std::int32_t, Pose>> pending_places;
  /// Moves and velocities (StepContext::request_move, request_velocity), applied after the
  /// places in that order; reserved at load, one of each per body.
  std::vector<std::pair<std::int32_t, Pose>> pending_moves;
  std::vector<std::pair<std::int32_t, Twist>> pending_velocities;
  static void request_place(const void* impl, std::int32_t body, const Pose& pose);
  static void request_move(const void* impl, std::int32_t body, const Pose& pose);
  static void request_velocity(const void* impl, std::int32_t body, const Twist& twist);
  void apply_pending_places();

  // Things added and deleted while running (runtime_things.cpp): the scene's things, then the
  // spare bodies, as they stand; the ones whose kernel side a component's request changed in
  // the current stage (applied with the places); each view's index by kernel body (-1: none).
  std::vector<ThingView> thing_views;
  std::vector<std::int32_t> pending_things;
  std::vector<std::int32_t> thing_of_body;
  void init_things();
  void reset_things();
  int take_spare_thing(const ThingSpec& spec, std::string_view id);
  void mark_thing_deleted(int body);
  /// Pushes view `t` into the kernel: shape, mass, gravity, parked; its pose too when `place`.
  void apply_thing(std::size_t t, bool place);
  void apply_pending_things();
  void declare_things_state();
  // Bodies' primitives resized and surfaces set while running (body_shapes.cpp), per kernel
  // body; the scene's surfaces of their own primitives; requests of the current stage.
  struct BodyShape {
    bool resized = false;
    Vec3 size_m;
    bool surfaced = false;
    double mu = 0, mu2 = 0;
  };
  std::vector<BodyShape> body_shapes;
  std::vector<collision::Surface> loaded_surfaces;
  struct PendingBodyChange {
    enum class Kind { resize, surface, mass } kind = Kind::resize;
    std::int32_t body = 0;
    Vec3 values;  // a size; mu, mu2; or the centre of mass
    double mass_kg = 0;
    Mat3 inertia_kg_m2;
  };
  std::vector<PendingBodyChange> pending_body_changes;
  std::int32_t own_shape(int body, const char* call) const;
  void check_resize(int body, const Vec3& size_m) const;
  void check_surface(int body, double mu, double mu2) const;
  void resize_body(int body, const Vec3& size_m);
  void set_body_surface(int body, double mu, double mu2);
  void apply_body_shape(int body);
  void apply_pending_body_changes();
  void init_body_shapes();
  void reset_body_shapes();
  void declare_body_shapes_state();
  static void request_resize(const void* impl, std::int32_t body, const Vec3& size_m);
  static void request_surface(const void* impl, std::int32_t body, double mu, double mu2);
  // Bodies' mass properties set while running (body_masses.cpp), per kernel body.
  struct BodyMass {
    bool changed = false;
    Simulation::MassProperties mass;
  };
  std::vector<BodyMass> body_masses;
  std::vector<double> body_mass_kg;  // per kernel body, the mass now (WorldView::body_mass_kg)
  /// What body `body` weighs without a change of its own: a present added thing its spec's
  /// (a uniform solid), any other body the scene's.
  Simulation::MassProperties base_mass(int body) const;
  Simulation::MassProperties mass_of(int body) const;
  /// Throws for a body that is not one, and for mass properties (when given) that are not
  /// physical.
  void check_mass(int body, const Simulation::MassProperties* mass, const char* call) const;
  void set_body_mass(int body, const Simulation::MassProperties& mass);
  /// Pushes body `body`'s mass properties into the multibody model and contact.
  void apply_body_mass(int body);
  /// The same for a loose body (runtime_things.cpp): whether it falls or is held follows from
  /// its thing's state.
  void apply_loose_mass(int body, const Simulation::MassProperties& mass);
  void init_body_masses();
  void reset_body_masses();
  void declare_body_masses_state();
  static void request_mass(const void* impl, std::int32_t body, double mass_kg, const Vec3* com_m,
                           const Mat3* inertia_kg_m2);
  // The scene's obstacles: which are present (a deleted one touches and shows nothing).
  std::vector<char> obstacle_present;
  std::vector<std::int32_t> pending_obstacles;
  void mark_obstacle_deleted(int index);
  void apply_obstacle(std::size_t o);
  static void request_delete_obstacle(const void* impl, std::int32_t obstacle);
  static std::int32_t request_add_thing(const void* impl, const ThingSpec& spec, const char* id,
                                        std::size_t id_size);
  static void request_delete_thing(const void* impl, std::int32_t body);
  /// "'id'" of a body for messages, or "index N" for one that is not in the scene.
  std::string body_label(int body) const;

  /// What components published for the people watching (WorldView::annotate,
  /// annotations.cpp); cleared by reset, not part of a snapshot.
  Annotations annotations;
  static void annotate(const void* impl, std::int32_t component, std::int32_t what, std::int32_t id,
                       const char* text, std::size_t text_size, const double* values);

  // Ray casting for sensors (WorldView::cast_ray), over the poses buffer.
  std::unique_ptr<collision::RayCaster> ray_caster;

  // --- images (images.cpp) ---------------------------------------------------------------------
  // Declared by components at configure; the pixels are allocated once, at bind_images, and
  // read in place by components, the façade and Python. Outputs, not state: a reset zeroes
  // them, a snapshot leaves them out.
  struct ImageSlot {
    std::string name;
    int component = -1;  ///< -1: the kernel's (a canvas)
    std::vector<std::uint8_t> pixels;
    std::uint8_t blank = 0;  ///< every byte after a reset: 0, or 255 for a canvas (white)
  };
  std::vector<ImageSlot> image_slots;
  std::vector<Image> images;
  const Simulation* facade = nullptr;  ///< what the renderer factory is given
  CameraRendererFactory renderer_factory;
  std::unique_ptr<CameraRenderer> renderer;
  std::string renderer_error;  ///< why the factory failed, said again at every later frame
  std::int32_t add_image(const std::string& name, int width_px, int height_px, PixelFormat format,
                         int component);
  /// The canvases of the scene's solids and obstacles (`<canvas>` on a box), rgb8 images
  /// `<body path>/canvas` and `obstacles/<index>/canvas`, declared before the components
  /// configure, white until written (canvases.cpp).
  void declare_canvases();
  /// The canvas image of scene body `body` (a scene index) or of obstacle `obstacle`.
  std::string solid_canvas_name(int body) const;
  static std::string obstacle_canvas_name(int obstacle);
  /// Gives every image its pixels and the WorldView its images and renderer, after configure.
  void bind_images();
  void reset_images();
  std::int32_t image_index(std::string_view name) const;  ///< -1 when unknown
  static void render_camera(const void* impl, const CameraShot& shot, Image* rgb, Image* depth,
                            Image* body_ids);

  // --- painting targets (painting_targets.cpp) -------------------------------------------------
  // The meshes of the scene's `<painting_target/>` geoms, read once at the first query
  // (ConfigureContext::painting_targets): configure-time data, not state.
  std::optional<std::vector<PaintingTarget>> painting_targets_read;
  const std::vector<PaintingTarget>& painting_targets();

  // Per-stage timing of the tick pipeline (Simulation::set_profiling); null when off.
  std::unique_ptr<sim::StageProfile> profile;

  // What a snapshot holds: every subsystem's state segments (snapshot.cpp), declared at load.
  common::StateLayout layout;

  // --- registration (signals.cpp) --------------------------------------------------------------
  std::size_t add_signal(std::string name, std::string unit, sim::Source source,
                         std::int32_t index);
  /// Declares an input or joins an existing one (units must agree, the ranges narrow to what
  /// both accept); a side of `valid` left unbounded takes the unit's sanity bound.
  std::int32_t add_input(const std::string& name, const std::string& unit, double initial,
                         const Location& where, const Range& valid = {});
  // Paths of scene objects by index (sim/names.hpp builds them).
  /// `robots/<robot>`.
  std::string robot_prefix(int robot) const;
  /// robot_prefix, or `world` for robot -1 (scene-level joints and axes).
  std::string scope_prefix(int robot) const;
  /// `robots/<robot>/joints/<joint>`, `world/joints/<joint>` for a scene-level joint.
  std::string joint_prefix(int joint) const;
  /// `robots/<robot>/axes/<axis>`, `world/axes/<axis>` for a scene-level axis.
  std::string axis_prefix(int axis) const;
  void register_kernel_signals();
  double read_signal(std::size_t i) const;
  /// SignalReader::read for components (SDK 0.7): `kernel` is this Impl.
  static double read_signal_callback(const void* kernel, std::int32_t index) {
    return static_cast<const Impl*>(kernel)->read_signal(static_cast<std::size_t>(index));
  }

  // --- components (component_host.cpp) ---------------------------------------------------------
  void add_component(plugin::PluginRegistry& registry, const std::string& kind,
                     const std::string& id, int robot, const scene::ParamSource& params,
                     const Location& where, std::optional<Category> required);
  void configure_components();
  /// After configure: a warning for every attribute of a `<plugin>` element (or of its
  /// children) that its component never asked for, a misspelling most of the time.
  void warn_unread_plugin_attributes();
  /// The `pascal_script` controller for the project's script, when `options` ask for it
  /// (script_attach.cpp): its element carries SimTwo's index tables (robots, solids, axes,
  /// sensors, things), the sheet and the scene constants.
  std::optional<scene::PluginInstance> script_instance() const;
  /// The script file that runs, when one does, and where its name came from.
  std::optional<std::filesystem::path> script_path(std::string& found_by) const;
  /// Whether the script that runs names a routine that adds things (AddThing...).
  bool script_adds_things() const;

  // --- snapshots (snapshot.cpp) ----------------------------------------------------------------
  /// Registers the state segments of the multibody, the contact layer and the buffers above;
  /// at the end of load.
  void declare_state();

  // --- stepping (step.cpp) ---------------------------------------------------------------------
  /// The buffers the components read, from the multibody's state after a tick.
  void refresh();
  void reset();
  /// One tick: the scheduled stages, then the physics (the stages in the parts when
  /// component_parts has them).
  void step_once();
  /// What the parts run at a tick's edges when the components are in the parts.
  struct PartHooks final : model::MultibodyIslands::TickHooks {
    explicit PartHooks(Impl& owner) : impl(owner) {}
    void start(int part, bool calling_thread, int ahead) override {
      impl.run_component_group(impl.component_parts.parts[static_cast<std::size_t>(part)],
                               calling_thread, ahead);
    }
    void end(int part) override {
      impl.record_group_axis_loads(impl.component_parts.parts[static_cast<std::size_t>(part)]);
    }
    Impl& impl;
  };
  PartHooks part_hooks{*this};
  /// `ticks` ticks, run ahead in stretches where it can (run_ahead.cpp), else one by one.
  void advance(std::int64_t ticks);
  /// Up to `ticks` ticks run ahead (run_ahead.cpp): how many ran; 0 when it could not start,
  /// or when a part left its fence and the state went back to where it was.
  std::int64_t step_ahead(std::int64_t ticks);
  /// After the layout restored a state: the models' caches and the components' view.
  void restored();
  /// Running ahead: the state it started from, kept for a part leaving its fence; the ticks
  /// still to run one by one before trying again, the stretches lost in a row, and how many
  /// times the next stretch's length doubles the first's (run_ahead.cpp).
  std::vector<double> ahead_checkpoint;
  std::int64_t ahead_wait_ticks = 0;
  int ahead_misses = 0;
  int ahead_growth = 0;
  Simulation::RunAheadCounts ahead_counts;
  /// Component `c`'s update when its schedule has it due this tick (true), through `local`'s
  /// view when it is local (its group's), else the
  /// world's; an exception becomes the kernel's Error naming it. Its schedule's clock: the
  /// view's tick.
  bool update_if_due(int c, sim::LocalView* local);
  /// Throws (runtime) naming the body, axis or drive when a component applied a non-finite
  /// load: among `bodies` and `axes` (null: all, the world's entry too) and the drives.
  void check_loads_finite(const std::vector<int>* bodies, const std::vector<int>* axes,
                          const AxisDrive* drives, std::int32_t drive_count) const;
};

}  // namespace s2sim
