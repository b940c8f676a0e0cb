// Components stepped in the island parts (component_parts.hpp): the plan made at load, the
// local components' views, and what each part's thread runs at the tick's edges.
#include "sim/running_component.hpp"
#include "sim/simulation_impl.hpp"
#include "sim/step.hpp"

#include <algorithm>
#include <numeric>
#include <string>

namespace s2sim {

namespace {

/// Union-find over the components and the inputs (component_parts.cpp's plan).
struct Groups {
  explicit Groups(std::size_t nodes) : parent(nodes) { std::iota(parent.begin(), parent.end(), 0); }
  std::size_t find(std::size_t n) {
    while (parent[n] != n)
      n = parent[n] = parent[parent[n]];
    return n;
  }
  void unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  std::vector<std::size_t> parent;
};

constexpr int kEveryPart = -2;    // read by every part (a conveyor belt's speed, in contact)
constexpr int kAllContacts = -3;  // the scene's contact list (merged on the calling thread)

using Pins = std::vector<std::pair<std::size_t, int>>;  // (node, part)
using Slots = std::vector<sim::ComponentSlot>;

std::string shared_reason(const Slots& components, Groups& groups, std::size_t node, int pin) {
  const std::size_t C = components.size();
  const std::string what =
      pin == kAllContacts ? "reads a signal of the scene's contacts (a body's contact_force, "
                            "contacts/count), which the parts hold in pieces"
                          : "touches a conveyor belt's speed, which every part's contact reads";
  for (std::size_t c = node < C ? node : 0; c < C; ++c)
    if (groups.find(c) == groups.find(node)) return components[c].label() + " " + what;
  return "an input " + what;
}

std::string two_parts_reason(const Slots& components, Groups& groups, const Pins& pins,
                             std::size_t node) {
  const std::size_t C = components.size();
  // A component that touches two parts itself, else two of the group on different parts.
  const std::size_t group = groups.find(node);
  std::vector<int> first_part(C, -1);
  std::size_t on[2] = {C, C};
  int part_on[2] = {-1, -1};
  for (const auto& [n, part] : pins) {
    if (n >= C || groups.find(n) != group) continue;
    if (first_part[n] >= 0 && first_part[n] != part)
      return components[n].label() + " touches the bodies or axes of two parts";
    first_part[n] = part;
    if (on[0] == C) {
      on[0] = n;
      part_on[0] = part;
    } else if (on[1] == C && part != part_on[0]) {
      on[1] = n;
      part_on[1] = part;
    }
  }
  if (on[1] == C) return "components touch the bodies or axes of two parts";
  return components[on[0]].label() + " and " + components[on[1]].label() +
         " touch the bodies or axes of two parts and share inputs or signals (directly or " +
         "through other components)";
}

}  // namespace

void Simulation::Impl::plan_component_parts() {
  sim::ComponentParts& plan = component_parts;
  plan.parts.clear();
  multibody->stage_drives_by_part(false);
  plan.whole.part = sim::ComponentGroup::kWholeScene;
  plan.whole.stage_order = stage_order;
  plan.whole.bodies.resize(poses.size());
  std::iota(plan.whole.bodies.begin(), plan.whole.bodies.end(), 0);
  plan.whole.axes.resize(axis_views.size());
  std::iota(plan.whole.axes.begin(), plan.whole.axes.end(), 0);
  const int parts = multibody->parts();
  if (parts < 2) {
    plan.serial_reason =
        "the scene is stepped as one part (threads = 1, a single island, or a loop-closing or "
        "Ball joint: docs/scheduling.md)";
    return;
  }
  for (const auto& slot : components)
    if (!slot.local) {
      plan.serial_reason =
          slot.label() + " is not declared local (ConfigureContext::declare_local)";
      return;
    }
  // Components [0, C) and inputs [C, C + I): a component is one node with every input it
  // touches and every component whose signals it reads; each node may be pinned to the part
  // that steps what it touches.
  const std::size_t C = components.size();
  Groups groups(C + inputs.size());
  Pins pins;
  for (std::size_t a = 0; a < axis_views.size(); ++a)  // the kernel adds them in the part
    pins.emplace_back(C + static_cast<std::size_t>(ref_torque_input[a]),
                      multibody->part_of_axis(static_cast<int>(a)));
  for (const auto& belt : belt_speed_inputs)
    pins.emplace_back(C + static_cast<std::size_t>(belt.second), kEveryPart);
  for (std::size_t c = 0; c < C; ++c) {
    const sim::Footprint& f = components[c].footprint;
    for (const std::int32_t b : f.bodies)
      pins.emplace_back(c, multibody->part_of_body(b));
    for (const std::int32_t a : f.axes)
      pins.emplace_back(c, multibody->part_of_axis(a));
    for (const std::int32_t j : f.joints)
      pins.emplace_back(c, multibody->part_of_joint(j));
    for (const std::int32_t i : f.inputs)
      groups.unite(c, C + static_cast<std::size_t>(i));
    for (const std::int32_t s : f.published)
      groups.unite(c, static_cast<std::size_t>(publisher[static_cast<std::size_t>(s)]));
    for (const std::int32_t e : f.readers) {
      const sim::SignalEntry& entry = signal_entries[static_cast<std::size_t>(e)];
      switch (entry.source) {
        case sim::Source::published:
          groups.unite(c,
                       static_cast<std::size_t>(publisher[static_cast<std::size_t>(entry.index)]));
          break;
        case sim::Source::input:
          groups.unite(c, C + static_cast<std::size_t>(entry.index));
          break;
        case sim::Source::axis_position:
        case sim::Source::axis_velocity:
        case sim::Source::axis_force:
          pins.emplace_back(c, multibody->part_of_axis(entry.index));
          break;
        case sim::Source::time:
          break;
        case sim::Source::body_contact_force:
        case sim::Source::contact_count:
          pins.emplace_back(c, kAllContacts);
          break;
        default:  // a body's pose or velocity
          pins.emplace_back(c, multibody->part_of_body(entry.index));
          break;
      }
    }
  }
  std::vector<int> part_of_group(C + inputs.size(), -1);
  for (const auto& [node, part] : pins) {
    int& at = part_of_group[groups.find(node)];
    if (at == -1) at = part;
    if (at == part && part >= 0) continue;
    plan.serial_reason = part < 0 ? shared_reason(components, groups, node, part)
                         : at < 0 ? shared_reason(components, groups, node, at)
                                  : two_parts_reason(components, groups, pins, node);
    return;
  }

  plan.parts.resize(static_cast<std::size_t>(parts));
  for (int p = 0; p < parts; ++p) {
    auto& part = plan.parts[static_cast<std::size_t>(p)];
    part.part = p;
    part.bodies = multibody->part_bodies(p);
    part.axes = multibody->part_axes(p);
  }
  for (std::size_t stage = 0; stage < stage_order.size(); ++stage)
    for (const int c : stage_order[stage]) {
      const int at = part_of_group[groups.find(static_cast<std::size_t>(c))];
      plan.parts[static_cast<std::size_t>(at < 0 ? 0 : at)].stage_order[stage].push_back(c);
    }
  multibody->stage_drives_by_part(true);
  plan.serial_reason.clear();
}

void Simulation::Impl::sync_local_views() {
  auto sync = [&](sim::LocalView& local, AxisDrive* drives, std::int32_t* drive_count) {
    local.view = world;
    local.sim = this;
    local.view.axis_drives = drives;
    local.view.axis_drive_count = drive_count;
    local.view.kernel = &local;
    local.view.cast_ray = &refuse_ray;
    local.view.renderer = &local;
    local.view.render_camera = &refuse_render;
    local.view.placer = &local;
    local.view.request_place = &refuse_place;
    local.view.request_move = &refuse_move;
    local.view.request_velocity = &refuse_velocity;
    local.view.request_add_thing = &refuse_add_thing;
    local.view.request_delete_thing = &refuse_delete_thing;
    local.view.request_delete_obstacle = &refuse_delete_obstacle;
    local.view.request_resize = &refuse_resize;
    local.view.request_surface = &refuse_surface;
    local.view.request_mass = &refuse_mass;
    local.view.annotator = &local;
    local.view.annotate = &refuse_annotation;
  };
  sync(component_parts.whole.local, world.axis_drives, world.axis_drive_count);
  for (std::size_t p = 0; p < component_parts.parts.size(); ++p) {
    const int part = static_cast<int>(p);
    sync(component_parts.parts[p].local, multibody->part_drives(part),
         multibody->part_drive_count(part));
  }
}

namespace {
[[noreturn]] void refuse(const void* local, const char* what) {
  const auto& view = *static_cast<const sim::LocalView*>(local);
  const auto& sim = *static_cast<const Simulation::Impl*>(view.sim);
  const sim::ComponentSlot& slot = sim.components[static_cast<std::size_t>(view.component)];
  throw Error(ErrorKind::runtime, slot.where,
              slot.label() + " declared itself local (ConfigureContext::declare_local) but " +
                  what + ", which a local component may not: drop the declaration");
}
}  // namespace

RayHit Simulation::Impl::refuse_ray(const void* local, const Vec3&, const Vec3&, double,
                                    std::int32_t) {
  refuse(local, "cast a ray");
}
void Simulation::Impl::refuse_render(const void* local, const CameraShot&, Image*, Image*, Image*) {
  refuse(local, "rendered a camera");
}
void Simulation::Impl::refuse_place(const void* local, std::int32_t, const Pose&) {
  refuse(local, "asked to place a body");
}
void Simulation::Impl::refuse_move(const void* local, std::int32_t, const Pose&) {
  refuse(local, "asked to move a body");
}
void Simulation::Impl::refuse_velocity(const void* local, std::int32_t, const Twist&) {
  refuse(local, "asked to set a body's velocity");
}
std::int32_t Simulation::Impl::refuse_add_thing(const void* local, const ThingSpec&, const char*,
                                                std::size_t) {
  refuse(local, "asked to add a thing");
  return -1;
}
void Simulation::Impl::refuse_delete_thing(const void* local, std::int32_t) {
  refuse(local, "asked to delete a thing");
}
void Simulation::Impl::refuse_delete_obstacle(const void* local, std::int32_t) {
  refuse(local, "asked to delete an obstacle");
}
void Simulation::Impl::refuse_resize(const void* local, std::int32_t, const Vec3&) {
  refuse(local, "asked to resize a body");
}
void Simulation::Impl::refuse_surface(const void* local, std::int32_t, double, double) {
  refuse(local, "asked to set a body's surface");
}
void Simulation::Impl::refuse_mass(const void* local, std::int32_t, double, const Vec3*,
                                   const Mat3*) {
  refuse(local, "asked to set a body's mass");
}
void Simulation::Impl::refuse_annotation(const void* local, std::int32_t, std::int32_t,
                                         std::int32_t, const char*, std::size_t, const double*) {
  refuse(local, "published an annotation (a log line, HUD text, trail, XY point or colour)");
}

void Simulation::Impl::run_component_group(sim::ComponentGroup& group, bool calling_thread,
                                           int ahead) {
  const bool whole = group.part == sim::ComponentGroup::kWholeScene;
  sim::StageProfile* timing = calling_thread ? profile.get() : nullptr;
  Wrench* wrenches = multibody->applied_wrenches();
  double* axis_force = multibody->applied_axis_forces();
  double* axis_friction = multibody->applied_axis_friction();
  for (const int b : group.bodies)
    wrenches[b] = Wrench{};
  for (const int a : group.axes)
    axis_force[a] = axis_friction[a] = 0.0;
  // The last substep's contacts: a part's on its bodies (its own lane, unmerged; the whole
  // list after a substep computed whole), the whole scene's merged.
  detail::WorldView& view = group.local.view;
  if (whole) {
    world.contacts = view.contacts = contacts->contacts();
    world.contact_count = view.contact_count = contacts->contact_count();
  } else {
    view.contacts = contacts->part_contacts(group.part, view.contact_count);
  }
  // The rest of the view changes only at load; the time as refresh() writes it.
  view.tick = tick + ahead;
  view.time_s = static_cast<double>(view.tick) * tick_s;
  const AxisDrive* drives = view.axis_drives;
  std::int32_t& drive_count = *view.axis_drive_count;
  drive_count = 0;
  for (std::size_t stage = 0; stage < group.stage_order.size(); ++stage) {
    sim::StageTimer timer(timing, static_cast<sim::PipelineStage>(stage));
    for (const int c : group.stage_order[stage]) {
      const std::int32_t before = drive_count;
      const sim::ComponentSlot& slot = components[static_cast<std::size_t>(c)];
      if (!update_if_due(c, slot.local ? &group.local : nullptr)) continue;
      if (whole) continue;
      for (std::int32_t d = before; d < drive_count; ++d) {
        const std::int32_t a = drives[d].axis;
        if (a >= 0 && static_cast<std::size_t>(a) < axis_views.size() &&
            multibody->part_of_axis(a) == group.part)
          continue;
        throw Error(ErrorKind::runtime, slot.where,
                    slot.label() +
                        " declared itself local (ConfigureContext::declare_local) "
                        "but applied a drive to axis index " +
                        std::to_string(a) + ", which it did not look up");
      }
    }
    // Only the whole scene's components may ask (a local one is refused).
    if (!pending_places.empty() || !pending_moves.empty() || !pending_velocities.empty() ||
        !pending_things.empty() || !pending_obstacles.empty() || !pending_body_changes.empty())
      apply_pending_places();
  }
  for (const int a : group.axes)
    axis_force[a] +=
        inputs[static_cast<std::size_t>(ref_torque_input[static_cast<std::size_t>(a)])];
  check_loads_finite(&group.bodies, &group.axes, drives, drive_count);
}

void Simulation::Impl::record_group_axis_loads(const sim::ComponentGroup& group) {
  const double* axis_force = multibody->applied_axis_forces();
  const double* drive = multibody->drive_force_applied();
  for (const int a : group.axes)
    axis_force_applied[static_cast<std::size_t>(a)] = axis_force[a] + drive[a];
}

const std::string& Simulation::components_serial_reason() const {
  return impl_->component_parts.serial_reason;
}

}  // namespace s2sim
