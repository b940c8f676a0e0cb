// Simulation::load: the scene, the multibody's plan, every component, then the multibody built
// with the axis inertias the components declared, contact and ray casting.
#include "scene/limits.hpp"
#include "sim/drive_train_components.hpp"
#include "sim/fluid_components.hpp"
#include "sim/names.hpp"
#include "sim/simulation_impl.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>

namespace s2sim {

std::unique_ptr<Simulation> Simulation::load(const std::filesystem::path& scene_path,
                                             const SimulationOptions& options) {
  auto impl = std::make_unique<Impl>();
  Impl& m = *impl;
  m.options = options;
  scene::LoadOptions load_options;
  load_options.constants = options.constants;
  load_options.model_path = options.model_path;
  m.scene = scene::load_scene(scene_path, load_options);
  m.warnings = m.scene.warnings;

  if (options.physics_step_s) m.scene.settings.physics_step_s = *options.physics_step_s;
  if (options.substeps) m.scene.settings.substeps = *options.substeps;
  // The scene's own values were checked at load (located); these are the caller's overrides.
  const double step = m.scene.settings.physics_step_s;
  if (!(step >= scene::limits::kMinPhysicsStep_s && step <= scene::limits::kMaxPhysicsStep_s)) {
    char message[160];
    std::snprintf(message, sizeof message, "the physics step must be from %g to %g s, got %g s",
                  scene::limits::kMinPhysicsStep_s, scene::limits::kMaxPhysicsStep_s, step);
    throw Error(ErrorKind::usage, message);
  }
  if (m.scene.settings.substeps < 1 || m.scene.settings.substeps > scene::limits::kMaxSubsteps)
    throw Error(ErrorKind::usage, "substeps must be from 1 to " +
                                      std::to_string(scene::limits::kMaxSubsteps) + ", got " +
                                      std::to_string(m.scene.settings.substeps));
  const int max_threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  if (options.threads < 1 || options.threads > max_threads)
    throw Error(ErrorKind::usage, "threads must be from 1 to " + std::to_string(max_threads) +
                                      " (this machine's hardware threads), got " +
                                      std::to_string(options.threads));
  m.tick_s = m.scene.settings.physics_step_s;
  // Spare bodies for things added while running, before anything counts the bodies.
  const int spare = options.runtime_things.value_or(m.scene.settings.runtime_things);
  scene::reserve_runtime_things(m.scene, spare >= 0 ? spare
                                         : m.script_adds_things()
                                             ? scene::limits::kDefaultRuntimeThings
                                             : 0);

  // The multibody's plan first: the components configure against its axes and may declare
  // axis inertias, which the Simbody system is then built with.
  m.topology = model::plan_topology(m.scene);
  m.shapes = std::make_unique<collision::ShapeTable>(m.scene);
  for (const auto& ax : m.topology.axes)
    m.axis_views.push_back({ax.name, ax.robot, ax.joint, ax.linear});
  for (std::size_t a = 0; a < m.axis_views.size(); ++a)  // the first of a repeated path
    m.axis_of_path.emplace(m.axis_prefix(static_cast<int>(a)), static_cast<int>(a));
  m.poses.resize(m.scene.bodies.size() + 1);  // body 0 is the world
  m.twists.resize(m.poses.size());
  m.axis_position.assign(m.axis_views.size(), 0.0);
  m.axis_velocity.assign(m.axis_views.size(), 0.0);
  m.axis_force_applied.assign(m.axis_views.size(), 0.0);
  m.axis_inertia.assign(m.axis_views.size(), 0.0);
  m.register_kernel_signals();
  m.declare_canvases();  // before the components, which look them up

  // Components: scene sensors with a plugin for their kind, then <plugin> instances, then the
  // drive train of every axis (sim/drive_train_components.hpp), then the <plugin> controllers:
  // configured last, they can address every input and signal of the scene (SDK 0.7,
  // ConfigureContext::signal_names; a remote link serves a whole robot). Order within a stage
  // is unchanged for the others; controllers keep their scene order among themselves.
  std::vector<std::string> robot_prefixes;
  for (std::size_t r = 0; r < m.scene.robots.size(); ++r)
    robot_prefixes.push_back(m.robot_prefix(static_cast<int>(r)));
  const std::vector<sim::FluidComponent> fluids =
      sim::fluid_components(m.scene, robot_prefixes, m.warnings);
  const bool needs_plugins = !m.scene.sensors.empty() || !m.scene.plugins.empty() ||
                             !m.axis_views.empty() || !fluids.empty();
  std::optional<plugin::PluginRegistry> registry;
  if (needs_plugins)
    registry.emplace(
        plugin::PluginRegistry::search_path(options.plugin_path, options.default_plugin_path));
  for (const auto& sensor : m.scene.sensors) {
    if (!registry->has(sensor.kind)) {
      m.warnings.push_back(sensor.where.str() + ": no plugin provides the sensor kind '" +
                           sensor.kind + "'; sensor '" + sensor.name + "' is inert");
      continue;
    }
    m.add_component(*registry, sensor.kind, sensor.name, sensor.robot, sensor.params, sensor.where,
                    Category::sensor);
    m.components.back().sensor = static_cast<int>(&sensor - m.scene.sensors.data());
  }
  auto is_controller = [&](const scene::PluginInstance& p) {
    return registry->has(p.kind) && registry->find(p.kind).category == Category::controller;
  };
  for (const auto& p : m.scene.plugins) {
    if (is_controller(p)) continue;
    m.add_component(*registry, p.kind, p.id, p.robot, p.params, p.where, std::nullopt);
    m.components.back().plugin_element = true;
  }
  // SimTwo's drag, buoyancy and propeller solids (sim/fluid_components.hpp).
  for (const auto& c : fluids) {
    if (!registry->has(c.kind)) {
      m.warnings.push_back(c.where.str() + ": no plugin provides the kind '" + c.kind +
                           "' (plugin fluids, libfluids.so); solid '" +
                           c.id.substr(0, c.id.rfind('/')) + "' gets no " + c.kind);
      continue;
    }
    m.add_component(*registry, c.kind, c.id, c.robot, c.params, c.where, std::nullopt);
    m.components.back().prefix = c.prefix;
  }
  std::vector<sim::DriveAxis> drive_axes;
  for (const auto& ax : m.topology.axes)
    drive_axes.push_back({ax.name,
                          (ax.robot >= 0 ? m.robot_prefix(ax.robot) : std::string("world")) +
                              "/axes/" + sim::segment(ax.name),
                          ax.robot, ax.joint, ax.which, ax.linear});
  for (auto& c : sim::drive_train_components(m.scene, drive_axes)) {
    if (!registry->has(c.kind)) {
      // Refuse rather than run unpowered and frictionless axes (docs/models/dc-motor.md).
      std::string why;
      try {
        (void)registry->find(c.kind);
      } catch (const Error& e) {
        why = e.message();
      }
      throw Error(ErrorKind::plugin, c.where,
                  "axis '" + c.prefix.substr(0, c.prefix.rfind('/')) +
                      "' needs the drive-train kind '" + c.kind +
                      "' (plugin drive_train, libdrive_train.so): " + why);
    }
    m.add_component(*registry, c.kind, c.id, c.robot, c.params, c.where, std::nullopt);
    m.components.back().prefix = c.prefix;
  }
  // Controllers after the drive train: they may look its signals and inputs up by name.
  for (const auto& p : m.scene.plugins) {
    if (!is_controller(p)) continue;
    m.add_component(*registry, p.kind, p.id, p.robot, p.params, p.where, std::nullopt);
    m.components.back().plugin_element = true;
  }
  // The SimTwo script last: it reads the signals the sensors and the drive train publish.
  if (const auto script = m.script_instance()) {
    if (!registry)
      registry.emplace(
          plugin::PluginRegistry::search_path(options.plugin_path, options.default_plugin_path));
    m.add_component(*registry, script->kind, script->id, -1, script->params, script->where,
                    std::nullopt);
  }
  if (registry)
    for (const auto& w : registry->scan_warnings())
      m.warnings.push_back("plugin search: " + w);
  m.configure_components();
  m.warn_unread_plugin_attributes();

  m.multibody = std::make_unique<model::MultibodyIslands>(
      m.scene, m.topology, m.axis_inertia, m.tick_s, m.scene.settings.substeps, options.threads);
  if (m.joint_reactions_wanted) m.multibody->request_joint_reactions();
  if (options.simbody_dynamics_only) {
    m.multibody->choose_dynamics(model::DynamicsChoice::simbody);
  } else if (options.check_dynamics) {
    m.multibody->choose_dynamics(model::DynamicsChoice::checked);
  }
  if (options.dynamics_agreement) {
    if (!(*options.dynamics_agreement > 0))
      throw Error(ErrorKind::usage, "SimulationOptions::dynamics_agreement must be positive, got " +
                                        std::to_string(*options.dynamics_agreement));
    m.multibody->set_dynamics_agreement(*options.dynamics_agreement);
  }
  m.contacts =
      std::make_unique<contact::ContactWorld>(*m.shapes, m.scene, m.multibody->apparent_mass_kg());
  m.contacts->set_mobility(m.multibody->contact_mobility());
  // Friction on jointed bodies is solved with the axes (docs/models/contact.md).
  m.multibody->reserve_contact_friction(m.contacts->point_capacity());
  std::vector<char> solved_friction(m.poses.size(), 0);
  for (std::size_t b = 1; b < solved_friction.size(); ++b)
    solved_friction[b] = m.multibody->solves_contact_friction(static_cast<int>(b));
  m.contacts->set_solved_friction(solved_friction);
  for (const auto& [body, input] : m.belt_speed_inputs)
    m.contacts->set_belt_speed_input(body, input);
  m.multibody->use_contact_wrenches();     // written by contact at every substep (sim/step.cpp)
  m.multibody->split_forces(*m.contacts);  // with several parts, each computes its own contact
  m.multibody->bind_read(m.poses.data(), m.twists.data(), m.axis_position.data(),
                         m.axis_velocity.data());  // and writes its own read-out (refresh())
  for (const auto& w : m.multibody->warnings())
    m.warnings.push_back(w);

  m.state = m.state_initial;
  m.random.assign(4 * m.components.size(), 0);
  // The counts StepContext checks every handle against; the buffers keep their sizes from here.
  m.world.body_count = static_cast<std::int32_t>(m.poses.size());
  m.world.axis_count = static_cast<std::int32_t>(m.axis_position.size());
  m.world.joint_count = static_cast<std::int32_t>(m.scene.joints.size());
  m.world.input_count = static_cast<std::int32_t>(m.inputs.size());
  m.world.signal_count = static_cast<std::int32_t>(m.published.size());
  m.world.state_count = static_cast<std::int32_t>(m.state.size());
  m.world.body_pose = m.poses.data();
  m.world.body_twist = m.twists.data();
  m.world.body_wrench = m.multibody->applied_wrenches();
  m.world.axis_position = m.axis_position.data();
  m.world.axis_velocity = m.axis_velocity.data();
  m.world.axis_force = m.multibody->applied_axis_forces();
  m.world.axis_friction = m.multibody->applied_axis_friction();
  m.world.axis_drives = m.multibody->axis_drives();
  m.world.axis_drive_count = m.multibody->axis_drive_count();
  m.world.axis_drive_capacity = m.multibody->axis_drive_capacity();
  m.world.inputs = m.inputs.data();
  m.input_names.clear();
  for (const SignalInfo& info : m.input_infos)
    m.input_names.push_back(info.name.c_str());
  m.world.input_min = m.input_min.data();
  m.world.input_max = m.input_max.data();
  m.world.input_names = m.input_names.data();
  m.world.signals = m.published.data();
  m.world.state = m.state.data();
  m.world.random_state = m.random.data();
  m.world.tick_s = m.tick_s;
  m.world.contacts = m.contacts->contacts();
  m.world.contact_count = m.contacts->contact_count();
  m.contacts->set_inputs(m.inputs.data());
  m.ray_caster = std::make_unique<collision::RayCaster>(*m.shapes, m.poses.data());
  m.world.kernel = m.ray_caster.get();
  m.world.cast_ray = &collision::RayCaster::callback;
  m.world.joint_reaction = m.multibody->joint_reactions();
  m.pending_places.reserve(m.poses.size());
  m.pending_moves.reserve(m.poses.size());
  m.pending_velocities.reserve(m.poses.size());
  m.world.placer = &m;
  m.world.request_place = &Simulation::Impl::request_place;
  m.world.request_move = &Simulation::Impl::request_move;
  m.world.request_velocity = &Simulation::Impl::request_velocity;
  m.world.annotator = &m;
  m.world.annotate = &Simulation::Impl::annotate;
  m.bind_images();
  m.init_body_masses();  // before the things, whose spares take their masses
  m.init_things();
  m.init_body_shapes();
  m.plan_component_parts();  // with several parts, the local components run in them
  m.declare_state();
  m.reset();
  return std::unique_ptr<Simulation>(new Simulation(std::move(impl)));
}

}  // namespace s2sim
