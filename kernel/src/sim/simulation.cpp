#include "common/signal_stack.hpp"
#include "sim/running_component.hpp"
#include "sim/simulation_impl.hpp"

#include <algorithm>
#include <cmath>

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

const char* running_component() noexcept {
  return sim::g_running_component.load(std::memory_order_relaxed);
}

std::size_t running_calls(RunningCall* out, std::size_t capacity) noexcept {
  const std::size_t used =
      std::min(sim::g_call_slots_used.load(std::memory_order_relaxed), sim::kMaxCallSlots);
  std::size_t n = 0;
  for (std::size_t i = 0; i < used && n < capacity; ++i) {
    const sim::CallSlot& slot = sim::g_call_slots[i];
    const char* label = slot.label.load(std::memory_order_acquire);
    if (!label) continue;
    out[n++] = {label, slot.calls.load(std::memory_order_relaxed)};
  }
  return n;
}

void use_alternate_signal_stack() noexcept {
  common::use_alternate_signal_stack();
}

Simulation::Simulation(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {
  impl_->facade = this;
}
Simulation::~Simulation() = default;

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

std::string Simulation::dynamics() const {
  return impl_->multibody->dynamics_name();
}
Simulation::DynamicsCheck Simulation::dynamics_check() const {
  const model::DynamicsCheck check = impl_->multibody->dynamics_check();
  return {check.compared,
          check.worst_relative,
          check.worst_time_s,
          check.agreement,
          check.judged_on_loops,
          check.worst_loop_error,
          check.worst_reference_loop_error};
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
const std::vector<Pose>& Simulation::body_poses() const {
  return impl_->poses;
}
const std::vector<Twist>& Simulation::body_twists() const {
  return impl_->twists;
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
const std::vector<double>& Simulation::axis_positions() const {
  return impl_->axis_position;
}
const std::vector<double>& Simulation::axis_velocities() const {
  return impl_->axis_velocity;
}
void Simulation::set_axis_state(std::size_t index, double position, double velocity) {
  Impl& m = *impl_;
  if (index >= m.axis_views.size())
    throw Error(ErrorKind::usage, "axis index " + std::to_string(index) + " is out of range (" +
                                      std::to_string(m.axis_views.size()) + " axes)");
  const std::string name = m.axis_prefix(static_cast<int>(index));
  if (!std::isfinite(position) || !std::isfinite(velocity))
    throw Error(ErrorKind::usage,
                "axis '" + name + "': position and velocity must be finite, got " +
                    std::to_string(position) + " and " + std::to_string(velocity));
  if (!m.multibody->set_axis_state(index, position, velocity))
    throw Error(ErrorKind::usage, "axis '" + name +
                                      "' closes a kinematic loop: its position follows from the "
                                      "bodies it joins and cannot be set");
  m.refresh();
  m.changed();
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

}  // namespace s2sim
