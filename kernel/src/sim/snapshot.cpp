// Snapshots (the state layout's segments, save and restore the whole run) and placing free
// bodies.
#include "sim/simulation_impl.hpp"

#include <bit>
#include <cmath>
#include <type_traits>

namespace s2sim {

namespace {

std::vector<common::StateLayout::Entry> entries_of(const Simulation::Snapshot& s) {
  std::vector<common::StateLayout::Entry> out;
  out.reserve(s.segments.size());
  for (const auto& seg : s.segments)
    out.push_back({seg.name, seg.size, seg.unit});
  return out;
}

/// A segment over one of the façade's buffers (their sizes are fixed at load).
template <class T>
void add_buffer(common::StateLayout& layout, const char* name, std::vector<T>& buffer) {
  layout.add(
      name, buffer.size(),
      [&buffer](double* out) {
        for (std::size_t i = 0; i < buffer.size(); ++i)
          if constexpr (std::is_same_v<T, double>)
            out[i] = buffer[i];
          else
            out[i] = std::bit_cast<double>(buffer[i]);  // random streams: their bits
      },
      [&buffer](const double* in, std::size_t) {
        for (std::size_t i = 0; i < buffer.size(); ++i)
          if constexpr (std::is_same_v<T, double>)
            buffer[i] = in[i];
          else
            buffer[i] = std::bit_cast<T>(in[i]);
      });
}

}  // namespace

void Simulation::Impl::declare_state() {
  multibody->declare_state(layout);
  contacts->declare_state(layout);
  declare_things_state();
  declare_body_shapes_state();
  declare_body_masses_state();
  // Written in place: the WorldView points into these buffers.
  add_buffer(layout, "components/state", state);
  add_buffer(layout, "inputs", inputs);
  add_buffer(layout, "published", published);
  add_buffer(layout, "axis_force_applied", axis_force_applied);
  add_buffer(layout, "random", random);
}

Simulation::Snapshot::Range Simulation::Snapshot::find(std::string_view name) const {
  const auto ranges = common::StateLayout::locate(entries_of(*this), values);
  for (std::size_t i = 0; i < segments.size(); ++i)
    if (segments[i].name == name) return {ranges[i].offset, ranges[i].size};
  throw Error(ErrorKind::usage, "the snapshot has no segment '" + std::string(name) + "' (" +
                                    common::StateLayout::describe(entries_of(*this)) + ")");
}

Simulation::Snapshot Simulation::save() const {
  const Impl& m = *impl_;
  Snapshot s;
  s.layout = m.layout.id();
  for (const auto& e : m.layout.entries())
    s.segments.push_back({e.name, e.size, e.unit});
  m.layout.save(s.values);
  return s;
}

void Simulation::restore(const Snapshot& snapshot) {
  Impl& m = *impl_;
  m.layout.restore(snapshot.layout, entries_of(snapshot), snapshot.values);
  m.restored();
  m.changed();
}

void Simulation::Impl::restored() {
  multibody->restored();
  world.contacts = contacts->contacts();  // the buffer may have grown
  tick = static_cast<std::int64_t>(std::llround(multibody->time_s() / tick_s));
  refresh();
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
  m.changed();
}

}  // namespace s2sim
