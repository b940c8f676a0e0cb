// Component instances: creation from the plugin registry, and the ConfigureContext through
// which each declares its signals, inputs, state and schedule.
#include "common/assert.hpp"
#include "common/closest_names.hpp"
#include "sim/names.hpp"
#include "sim/running_component.hpp"
#include "sim/simulation_impl.hpp"

#include <algorithm>
#include <cmath>
#include <new>

namespace s2sim {

namespace {

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

/// The ConfigureContext a component sees while the simulation is being built.
class ConfigureContextImpl final : public ConfigureContext {
 public:
  ConfigureContextImpl(Simulation::Impl& sim, int component_index)
      : sim_(sim), index_(component_index) {
    S2SIM_ASSERT(
        component_index >= 0 && static_cast<std::size_t>(component_index) < sim.components.size(),
        "configure context for a component that does not exist");
  }

  const Params& params() const override { return *slot().params; }
  std::string_view id() const override { return slot().id; }
  std::string_view signal_prefix() const override { return slot().prefix; }
  void refuse_unread_attributes() override { slot().strict_attributes = true; }
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
        if (bodies[b].id == n) return noted_body(b + 1);
      throw fail(unknown("solid", n, robot_body_names(slot().robot)));
    }
    std::vector<std::string> all;
    for (std::size_t r = 0; r < sim_.scene.robots.size(); ++r)
      for (int b : sim_.scene.robots[r].bodies) {
        all.push_back(sim::solid_path(sim_.robot_prefix(static_cast<int>(r)), bodies[b].id));
        if (all.back() == n) return noted_body(b + 1);
      }
    for (int b : sim_.scene.things) {
      all.push_back(sim::thing_path(bodies[b].id));
      if (all.back() == n) return noted_body(b + 1);
    }
    throw fail(unknown("body", n, all));
  }

  double body_mass_kg(BodyHandle b) const override {
    return b.index <= 0 ? 0.0 : sim_.scene.bodies[b.index - 1].mass_kg;
  }

  AxisHandle axis(std::string_view name) override {
    const std::string n(name);
    if (n.find('/') != std::string::npos) {
      const auto found = sim_.axis_of_path.find(n);
      if (found != sim_.axis_of_path.end()) {
        slot().footprint.axes.push_back(found->second);
        return AxisHandle{found->second};
      }
    }
    std::vector<std::string> names;  // the own robot's axes, or every path: for the error
    for (std::size_t a = 0; a < sim_.axis_views.size(); ++a) {
      const auto& ax = sim_.axis_views[a];
      if (n.find('/') == std::string::npos) {
        if (ax.robot != slot().robot) continue;
        names.push_back(ax.name);
      } else {
        names.push_back(axis_prefix(AxisHandle{static_cast<std::int32_t>(a)}));
      }
      if (names.back() == n) {
        slot().footprint.axes.push_back(static_cast<std::int32_t>(a));
        return AxisHandle{static_cast<std::int32_t>(a)};
      }
    }
    throw fail(unknown("axis", n, names));
  }

  bool axis_is_linear(AxisHandle a) const override { return sim_.axis_views.at(a.index).linear; }
  std::string axis_prefix(AxisHandle a) const override {
    // The handle comes from the plugin: a bad one is the plugin's error, not an invariant.
    if (a.index < 0 || static_cast<std::size_t>(a.index) >= sim_.axis_views.size())
      throw fail("axis handle " + std::to_string(a.index) + " is out of range");
    return sim_.axis_prefix(a.index);
  }

  SignalHandle declare_signal(std::string_view name, std::string_view unit) override {
    return declare_signal_at(sim::field_path(slot().prefix, name), unit);
  }
  SignalHandle declare_signal_at(std::string_view full_name, std::string_view unit) override {
    const std::string n(full_name);
    if (sim_.signal_by_name.count(n)) throw fail("signal '" + n + "' is already declared");
    const auto index = static_cast<std::int32_t>(sim_.published.size());
    sim_.published.push_back(0.0);
    sim_.publisher.push_back(index_);
    sim_.add_signal(n, std::string(unit), sim::Source::published, index);
    return SignalHandle{index};
  }
  InputHandle declare_input(std::string_view name, std::string_view unit, double initial,
                            const Range& valid) override {
    return declare_input_at(sim::field_path(slot().prefix, name), unit, initial, valid);
  }
  InputHandle declare_input_at(std::string_view full_name, std::string_view unit, double initial,
                               const Range& valid) override {
    const std::int32_t input =
        sim_.add_input(std::string(full_name), std::string(unit), initial, slot().where, valid);
    slot().footprint.inputs.push_back(input);
    return InputHandle{input};
  }
  StateHandle declare_state(std::string_view name, int count, double initial) override {
    if (count <= 0) throw fail("state '" + std::string(name) + "' must have a positive size");
    const auto offset = static_cast<std::int32_t>(sim_.state_initial.size());
    sim_.state_initial.insert(sim_.state_initial.end(), static_cast<std::size_t>(count), initial);
    return StateHandle{offset, count};
  }
  ImageHandle declare_image(std::string_view name, int width_px, int height_px,
                            PixelFormat format) override {
    try {
      return ImageHandle{sim_.add_image(sim::field_path(slot().prefix, name), width_px, height_px,
                                        format, index_)};
    } catch (const Error& e) {
      throw fail(e.what());
    }
  }
  ImageHandle image(std::string_view full_name) const override {
    const std::int32_t i = sim_.image_index(full_name);
    if (i >= 0) return ImageHandle{i};
    std::vector<std::string> names;
    for (const auto& img : sim_.image_slots)
      names.push_back(img.name);
    throw fail(unknown("image", std::string(full_name), names));
  }
  const SensorSpec* sensor_spec() const override {
    if (slot().sensor < 0) return nullptr;
    S2SIM_ASSERT(static_cast<std::size_t>(slot().sensor) < sim_.scene.sensors.size(),
                 "component's scene sensor out of range");
    const scene::Sensor& s = sim_.scene.sensors[static_cast<std::size_t>(slot().sensor)];
    SensorSpec& o = spec_;
    o.kind = s.kind;
    o.body = BodyHandle{s.body + 1};  // scene body i is body i + 1; -1 (world) is 0
    if (s.body >= 0) slot().footprint.bodies.push_back(s.body + 1);
    o.pose = s.pose;
    o.beam = s.beam;  // the SDK's types: the loader's defaults and rules
    o.noise = s.noise;
    o.period_s = s.period_s;
    o.simtwo.absolute_coords = s.absolute_coords;
    o.simtwo.is_tool = s.is_tool;
    o.simtwo.tags = s.tags;
    o.simtwo.solenoid_force = s.force;
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
  std::vector<PaintingTarget> painting_targets() const override { return sim_.painting_targets(); }
  int body_count() const override { return static_cast<int>(sim_.poses.size()); }
  SignalHandle published_signal(std::string_view full_name) const override {
    auto it = sim_.signal_by_name.find(std::string(full_name));
    if (it != sim_.signal_by_name.end() &&
        sim_.signal_entries[it->second].source == sim::Source::published) {
      slot().footprint.published.push_back(sim_.signal_entries[it->second].index);
      return SignalHandle{sim_.signal_entries[it->second].index};
    }
    std::vector<std::string> names;
    for (std::size_t i = 0; i < sim_.signal_infos.size(); ++i)
      if (sim_.signal_entries[i].source == sim::Source::published)
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
      sim_.joint_reactions_wanted = true;  // asked of the multibody once it is built
      if (sim_.topology.joint_is_loop[j])
        sim_.warnings.push_back(
            slot().where.str() + ": " + slot().label() + ": joint '" + joints[j].id +
            "' closes a kinematic loop (realised by constraints); its reaction reads zero");
      slot().footprint.joints.push_back(static_cast<std::int32_t>(j));
      return JointHandle{static_cast<std::int32_t>(j)};
    }
    throw fail(unknown("joint", n, names));
  }
  BodyHandle joint_body(JointHandle j, int which) const override {
    const auto& jt = sim_.scene.joints.at(static_cast<std::size_t>(j.index));
    const int body = (which == 2 ? jt.body2 : jt.body1) + 1;  // scene -1 (world) is 0
    if (body > 0) slot().footprint.bodies.push_back(body);
    return BodyHandle{body};
  }
  std::string body_id(BodyHandle b) const override {
    if (b.index <= 0 || b.index > static_cast<int>(sim_.scene.bodies.size())) return {};
    return sim_.scene.bodies[static_cast<std::size_t>(b.index - 1)].id;
  }

  void warn(std::string_view message) override {
    sim_.warnings.push_back(slot().where.str() + ": " + slot().label() + ": " +
                            std::string(message));
  }
  void add_axis_inertia(AxisHandle a, double inertia) override {
    if (a.index < 0 || a.index >= static_cast<std::int32_t>(sim_.axis_inertia.size()))
      throw fail("add_axis_inertia: invalid axis handle");
    if (!(inertia >= 0) || !std::isfinite(inertia))
      throw fail("add_axis_inertia: the inertia of axis '" +
                 sim_.axis_views[static_cast<std::size_t>(a.index)].name +
                 "' must be finite and >= 0, got " + std::to_string(inertia));
    sim_.axis_inertia[static_cast<std::size_t>(a.index)] += inertia;
  }

  std::uint64_t seed() const override { return sim_.options.seed; }
  void declare_local() override { slot().local = true; }

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
    if (static_cast<std::size_t>(stage) >= sim_.stage_order.size())
      throw fail("unknown stage " + std::to_string(static_cast<int>(stage)));
    sim::ComponentSlot& s = sim_.components[index_];
    s.stage = stage;
    s.period_ticks = period;
    s.phase_ticks = phase;
  }

  std::vector<NamedUnit> signal_names(std::string_view pattern) const override {
    std::vector<NamedUnit> out;
    for (const auto& info : sim_.signal_infos)
      if (sim::glob_match(pattern, info.name)) out.push_back({info.name, info.unit});
    return out;
  }
  std::vector<NamedUnit> input_names(std::string_view pattern) const override {
    std::vector<NamedUnit> out;
    for (const auto& info : sim_.input_infos)
      if (sim::glob_match(pattern, info.name)) out.push_back({info.name, info.unit});
    return out;
  }
  InputHandle input(std::string_view full_name) override {
    auto it = sim_.input_by_name.find(std::string(full_name));
    if (it != sim_.input_by_name.end()) {
      slot().footprint.inputs.push_back(static_cast<std::int32_t>(it->second));
      return InputHandle{static_cast<std::int32_t>(it->second)};
    }
    std::vector<std::string> names;
    for (const auto& info : sim_.input_infos)
      names.push_back(info.name);
    throw fail(unknown("input", std::string(full_name), names));
  }
  SignalReader signal_reader(std::string_view full_name) const override {
    auto it = sim_.signal_by_name.find(std::string(full_name));
    if (it != sim_.signal_by_name.end()) {
      slot().footprint.readers.push_back(static_cast<std::int32_t>(it->second));
      return SignalReader{&Simulation::Impl::read_signal_callback, &sim_,
                          static_cast<std::int32_t>(it->second)};
    }
    std::vector<std::string> names;
    for (const auto& info : sim_.signal_infos)
      names.push_back(info.name);
    throw fail(unknown("signal", std::string(full_name), names));
  }

 private:
  sim::ComponentSlot& slot() const { return sim_.components[index_]; }
  BodyHandle noted_body(int body) const {
    slot().footprint.bodies.push_back(body);
    return BodyHandle{body};
  }
  Error fail(const std::string& message) const {
    return Error(ErrorKind::plugin, slot().where, slot().label() + ": " + message);
  }
  static std::string unknown(const char* what, const std::string& name,
                             const std::vector<std::string>& names) {
    return common::unknown_name_message(what, name, names);
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
  sim::ComponentSlot slot;
  slot.kind = kind;
  slot.id = id;
  slot.robot = robot;
  slot.category = info.category;
  slot.stage = default_stage(info.category);
  slot.where = where;
  slot.prefix = sim::component_path(robot >= 0 ? robot_prefix(robot) : std::string(),
                                    category_folder(info.category), id);
  slot.params = std::make_unique<scene::ElementParams>(params);
  if (info.category == Category::controller) {
    slot.period_ticks = std::max<std::int64_t>(
        1, static_cast<std::int64_t>(std::llround(scene.settings.control_period_s / tick_s)));
  }
  slot.library = info.library.string();
  slot.crash_label = "component '" + slot.prefix + "' (kind '" + kind + "') from " + slot.library;
  {
    // The factory runs the component's constructor: a crash there is reported as its own.
    const sim::RunningComponent running(slot.crash_label.c_str());
    slot.component = registry.create(kind);
  }
  components.push_back(std::move(slot));
}

sim::ComponentSlot::~ComponentSlot() {
  if (!component) return;
  const RunningComponent running(crash_label.c_str());
  component = plugin::ComponentPtr();
}

void sim::rethrow_from_component(const ComponentSlot& slot, const char* call, ErrorKind fallback) {
  const std::string label = slot.label();
  const std::string from = " from " + slot.library;
  try {
    throw;
  } catch (const Error& e) {
    // Copied while the plugin is still loaded. A located error (a parameter's, through
    // Params) or one that names the component already (a ConfigureContext lookup) keeps its
    // words; any other gets the component's place and name.
    const Location& at = e.where();
    if (!at.element.empty() || !at.attribute.empty()) {  // located by the plugin or Params
      throw Error(e.kind(),
                  Location{at.file.empty() ? slot.where.file : at.file, at.element, at.attribute},
                  e.message());
    }
    if (!at.file.empty() || e.message().rfind(label, 0) == 0)
      throw Error(e.kind(), at, e.message());
    throw Error(e.kind(), slot.where, label + from + ", " + call + ": " + e.message());
  } catch (const std::bad_alloc&) {
    throw;  // out of memory is the system's refusal, not the component's error
  } catch (const std::exception& e) {
    throw Error(fallback, slot.where, label + from + ", " + call + ": " + e.what());
  } catch (...) {
    throw Error(fallback, slot.where,
                label + from + ", " + call + ": threw something that is not an exception");
  }
}

void Simulation::Impl::configure_components() {
  for (std::size_t c = 0; c < components.size(); ++c) {
    ConfigureContextImpl ctx(*this, static_cast<int>(c));
    try {
      const sim::RunningComponent running(components[c].crash_label.c_str());
      components[c].component->configure(ctx);
    } catch (...) {
      sim::rethrow_from_component(components[c], "configure", ErrorKind::plugin);
    }
  }
  for (std::size_t c = 0; c < components.size(); ++c) {
    const auto stage = static_cast<std::size_t>(components[c].stage);
    S2SIM_ASSERT(stage < stage_order.size(), "component stage outside the pipeline");
    stage_order[stage].push_back(static_cast<int>(c));
  }
}

namespace {

// The unread attributes of `element` and its children, as located warnings.
void collect_unread(const scene::ElementParams& params, const scene::Element& element, bool is_root,
                    const std::string& kind, std::vector<std::string>& out) {
  for (std::size_t i = 0; i < element.attributes.size(); ++i) {
    const std::string& name = element.attributes[i].first;
    if (is_root && (name == "kind" || name == "id")) continue;  // the loader's
    if (params.asked(&element, name)) continue;
    const std::string& at = element.attribute_paths.size() == element.attributes.size()
                                ? element.attribute_paths[i]
                                : element.path;
    std::string message = Location{params.source().file, at, name}.str() +
                          ": attribute ignored: kind '" + kind + "' does not read it";
    // Names the component asked for here and did not find: the misspelling's likely target.
    std::vector<std::string> missing;
    for (const std::string& asked : params.asked_on(&element))
      if (element.attribute(asked) == nullptr) missing.push_back(asked);
    const std::size_t allowed = std::max<std::size_t>(2, name.size() / 3);
    std::vector<std::string> close;
    for (const std::string& c : common::closest_names(name, missing, 2))
      if (common::edit_distance(name, c) <= allowed) close.push_back("'" + c + "'");
    if (!close.empty()) {
      message += "; did you mean " + close[0];
      if (close.size() > 1) message += " or " + close[1];
      message += "?";
    }
    out.push_back(std::move(message));
  }
  for (const auto& child : element.children)
    collect_unread(params, child, false, kind, out);
}

}  // namespace

void Simulation::Impl::warn_unread_plugin_attributes() {
  for (const auto& slot : components) {
    if (!slot.plugin_element || !slot.params) continue;
    if (!slot.strict_attributes) {
      collect_unread(*slot.params, slot.params->source().element, true, slot.kind, warnings);
      continue;
    }
    std::vector<std::string> unread;
    collect_unread(*slot.params, slot.params->source().element, true, slot.kind, unread);
    if (unread.empty()) continue;
    // "file: element@attribute: attribute ignored: ..." becomes a refusal of the scene.
    std::string message = unread.front();
    const std::string ignored = "attribute ignored: ";
    if (const auto at = message.find(ignored); at != std::string::npos)
      message.replace(at, ignored.size(), "unknown attribute: ");
    throw Error(ErrorKind::scene, message);
  }
}

// --- façade ------------------------------------------------------------------------------------

}  // namespace s2sim
