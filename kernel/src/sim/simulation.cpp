#include <s2sim/kernel/simulation.hpp>

#include "collision/ray_caster.hpp"
#include "contact/contact_world.hpp"
#include "model/multibody.hpp"
#include "plugin/plugin_loader.hpp"
#include "scene/element_params.hpp"
#include "sim/drive_train_components.hpp"
#include "sim/names.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

namespace s2sim {

int exit_code(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::scene:
      return 2;
    case ErrorKind::plugin:
      return 3;
    case ErrorKind::usage:
      return 4;
    case ErrorKind::runtime:
      return 5;
  }
  return 1;
}

namespace {

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
  int sensor = -1;  // index into scene.sensors when made for a scene sensor element
  std::string label() const { return prefix + " (kind '" + kind + "')"; }
};

Stage default_stage(Category c) {
  switch (c) {
    case Category::sensor:
      return Stage::sense;
    case Category::controller:
      return Stage::control;
    case Category::actuator:
    case Category::body:
      return Stage::actuate;
  }
  return Stage::actuate;
}

const char* category_folder(Category c) {
  switch (c) {
    case Category::sensor:
      return "sensors";
    case Category::controller:
      return "controllers";
    case Category::actuator:
      return "actuators";
    case Category::body:
      return "bodies";
  }
  return "plugins";
}

std::uint64_t fnv1a(std::string_view s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : s) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

}  // namespace

struct Simulation::Impl {
  scene::Scene scene;
  SimulationOptions options;
  std::vector<std::string> warnings;
  double tick_s = 1e-3;
  std::int64_t tick = 0;
  std::unique_ptr<model::Multibody> multibody;
  std::unique_ptr<collision::ShapeTable> shapes;
  std::unique_ptr<contact::ContactWorld> contacts;
  std::vector<AxisView> axis_views;

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
  std::vector<SignalEntry> signal_entries;
  std::unordered_map<std::string, std::size_t> signal_by_name;
  std::vector<SignalInfo> input_infos;
  std::unordered_map<std::string, std::size_t> input_by_name;
  std::vector<std::int32_t> ref_torque_input;  // per axis

  std::vector<ComponentSlot> components;
  std::array<std::vector<int>, 4> stage_order;

  // Ray casting for sensors (WorldView::cast_ray), over the poses buffer.
  std::unique_ptr<collision::RayCaster> ray_caster;

  // --- registration -----------------------------------------------------------------------

  std::size_t add_signal(std::string name, std::string unit, Source source, std::int32_t index) {
    // Duplicate scene IDs are legal in SimTwo; later ones get a "#n" suffix.
    std::string unique = name;
    for (int n = 2; signal_by_name.count(unique); ++n)
      unique = name + "#" + std::to_string(n);
    signal_by_name.emplace(unique, signal_infos.size());
    signal_infos.push_back({unique, std::move(unit)});
    signal_entries.push_back({source, index});
    return signal_infos.size() - 1;
  }

  /// Declares an input or joins an existing one (units must agree).
  std::int32_t add_input(const std::string& name, const std::string& unit, double initial,
                         const Location& where) {
    if (auto it = input_by_name.find(name); it != input_by_name.end()) {
      if (input_infos[it->second].unit != unit)
        throw Error(ErrorKind::plugin, where,
                    "input '" + name + "' is declared with unit '" + unit +
                        "' but already exists with unit '" + input_infos[it->second].unit + "'");
      return static_cast<std::int32_t>(it->second);
    }
    const auto index = static_cast<std::int32_t>(inputs.size());
    input_by_name.emplace(name, inputs.size());
    input_infos.push_back({name, unit});
    inputs.push_back(initial);
    inputs_initial.push_back(initial);
    add_signal(name, unit, Source::input, index);
    return index;
  }

  std::string robot_prefix(int robot) const {
    return "robots/" + sim::segment(scene.robots[robot].id);
  }
  /// `robots/<robot>/joints/<joint>`, `world/joints/<joint>` for a scene-level joint.
  std::string joint_prefix(int joint) const {
    const auto& jt = scene.joints[static_cast<std::size_t>(joint)];
    return (jt.robot >= 0 ? robot_prefix(jt.robot) : std::string("world")) + "/joints/" +
           sim::segment(jt.id);
  }

  void register_kernel_signals() {
    add_signal("time", "s", Source::time, 0);
    add_signal("contacts/count", "1", Source::contact_count, 0);
    auto add_body = [&](const std::string& p, int body) {
      const std::pair<const char*, Source> fields[] = {
          {"x", Source::body_x},       {"y", Source::body_y},         {"z", Source::body_z},
          {"roll", Source::body_roll}, {"pitch", Source::body_pitch}, {"yaw", Source::body_yaw},
          {"vx", Source::body_vx},     {"vy", Source::body_vy},       {"vz", Source::body_vz},
          {"wx", Source::body_wx},     {"wy", Source::body_wy},       {"wz", Source::body_wz}};
      for (const auto& [name, source] : fields) {
        const std::string_view n = name;
        const char* unit = n[0] == 'v'     ? "m/s"
                           : n[0] == 'w'   ? "rad/s"
                           : n.size() == 1 ? "m"
                                           : "rad";
        add_signal(p + "/" + name, unit, source, body);
      }
      add_signal(p + "/contact_force", "N", Source::body_contact_force, body);
    };
    for (std::size_t r = 0; r < scene.robots.size(); ++r) {
      const auto& robot = scene.robots[r];
      if (robot.main_body >= 0) add_body(robot_prefix(static_cast<int>(r)), robot.main_body + 1);
      for (int b : robot.bodies)
        add_body(robot_prefix(static_cast<int>(r)) + "/solids/" + sim::segment(scene.bodies[b].id),
                 b + 1);
    }
    for (int b : scene.things)
      add_body("things/" + sim::segment(scene.bodies[b].id), b + 1);
    // A conveyor belt's surface speed along its +X, settable at run time (spec §4.3).
    for (std::int32_t body : contacts->belt_bodies()) {
      const auto& b = scene.bodies[body - 1];
      const std::string p = b.robot >= 0 ? robot_prefix(b.robot) + "/solids/" + sim::segment(b.id)
                                         : "things/" + sim::segment(b.id);
      contacts->set_belt_speed_input(body, add_input(p + "/belt_speed", "m/s", 0.5, b.where));
    }
    for (std::size_t a = 0; a < axis_views.size(); ++a) {
      const AxisView& ax = axis_views[a];
      const std::string p = (ax.robot >= 0 ? robot_prefix(ax.robot) : std::string("world")) +
                            "/axes/" + sim::segment(ax.name);
      const auto i = static_cast<std::int32_t>(a);
      add_signal(p + "/pos", ax.linear ? "m" : "rad", Source::axis_position, i);
      add_signal(p + "/speed", ax.linear ? "m/s" : "rad/s", Source::axis_velocity, i);
      add_signal(p + "/torque", ax.linear ? "N" : "N*m", Source::axis_force, i);
      ref_torque_input.push_back(
          add_input(p + "/ref_torque", ax.linear ? "N" : "N*m", 0.0, scene.joints[ax.joint].where));
    }
  }

  // --- components ---------------------------------------------------------------------------

  void add_component(plugin::PluginRegistry& registry, const std::string& kind,
                     const std::string& id, int robot, const scene::ParamSource& params,
                     const Location& where, std::optional<Category> required);
  void configure_components();

  // --- stepping -----------------------------------------------------------------------------

  void refresh() {
    multibody->read(poses.data(), twists.data(), axis_position.data(), axis_velocity.data());
    world.time_s = static_cast<double>(tick) * tick_s;
    world.tick = tick;
    if (ray_caster) ray_caster->invalidate();
  }

  void reset() {
    tick = 0;
    multibody->reset();
    contacts->reset();
    // Copy in place: the WorldView points into these buffers.
    std::copy(inputs_initial.begin(), inputs_initial.end(), inputs.begin());
    std::copy(state_initial.begin(), state_initial.end(), state.begin());
    std::fill(published.begin(), published.end(), 0.0);
    std::fill(axis_force_applied.begin(), axis_force_applied.end(), 0.0);
    for (std::size_t c = 0; c < components.size(); ++c)
      RandomStream::seed(random.data() + 4 * c, options.seed ^ fnv1a(components[c].prefix));
    refresh();
    for (std::size_t c = 0; c < components.size(); ++c) {
      StepContext ctx(&world, static_cast<std::int32_t>(c), components[c].period_ticks);
      components[c].component->initialize(ctx);
    }
  }

  void step_once() {
    Wrench* wrenches = multibody->applied_wrenches();
    double* axis_force = multibody->applied_axis_forces();
    double* axis_friction = multibody->applied_axis_friction();
    std::fill(wrenches, wrenches + poses.size(), Wrench{});
    std::fill(axis_force, axis_force + axis_views.size(), 0.0);
    std::fill(axis_friction, axis_friction + axis_views.size(), 0.0);
    for (const auto& order : stage_order) {
      for (int c : order) {
        const ComponentSlot& slot = components[c];
        const std::int64_t since = tick - slot.phase_ticks;
        if (since < 0 || since % slot.period_ticks != 0) continue;
        StepContext ctx(&world, c, slot.period_ticks);
        slot.component->update(ctx);
      }
    }
    for (std::size_t a = 0; a < axis_views.size(); ++a)
      axis_force[a] += inputs[ref_torque_input[a]];
    std::copy(axis_force, axis_force + axis_views.size(), axis_force_applied.begin());
    multibody->step();
    ++tick;
    refresh();
    world.contacts = contacts->contacts();  // the buffer may have grown
  }

  double read_signal(std::size_t i) const {
    const SignalEntry& e = signal_entries[i];
    const std::int32_t k = e.index;
    switch (e.source) {
      case Source::published:
        return published[k];
      case Source::input:
        return inputs[k];
      case Source::time:
        return static_cast<double>(tick) * tick_s;
      case Source::body_x:
        return poses[k].position.x;
      case Source::body_y:
        return poses[k].position.y;
      case Source::body_z:
        return poses[k].position.z;
      case Source::body_roll:
        return std::atan2(poses[k].rotation.m[2][1], poses[k].rotation.m[2][2]);
      case Source::body_pitch:
        return std::asin(std::clamp(-poses[k].rotation.m[2][0], -1.0, 1.0));
      case Source::body_yaw:
        return yaw_of(poses[k].rotation);
      case Source::body_vx:
        return twists[k].linear_m_s.x;
      case Source::body_vy:
        return twists[k].linear_m_s.y;
      case Source::body_vz:
        return twists[k].linear_m_s.z;
      case Source::body_wx:
        return twists[k].angular_rad_s.x;
      case Source::body_wy:
        return twists[k].angular_rad_s.y;
      case Source::body_wz:
        return twists[k].angular_rad_s.z;
      case Source::axis_position:
        return axis_position[k];
      case Source::axis_velocity:
        return axis_velocity[k];
      case Source::axis_force:
        return axis_force_applied[k];
      case Source::body_contact_force: {
        Vec3 sum;
        const ContactInfo* c = contacts->contacts();
        for (std::int32_t n = 0; n < *contacts->contact_count(); ++n) {
          if (c[n].body_a.index == k) sum += c[n].force_N;
          if (c[n].body_b.index == k) sum -= c[n].force_N;
        }
        return norm(sum);
      }
      case Source::contact_count:
        return *contacts->contact_count();
    }
    return 0.0;
  }
};

namespace {

/// The ConfigureContext a component sees while the simulation is being built.
class ConfigureContextImpl final : public ConfigureContext {
 public:
  ConfigureContextImpl(Simulation::Impl& sim, int component_index)
      : sim_(sim), index_(component_index) {}

  const Params& params() const override { return *slot().params; }
  std::string_view id() const override { return slot().id; }
  std::string_view signal_prefix() const override { return slot().prefix; }
  std::string_view robot() const override {
    return slot().robot >= 0 ? std::string_view(sim_.scene.robots[slot().robot].id)
                             : std::string_view();
  }
  double tick_s() const override { return sim_.tick_s; }

  BodyHandle body(std::string_view name) override {
    if (name == "world" || name == "0") return BodyHandle{0};
    const std::string n(name);
    const auto& bodies = sim_.scene.bodies;
    if (n.find('/') == std::string::npos) {
      if (slot().robot < 0)
        throw fail(
            "a scene-level component names bodies by full path ('things/<id>' or "
            "'robots/<robot>/solids/<id>'), got '" +
            n + "'");
      for (int b : sim_.scene.robots[slot().robot].bodies)
        if (bodies[b].id == n) return BodyHandle{b + 1};
      throw fail(unknown("solid", n, robot_body_names(slot().robot)));
    }
    std::vector<std::string> all;
    for (std::size_t r = 0; r < sim_.scene.robots.size(); ++r)
      for (int b : sim_.scene.robots[r].bodies) {
        all.push_back(sim_.robot_prefix(static_cast<int>(r)) + "/solids/" +
                      sim::segment(bodies[b].id));
        if (all.back() == n) return BodyHandle{b + 1};
      }
    for (int b : sim_.scene.things) {
      all.push_back("things/" + sim::segment(bodies[b].id));
      if (all.back() == n) return BodyHandle{b + 1};
    }
    throw fail(unknown("body", n, all));
  }

  double body_mass_kg(BodyHandle b) const override {
    return b.index <= 0 ? 0.0 : sim_.scene.bodies[b.index - 1].mass_kg;
  }

  AxisHandle axis(std::string_view name) override {
    const std::string n(name);
    std::vector<std::string> names;
    for (std::size_t a = 0; a < sim_.axis_views.size(); ++a) {
      const auto& ax = sim_.axis_views[a];
      if (n.find('/') == std::string::npos) {
        if (ax.robot != slot().robot) continue;
        names.push_back(ax.name);
      } else {
        names.push_back(axis_prefix(AxisHandle{static_cast<std::int32_t>(a)}));
      }
      if (names.back() == n) return AxisHandle{static_cast<std::int32_t>(a)};
    }
    throw fail(unknown("axis", n, names));
  }

  bool axis_is_linear(AxisHandle a) const override { return sim_.axis_views.at(a.index).linear; }
  std::string axis_prefix(AxisHandle a) const override {
    const auto& ax = sim_.axis_views.at(a.index);
    return (ax.robot >= 0 ? sim_.robot_prefix(ax.robot) : std::string("world")) + "/axes/" +
           sim::segment(ax.name);
  }

  SignalHandle declare_signal(std::string_view name, std::string_view unit) override {
    return declare_signal_at(slot().prefix + "/" + std::string(name), unit);
  }
  SignalHandle declare_signal_at(std::string_view full_name, std::string_view unit) override {
    const std::string n(full_name);
    if (sim_.signal_by_name.count(n)) throw fail("signal '" + n + "' is already declared");
    const auto index = static_cast<std::int32_t>(sim_.published.size());
    sim_.published.push_back(0.0);
    sim_.add_signal(n, std::string(unit), Source::published, index);
    return SignalHandle{index};
  }
  InputHandle declare_input(std::string_view name, std::string_view unit, double initial) override {
    return declare_input_at(slot().prefix + "/" + std::string(name), unit, initial);
  }
  InputHandle declare_input_at(std::string_view full_name, std::string_view unit,
                               double initial) override {
    return InputHandle{
        sim_.add_input(std::string(full_name), std::string(unit), initial, slot().where)};
  }
  StateHandle declare_state(std::string_view name, int count, double initial) override {
    if (count <= 0) throw fail("state '" + std::string(name) + "' must have a positive size");
    const auto offset = static_cast<std::int32_t>(sim_.state_initial.size());
    sim_.state_initial.insert(sim_.state_initial.end(), static_cast<std::size_t>(count), initial);
    return StateHandle{offset, count};
  }
  const SensorSpec* sensor_spec() const override {
    if (slot().sensor < 0) return nullptr;
    const scene::Sensor& s = sim_.scene.sensors[static_cast<std::size_t>(slot().sensor)];
    SensorSpec& o = spec_;
    o.kind = s.kind;
    o.body = BodyHandle{s.body + 1};  // scene body i is body i + 1; -1 (world) is 0
    o.pose = s.pose;
    o.absolute_coords = s.absolute_coords;
    o.is_tool = s.is_tool;
    o.beam = {s.beam.length_m, s.beam.initial_width_m, s.beam.final_width_m, s.beam.angle_rad,
              s.beam.rays};
    o.noise = {s.noise.present, s.noise.stdev, s.noise.stdev_p, s.noise.offset,
               s.noise.gain,    s.noise.var_k, s.noise.var_d};
    o.tags = s.tags;
    o.period_s = s.period_s;
    o.force_fmax_N = s.force.fmax_N;
    o.force_k1 = s.force.k1;
    o.force_k2 = s.force.k2;
    return &o;
  }
  std::vector<FloorPolygon> floor_polygons() const override {
    std::vector<FloorPolygon> out;
    for (const auto& t : sim_.scene.tracks) {
      FloorPolygon p;
      p.tag = t.tag;
      p.z_m = t.z_m;
      for (const auto& [x, y] : t.vertices) {
        p.x_m.push_back(x);
        p.y_m.push_back(y);
      }
      out.push_back(std::move(p));
    }
    return out;
  }
  int body_count() const override { return static_cast<int>(sim_.poses.size()); }
  SignalHandle published_signal(std::string_view full_name) const override {
    auto it = sim_.signal_by_name.find(std::string(full_name));
    if (it != sim_.signal_by_name.end() &&
        sim_.signal_entries[it->second].source == Source::published)
      return SignalHandle{sim_.signal_entries[it->second].index};
    std::vector<std::string> names;
    for (std::size_t i = 0; i < sim_.signal_infos.size(); ++i)
      if (sim_.signal_entries[i].source == Source::published)
        names.push_back(sim_.signal_infos[i].name);
    throw fail(unknown("published signal", std::string(full_name), names));
  }
  JointHandle joint(std::string_view name) override {
    const std::string n(name);
    const auto& joints = sim_.scene.joints;
    std::vector<std::string> names;
    for (std::size_t j = 0; j < joints.size(); ++j) {
      if (n.find('/') == std::string::npos) {
        if (joints[j].robot != slot().robot) continue;
        names.push_back(joints[j].id);
      } else {
        names.push_back(sim_.joint_prefix(static_cast<int>(j)));
      }
      if (names.back() != n) continue;
      sim_.multibody->request_joint_reactions();
      if (sim_.multibody->joint_is_loop(static_cast<int>(j)))
        sim_.warnings.push_back(
            slot().where.str() + ": " + slot().label() + ": joint '" + joints[j].id +
            "' closes a kinematic loop (realised by constraints); its reaction reads zero");
      return JointHandle{static_cast<std::int32_t>(j)};
    }
    throw fail(unknown("joint", n, names));
  }
  BodyHandle joint_body(JointHandle j, int which) const override {
    const auto& jt = sim_.scene.joints.at(static_cast<std::size_t>(j.index));
    return BodyHandle{(which == 2 ? jt.body2 : jt.body1) + 1};  // scene -1 (world) is 0
  }
  std::string body_id(BodyHandle b) const override {
    if (b.index <= 0 || b.index > static_cast<int>(sim_.scene.bodies.size())) return {};
    return sim_.scene.bodies[static_cast<std::size_t>(b.index - 1)].id;
  }

  void set_schedule(Stage stage, double period_s, double phase_s) override {
    auto to_ticks = [&](double t, const char* what) {
      const double ticks = t / sim_.tick_s;
      const double rounded = std::round(ticks);
      if (!std::isfinite(ticks) || std::abs(ticks - rounded) > 1e-6 * std::max(1.0, ticks))
        throw fail(std::string(what) + " " + std::to_string(t) +
                   " s is not a whole multiple of the physics step " + std::to_string(sim_.tick_s) +
                   " s");
      return static_cast<std::int64_t>(rounded);
    };
    const std::int64_t period = to_ticks(period_s, "period");
    const std::int64_t phase = to_ticks(phase_s, "phase");
    if (period < 1) throw fail("period must be at least one physics step");
    if (phase < 0) throw fail("phase must not be negative");
    ComponentSlot& s = sim_.components[index_];
    s.stage = stage;
    s.period_ticks = period;
    s.phase_ticks = phase;
  }

 private:
  ComponentSlot& slot() const { return sim_.components[index_]; }
  Error fail(const std::string& message) const {
    return Error(ErrorKind::plugin, slot().where, slot().label() + ": " + message);
  }
  static std::string unknown(const char* what, const std::string& name,
                             const std::vector<std::string>& names) {
    return sim::unknown_name_message(what, name, names);
  }
  std::vector<std::string> robot_body_names(int robot) const {
    std::vector<std::string> names;
    for (int b : sim_.scene.robots[robot].bodies)
      names.push_back(sim_.scene.bodies[b].id);
    return names;
  }

  Simulation::Impl& sim_;
  int index_;
  mutable SensorSpec spec_;
};

}  // namespace

void Simulation::Impl::add_component(plugin::PluginRegistry& registry, const std::string& kind,
                                     const std::string& id, int robot,
                                     const scene::ParamSource& params, const Location& where,
                                     std::optional<Category> required) {
  const plugin::KindInfo* found = nullptr;
  try {
    found = &registry.find(kind);
  } catch (const Error& e) {
    throw Error(ErrorKind::plugin, where, e.message());  // say where the scene asks for it
  }
  const plugin::KindInfo& info = *found;
  if (required && info.category != *required)
    throw Error(ErrorKind::plugin, where,
                "kind '" + kind + "' from " + info.library.string() + " is not a sensor kind");
  ComponentSlot slot;
  slot.kind = kind;
  slot.id = id;
  slot.robot = robot;
  slot.category = info.category;
  slot.stage = default_stage(info.category);
  slot.where = where;
  slot.prefix = (robot >= 0 ? robot_prefix(robot) + "/" : std::string()) +
                category_folder(info.category) + "/" + sim::segment(id);
  slot.params = std::make_unique<scene::ElementParams>(params);
  if (info.category == Category::controller) {
    slot.period_ticks = std::max<std::int64_t>(
        1, static_cast<std::int64_t>(std::llround(scene.settings.control_period_s / tick_s)));
  }
  slot.component = registry.create(kind);
  components.push_back(std::move(slot));
}

void Simulation::Impl::configure_components() {
  for (std::size_t c = 0; c < components.size(); ++c) {
    ConfigureContextImpl ctx(*this, static_cast<int>(c));
    try {
      components[c].component->configure(ctx);
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      throw Error(ErrorKind::plugin, components[c].where,
                  components[c].label() + " refused its configuration: " + e.what());
    }
  }
  for (std::size_t c = 0; c < components.size(); ++c)
    stage_order[static_cast<std::size_t>(components[c].stage)].push_back(static_cast<int>(c));
}

// --- façade ------------------------------------------------------------------------------------

Simulation::Simulation(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Simulation::~Simulation() = default;

std::unique_ptr<Simulation> Simulation::load(const std::filesystem::path& scene_path,
                                             const SimulationOptions& options) {
  auto impl = std::make_unique<Impl>();
  Impl& m = *impl;
  m.options = options;
  scene::LoadOptions load_options;
  load_options.constants = options.constants;
  m.scene = scene::load_scene(scene_path, load_options);
  m.warnings = m.scene.warnings;

  if (options.physics_step_s) m.scene.settings.physics_step_s = *options.physics_step_s;
  if (options.substeps) m.scene.settings.substeps = *options.substeps;
  if (!(m.scene.settings.physics_step_s > 0) || !std::isfinite(m.scene.settings.physics_step_s))
    throw Error(ErrorKind::usage, "the physics step must be positive, got " +
                                      std::to_string(m.scene.settings.physics_step_s) + " s");
  if (m.scene.settings.substeps < 1)
    throw Error(ErrorKind::usage,
                "substeps must be at least 1, got " + std::to_string(m.scene.settings.substeps));
  m.tick_s = m.scene.settings.physics_step_s;

  m.multibody = std::make_unique<model::Multibody>(m.scene, m.tick_s, m.scene.settings.substeps);
  m.shapes = std::make_unique<collision::ShapeTable>(m.scene);
  m.contacts =
      std::make_unique<contact::ContactWorld>(*m.shapes, m.scene, m.multibody->apparent_mass_kg());
  m.multibody->set_substep_forces(m.contacts.get());
  for (const auto& w : m.multibody->warnings())
    m.warnings.push_back(w);
  for (const auto& ax : m.multibody->axes())
    m.axis_views.push_back({ax.name, ax.robot, ax.joint, ax.linear});
  m.poses.resize(static_cast<std::size_t>(m.multibody->body_count()));
  m.twists.resize(m.poses.size());
  m.axis_position.assign(m.axis_views.size(), 0.0);
  m.axis_velocity.assign(m.axis_views.size(), 0.0);
  m.axis_force_applied.assign(m.axis_views.size(), 0.0);
  m.register_kernel_signals();

  // Components: scene sensors with a plugin for their kind, then <plugin> instances, then the
  // drive train of every axis (sim/drive_train_components.hpp).
  const bool needs_plugins =
      !m.scene.sensors.empty() || !m.scene.plugins.empty() || !m.axis_views.empty();
  std::optional<plugin::PluginRegistry> registry;
  if (needs_plugins)
    registry.emplace(options.plugin_path.empty() ? plugin::PluginRegistry::default_search_path()
                                                 : options.plugin_path);
  for (const auto& sensor : m.scene.sensors) {
    if (!registry->has(sensor.kind)) {
      m.warnings.push_back(sensor.where.str() + ": no plugin provides the sensor kind '" +
                           sensor.kind + "'; sensor '" + sensor.id + "' is inert");
      continue;
    }
    m.add_component(*registry, sensor.kind, sensor.id, sensor.robot, sensor.params, sensor.where,
                    Category::sensor);
    m.components.back().sensor = static_cast<int>(&sensor - m.scene.sensors.data());
  }
  for (const auto& p : m.scene.plugins)
    m.add_component(*registry, p.kind, p.id, p.robot, p.params, p.where, std::nullopt);
  std::vector<sim::DriveAxis> drive_axes;
  for (const auto& ax : m.multibody->axes())
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
  m.configure_components();

  m.state = m.state_initial;
  m.random.assign(4 * m.components.size(), 0);
  m.world.body_pose = m.poses.data();
  m.world.body_twist = m.twists.data();
  m.world.body_wrench = m.multibody->applied_wrenches();
  m.world.axis_position = m.axis_position.data();
  m.world.axis_velocity = m.axis_velocity.data();
  m.world.axis_force = m.multibody->applied_axis_forces();
  m.world.axis_friction = m.multibody->applied_axis_friction();
  m.world.inputs = m.inputs.data();
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
  m.reset();
  return std::unique_ptr<Simulation>(new Simulation(std::move(impl)));
}

const scene::Scene& Simulation::scene() const {
  return impl_->scene;
}
const std::vector<std::string>& Simulation::warnings() const {
  return impl_->warnings;
}
double Simulation::time_s() const {
  return static_cast<double>(impl_->tick) * impl_->tick_s;
}
std::int64_t Simulation::tick() const {
  return impl_->tick;
}
double Simulation::tick_s() const {
  return impl_->tick_s;
}

void Simulation::step(std::int64_t ticks) {
  for (std::int64_t i = 0; i < ticks; ++i)
    impl_->step_once();
}

void Simulation::run_until(double t_s) {
  const auto target = static_cast<std::int64_t>(std::llround(t_s / impl_->tick_s));
  while (impl_->tick < target)
    impl_->step_once();
}

void Simulation::reset() {
  impl_->reset();
}

std::size_t Simulation::signal_count() const {
  return impl_->signal_infos.size();
}
const SignalInfo& Simulation::signal_info(std::size_t i) const {
  return impl_->signal_infos.at(i);
}
std::optional<std::size_t> Simulation::find_signal(std::string_view name) const {
  auto it = impl_->signal_by_name.find(std::string(name));
  if (it == impl_->signal_by_name.end()) return std::nullopt;
  return it->second;
}
std::size_t Simulation::signal_index(std::string_view name) const {
  if (auto i = find_signal(name)) return *i;
  std::vector<std::string> names;
  for (const auto& s : impl_->signal_infos)
    names.push_back(s.name);
  throw Error(ErrorKind::usage, sim::unknown_name_message("signal", name, names));
}
double Simulation::signal(std::size_t index) const {
  return impl_->read_signal(index);
}
std::vector<std::size_t> Simulation::match_signals(std::string_view pattern) const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < impl_->signal_infos.size(); ++i)
    if (sim::glob_match(pattern, impl_->signal_infos[i].name)) out.push_back(i);
  return out;
}

std::size_t Simulation::input_count() const {
  return impl_->input_infos.size();
}
const SignalInfo& Simulation::input_info(std::size_t i) const {
  return impl_->input_infos.at(i);
}
std::size_t Simulation::input_index(std::string_view name) const {
  auto it = impl_->input_by_name.find(std::string(name));
  if (it != impl_->input_by_name.end()) return it->second;
  std::vector<std::string> names;
  for (const auto& s : impl_->input_infos)
    names.push_back(s.name);
  throw Error(ErrorKind::usage, sim::unknown_name_message("input", name, names));
}
void Simulation::set_input(std::size_t index, double value) {
  if (!std::isfinite(value))
    throw Error(ErrorKind::usage, "input '" + impl_->input_infos.at(index).name +
                                      "' must be finite, got " + std::to_string(value));
  impl_->inputs.at(index) = value;
}
double Simulation::input(std::size_t index) const {
  return impl_->inputs.at(index);
}

int Simulation::body_count() const {
  return static_cast<int>(impl_->poses.size());
}
const Pose& Simulation::body_pose(int body) const {
  return impl_->poses.at(body);
}
const Twist& Simulation::body_twist(int body) const {
  return impl_->twists.at(body);
}
RayHit Simulation::cast_ray(const Vec3& origin_m, const Vec3& direction, double max_distance_m,
                            int ignore_body) const {
  return impl_->ray_caster->cast(origin_m, direction, max_distance_m, ignore_body);
}

std::size_t Simulation::axis_count() const {
  return impl_->axis_views.size();
}
const Simulation::AxisView& Simulation::axis(std::size_t i) const {
  return impl_->axis_views.at(i);
}
double Simulation::axis_position(std::size_t i) const {
  return impl_->axis_position.at(i);
}
double Simulation::axis_velocity(std::size_t i) const {
  return impl_->axis_velocity.at(i);
}

std::size_t Simulation::contact_count() const {
  return static_cast<std::size_t>(*impl_->contacts->contact_count());
}
const ContactInfo& Simulation::contact(std::size_t index) const {
  if (index >= contact_count())
    throw Error(ErrorKind::usage,
                "contact " + std::to_string(index) + " of " + std::to_string(contact_count()));
  return impl_->contacts->contacts()[index];
}

double Simulation::kinetic_energy_J() const {
  return impl_->multibody->kinetic_energy_J();
}
double Simulation::potential_energy_J() const {
  return impl_->multibody->potential_energy_J();
}

Simulation::Snapshot Simulation::save() const {
  const Impl& m = *impl_;
  Snapshot s;
  s.values = m.multibody->save();
  auto append = [&](const std::vector<double>& v) {
    s.values.push_back(static_cast<double>(v.size()));
    s.values.insert(s.values.end(), v.begin(), v.end());
  };
  append(m.inputs);
  append(m.published);
  append(m.state);
  append(m.axis_force_applied);
  s.random = m.random;
  m.contacts->save(s.contacts);
  return s;
}

void Simulation::restore(const Snapshot& snapshot) {
  Impl& m = *impl_;
  // The tail holds four sized blocks; walk them from the back to find the multibody part.
  const auto& v = snapshot.values;
  std::vector<std::vector<double>*> blocks = {&m.inputs, &m.published, &m.state,
                                              &m.axis_force_applied};
  std::size_t multibody_size = v.size();
  for (auto it = blocks.rbegin(); it != blocks.rend(); ++it)
    multibody_size -= (*it)->size() + 1;
  m.multibody->restore(
      std::vector<double>(v.begin(), v.begin() + static_cast<long>(multibody_size)));
  std::size_t k = multibody_size;
  for (auto* b : blocks) {
    const auto n = static_cast<std::size_t>(v.at(k++));
    if (n != b->size()) throw Error(ErrorKind::usage, "snapshot from another simulation");
    std::copy(v.begin() + static_cast<long>(k), v.begin() + static_cast<long>(k + n), b->begin());
    k += n;
  }
  m.random = snapshot.random;
  m.contacts->restore(snapshot.contacts, 0);
  m.world.contacts = m.contacts->contacts();
  m.tick = static_cast<std::int64_t>(std::llround(m.multibody->time_s() / m.tick_s));
  m.refresh();
}

void Simulation::place_body(int body, const Pose& pose) {
  Impl& m = *impl_;
  const auto& bodies = m.scene.bodies;
  const std::string name = body > 0 && body <= static_cast<int>(bodies.size())
                               ? "'" + bodies[body - 1].id + "'"
                               : "index " + std::to_string(body);
  if (!m.multibody->place_free_body(body, pose))
    throw Error(ErrorKind::usage,
                "body " + name +
                    " cannot be placed: only a thing or a robot's root body (free "
                    "on the world) can be moved");
  m.refresh();
}

}  // namespace s2sim
