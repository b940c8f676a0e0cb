// The signal and input registry: every readable value has a name, a unit and a source.
#include "common/assert.hpp"
#include "common/closest_names.hpp"
#include "sim/names.hpp"
#include "sim/simulation_impl.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

namespace s2sim {

std::size_t Simulation::Impl::add_signal(std::string name, std::string unit, sim::Source source,
                                         std::int32_t index) {
  // read_signal() indexes the source's buffer unchecked: the entry must point into it.
  const std::size_t extent = [&]() -> std::size_t {
    switch (source) {
      case sim::Source::published:
        return published.size();
      case sim::Source::input:
        return inputs.size();
      case sim::Source::time:
      case sim::Source::contact_count:
        return 1;
      case sim::Source::axis_position:
      case sim::Source::axis_velocity:
      case sim::Source::axis_force:
        return axis_force_applied.size();
      default:  // the body sources
        return poses.size();
    }
  }();
  S2SIM_ASSERT(index >= 0 && static_cast<std::size_t>(index) < extent,
               "signal index out of its source's buffer");
  S2SIM_ASSERT(signal_infos.size() == signal_entries.size(),
               "signal names and entries out of step");
  // Duplicate scene IDs are legal in SimTwo; later ones get a "#n" suffix.
  std::string unique = name;
  for (int n = 2; signal_by_name.count(unique); ++n)
    unique = name + "#" + std::to_string(n);
  signal_by_name.emplace(unique, signal_infos.size());
  signal_infos.push_back({unique, std::move(unit)});
  signal_entries.push_back({source, index});
  return signal_infos.size() - 1;
}

namespace {

/// The sanity bound of an input of `unit` that its component leaves unbounded: magnitudes no
/// honest scene reaches, so that a value such as 1e30 N from a remote peer or a script's bug
/// is refused rather than applied. Inputs of other units only have to be finite.
double unit_bound(std::string_view unit) {
  struct Bound {
    std::string_view unit;
    double magnitude;
  };
  static constexpr Bound kBounds[] = {
      {"V", 1e5},    {"A", 1e5},        {"N", 1e8},      {"N*m", 1e8},
      {"m/s", 1e6},  {"rad/s", 1e6},    {"m", 1e9},      {"rad", 1e9},
      {"ohm", 1e9},  {"H", 1e6},        {"N/A", 1e6},    {"N*m/A", 1e6},
      {"N/m", 1e12}, {"N*m/rad", 1e12}, {"N*s/m", 1e12}, {"N*m*s/rad", 1e12},
  };
  for (const Bound& b : kBounds)
    if (b.unit == unit) return b.magnitude;
  return std::numeric_limits<double>::max();
}

std::string range_text(double min, double max) {
  return "[" + sim::short_decimal(min) + ", " + sim::short_decimal(max) + "]";
}

}  // namespace

std::int32_t Simulation::Impl::add_input(const std::string& name, const std::string& unit,
                                         double initial, const Location& where,
                                         const Range& valid) {
  // Bounds included: an exclusive one becomes the next double inside.
  const double bound = unit_bound(unit);
  double min = std::isinf(valid.min) ? -bound : valid.min;
  double max = std::isinf(valid.max) ? bound : valid.max;
  if (valid.min_exclusive) min = std::nextafter(min, max);
  if (valid.max_exclusive) max = std::nextafter(max, min);
  std::size_t index = inputs.size();
  if (auto it = input_by_name.find(name); it != input_by_name.end()) {
    index = it->second;
    if (input_infos[index].unit != unit)
      throw Error(ErrorKind::plugin, where,
                  "input '" + name + "' is declared with unit '" + unit +
                      "' but already exists with unit '" + input_infos[index].unit + "'");
    min = std::max(min, input_min[index]);
    max = std::min(max, input_max[index]);
  }
  if (!(min <= max))
    throw Error(ErrorKind::plugin, where,
                "input '" + name + "': its ranges leave no value " + range_text(min, max));
  if (!(initial >= min && initial <= max))
    throw Error(ErrorKind::plugin, where,
                "input '" + name + "': the initial value " + sim::short_decimal(initial) +
                    " is outside its range " + range_text(min, max));
  if (index < inputs.size()) {
    input_min[index] = min;
    input_max[index] = max;
    return static_cast<std::int32_t>(index);
  }
  input_by_name.emplace(name, index);
  input_infos.push_back({name, unit});
  inputs.push_back(initial);
  inputs_initial.push_back(initial);
  input_min.push_back(min);
  input_max.push_back(max);
  S2SIM_ASSERT(input_infos.size() == inputs.size() && inputs_initial.size() == inputs.size(),
               "input names, values and initial values out of step");
  add_signal(name, unit, sim::Source::input, static_cast<std::int32_t>(index));
  return static_cast<std::int32_t>(index);
}

std::string Simulation::Impl::robot_prefix(int robot) const {
  return sim::robot_path(scene.robots[robot].id);
}
std::string Simulation::Impl::scope_prefix(int robot) const {
  return robot >= 0 ? robot_prefix(robot) : std::string(sim::kWorldScope);
}
std::string Simulation::Impl::joint_prefix(int joint) const {
  const auto& jt = scene.joints[static_cast<std::size_t>(joint)];
  return sim::joint_path(scope_prefix(jt.robot), jt.id);
}
std::string Simulation::Impl::axis_prefix(int axis) const {
  const AxisView& ax = axis_views[static_cast<std::size_t>(axis)];
  return sim::axis_path(scope_prefix(ax.robot), ax.name);
}

std::string Simulation::body_path(int body) const {
  const Impl& m = *impl_;
  if (body < 0 || body > static_cast<int>(m.scene.bodies.size()))
    throw Error(ErrorKind::usage, "body index " + std::to_string(body) + " is out of range (0 to " +
                                      std::to_string(m.scene.bodies.size()) + ")");
  if (body == 0) return std::string(sim::kWorldScope);
  const auto& b = m.scene.bodies[static_cast<std::size_t>(body - 1)];
  const auto& spare = m.scene.runtime_things;
  if (!spare.empty() && body - 1 >= spare.front())
    return "runtime_things/" + std::to_string(body - 1 - spare.front());
  return b.robot >= 0 ? sim::solid_path(m.robot_prefix(b.robot), b.id) : sim::thing_path(b.id);
}
std::string Simulation::axis_path(std::size_t index) const {
  if (index >= impl_->axis_views.size())
    throw Error(ErrorKind::usage, "axis index " + std::to_string(index) + " is out of range (" +
                                      std::to_string(impl_->axis_views.size()) + " axes)");
  return impl_->axis_prefix(static_cast<int>(index));
}

void Simulation::Impl::register_kernel_signals() {
  add_signal("time", "s", sim::Source::time, 0);
  add_signal("contacts/count", "1", sim::Source::contact_count, 0);
  auto add_body = [&](const std::string& p, int body) {
    const std::pair<const char*, sim::Source> fields[] = {
        {"x", sim::Source::body_x},         {"y", sim::Source::body_y},
        {"z", sim::Source::body_z},         {"roll", sim::Source::body_roll},
        {"pitch", sim::Source::body_pitch}, {"yaw", sim::Source::body_yaw},
        {"vx", sim::Source::body_vx},       {"vy", sim::Source::body_vy},
        {"vz", sim::Source::body_vz},       {"wx", sim::Source::body_wx},
        {"wy", sim::Source::body_wy},       {"wz", sim::Source::body_wz}};
    for (const auto& [name, source] : fields) {
      const std::string_view n = name;
      const char* unit = n[0] == 'v' ? "m/s" : n[0] == 'w' ? "rad/s" : n.size() == 1 ? "m" : "rad";
      add_signal(sim::field_path(p, name), unit, source, body);
    }
    add_signal(sim::field_path(p, "contact_force"), "N", sim::Source::body_contact_force, body);
  };
  for (std::size_t r = 0; r < scene.robots.size(); ++r) {
    const auto& robot = scene.robots[r];
    if (robot.main_body >= 0) add_body(robot_prefix(static_cast<int>(r)), robot.main_body + 1);
    for (int b : robot.bodies)
      add_body(sim::solid_path(robot_prefix(static_cast<int>(r)), scene.bodies[b].id), b + 1);
  }
  for (int b : scene.things)
    add_body(sim::thing_path(scene.bodies[b].id), b + 1);
  // Spare bodies by number: which thing holds one is known only while running.
  for (std::size_t k = 0; k < scene.runtime_things.size(); ++k)  // as body_path() names them
    add_body("runtime_things/" + std::to_string(k), scene.runtime_things[k] + 1);
  // A conveyor belt's surface speed along its +X, settable at run time (spec §4.3).
  // Handed to contact once it exists (it is built after the components, with the multibody).
  for (std::int32_t s = 0; s < shapes->size(); ++s) {
    if (!shapes->surfaces()[static_cast<std::size_t>(s)].belt) continue;
    const std::int32_t body = shapes->bodies()[static_cast<std::size_t>(s)];
    const auto& b = scene.bodies[body - 1];
    const std::string p =
        b.robot >= 0 ? sim::solid_path(robot_prefix(b.robot), b.id) : sim::thing_path(b.id);
    belt_speed_inputs.emplace_back(
        body, add_input(sim::field_path(p, "belt_speed"), "m/s", 0.5, b.where));
  }
  for (std::size_t a = 0; a < axis_views.size(); ++a) {
    const AxisView& ax = axis_views[a];
    const auto i = static_cast<std::int32_t>(a);
    const std::string p = axis_prefix(i);
    add_signal(sim::field_path(p, "pos"), ax.linear ? "m" : "rad", sim::Source::axis_position, i);
    add_signal(sim::field_path(p, "speed"), ax.linear ? "m/s" : "rad/s", sim::Source::axis_velocity,
               i);
    add_signal(sim::field_path(p, "torque"), ax.linear ? "N" : "N*m", sim::Source::axis_force, i);
    ref_torque_input.push_back(add_input(sim::field_path(p, "ref_torque"), ax.linear ? "N" : "N*m",
                                         0.0, scene.joints[ax.joint].where));
  }
}

double Simulation::Impl::read_signal(std::size_t i) const {
  const sim::SignalEntry& e = signal_entries[i];
  const std::int32_t k = e.index;
  switch (e.source) {
    case sim::Source::published:
      return published[k];
    case sim::Source::input:
      return inputs[k];
    case sim::Source::time:
      return static_cast<double>(tick) * tick_s;
    case sim::Source::body_x:
      return poses[k].position.x;
    case sim::Source::body_y:
      return poses[k].position.y;
    case sim::Source::body_z:
      return poses[k].position.z;
    case sim::Source::body_roll:
      return std::atan2(poses[k].rotation.m[2][1], poses[k].rotation.m[2][2]);
    case sim::Source::body_pitch:
      return std::asin(std::clamp(-poses[k].rotation.m[2][0], -1.0, 1.0));
    case sim::Source::body_yaw:
      return yaw_of(poses[k].rotation);
    case sim::Source::body_vx:
      return twists[k].linear_m_s.x;
    case sim::Source::body_vy:
      return twists[k].linear_m_s.y;
    case sim::Source::body_vz:
      return twists[k].linear_m_s.z;
    case sim::Source::body_wx:
      return twists[k].angular_rad_s.x;
    case sim::Source::body_wy:
      return twists[k].angular_rad_s.y;
    case sim::Source::body_wz:
      return twists[k].angular_rad_s.z;
    case sim::Source::axis_position:
      return axis_position[k];
    case sim::Source::axis_velocity:
      return axis_velocity[k];
    case sim::Source::axis_force:
      return axis_force_applied[k];
    case sim::Source::body_contact_force: {
      Vec3 sum;
      const ContactInfo* c = contacts->contacts();
      for (std::int32_t n = 0; n < *contacts->contact_count(); ++n) {
        if (c[n].body_a.index == k) sum += c[n].force_N;
        if (c[n].body_b.index == k) sum -= c[n].force_N;
      }
      return norm(sum);
    }
    case sim::Source::contact_count:
      return *contacts->contact_count();
  }
  return 0.0;
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
  throw Error(ErrorKind::usage, common::unknown_name_message("signal", name, names));
}
double Simulation::signal(std::size_t index) const {
  return impl_->read_signal(index);
}
void Simulation::Impl::changed() const {
  if (!signal_values_kept) return;
  for (std::size_t i = 0; i < signal_values.size(); ++i)
    signal_values[i] = read_signal(i);
}
const std::vector<double>& Simulation::signal_values() const {
  Impl& m = *impl_;
  if (!m.signal_values_kept) {
    m.signal_values.assign(m.signal_infos.size(), 0.0);  // its size is fixed at load
    m.signal_values_kept = true;
    m.changed();
  }
  return m.signal_values;
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
  throw Error(ErrorKind::usage, common::unknown_name_message("input", name, names));
}
void Simulation::set_input(std::size_t index, double value) {
  const Impl& m = *impl_;
  const SignalInfo& info = m.input_infos.at(index);
  if (!(value >= m.input_min[index] && value <= m.input_max[index]))
    throw Error(ErrorKind::usage,
                "input '" + info.name + "' must lie in " +
                    range_text(m.input_min[index], m.input_max[index]) +
                    (info.unit.empty() || info.unit == "1" ? "" : " " + info.unit) + ", got " +
                    sim::short_decimal(value));
  impl_->inputs.at(index) = value;
  impl_->changed();
}
double Simulation::input(std::size_t index) const {
  return impl_->inputs.at(index);
}
const std::vector<double>& Simulation::inputs() const {
  return impl_->inputs;
}

}  // namespace s2sim
