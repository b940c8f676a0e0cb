// Snapshots (save and restore the whole run) and placing free bodies.
#include "sim/simulation_impl.hpp"

namespace s2sim {

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
