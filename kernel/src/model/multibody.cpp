// Multibody: the scene's bodies and joints as a Simbody system, seen by the kernel as plain
// arrays (the constructor is in multibody_build.cpp, the integrator in integrator.cpp).
#include "model/dynamics.hpp"

#include "common/state_layout.hpp"

#include <algorithm>
#include <cmath>
#include <new>

namespace s2sim::model {

Multibody::~Multibody() = default;

int Multibody::body_count() const {
  return static_cast<int>(impl_->mobod_of_body.size());
}
const std::vector<AxisInfo>& Multibody::axes() const {
  return impl_->axes;
}
const std::vector<std::string>& Multibody::warnings() const {
  return impl_->warnings;
}
Wrench* Multibody::applied_wrenches() {
  return impl_->wrenches.data();
}
double* Multibody::applied_axis_forces() {
  return impl_->axis_forces.data();
}
double* Multibody::applied_axis_friction() {
  return impl_->axis_friction.data();
}
AxisDrive* Multibody::axis_drives() {
  return impl_->drives.data();
}
std::int32_t* Multibody::axis_drive_count() {
  return &impl_->drive_count;
}
std::int32_t Multibody::axis_drive_capacity() const {
  return static_cast<std::int32_t>(impl_->drives.size());
}
const double* Multibody::drive_force_applied() const {
  return impl_->drive_applied.data();
}
void Multibody::request_joint_reactions() {
  impl_->reactions_wanted = true;
  select_dynamics(*impl_);
}
const Wrench* Multibody::joint_reactions() const {
  return impl_->joint_reactions.data();
}
bool Multibody::joint_is_loop(int joint) const {
  return !impl_->joint_reaction_source.at(static_cast<std::size_t>(joint)).mobod.isValid();
}
void Multibody::choose_dynamics(DynamicsChoice choice) {
  impl_->choice = choice;
  select_dynamics(*impl_);
}
bool Multibody::uses_tree_fast_path() const {
  return impl_->dynamics != &simbody_dynamics();
}
const char* Multibody::dynamics_name() const {
  // Without a joint every body is a loose one: no equations of motion of a tree to choose.
  return impl_->has_mobilized_bodies ? impl_->dynamics->name() : "loose";
}
bool Multibody::needs_simbody_dynamics() const {
  return impl_->has_mobilized_bodies && !impl_->tree;
}
DynamicsCheck Multibody::dynamics_check() const {
  return impl_->check;
}
void Multibody::set_dynamics_agreement(double relative) {
  impl_->check.agreement = relative;
}
Wrench* Multibody::use_contact_wrenches() {
  impl_->contact_wrenches_used = true;
  return impl_->substep_wrenches.data();
}

std::vector<double> Multibody::apparent_mass_kg() const {
  const Impl& m = *impl_;
  const SimTK::State& s = m.initial_state;
  m.system.realize(s, SimTK::Stage::Position);
  std::vector<double> out(m.mobod_of_body.size(), 0.0);
  for (std::size_t b = 1; b < m.mobod_of_body.size(); ++b)
    if (!m.mobod_of_body[b].isValid()) out[b] = m.loose.mass_kg(static_cast<int>(b));  // its own
  LoadResponse response(m);
  for (const auto& bodies : response.rounds([](std::size_t) { return true; })) {
    for (std::size_t b : bodies)
      out[b] = SimTK::Infinity;
    for (int axis = 0; axis < 3; ++axis) {
      SimTK::Vec3 force(0);
      force[axis] = 1;
      response.clear();
      for (std::size_t b : bodies)
        response.add(s, b, SimTK::Vec3(0), force);
      response.solve(s);
      for (std::size_t b : bodies) {
        const double a = response.at_com(s, b).second[axis];
        if (a > 1e-12) out[b] = std::min(out[b], 1 / a);
      }
    }
  }
  return out;
}

double Multibody::time_s() const {
  return static_cast<double>(impl_->ticks) * impl_->tick_s;
}

void Multibody::reset() {
  impl_->ticks = 0;
  std::fill(impl_->joint_reactions.begin(), impl_->joint_reactions.end(), Wrench{});
  impl_->current = impl_->initial_state;
  impl_->half_kick_pending = true;
  impl_->bodies_fresh = false;
  clear_columns(*impl_);
  impl_->substep = 0;
  impl_->drive_count = 0;
  impl_->friction.count = 0;
  impl_->rows.clear();
  std::fill(impl_->explicit_drive.begin(), impl_->explicit_drive.end(), 0.0);
  std::fill(impl_->drive_sum.begin(), impl_->drive_sum.end(), 0.0);
  std::fill(impl_->drive_applied.begin(), impl_->drive_applied.end(), 0.0);
  impl_->loose.reset();
  impl_->system.realize(impl_->current, SimTK::Stage::Velocity);
  if (impl_->reactions_wanted) {
    // The reading before the first step: the initial state under gravity alone (the kernel
    // rewrites every applied load before each step, so clearing them here changes nothing).
    Impl& m = *impl_;
    std::fill(m.wrenches.begin(), m.wrenches.end(), Wrench{});
    std::fill(m.substep_wrenches.begin(), m.substep_wrenches.end(), Wrench{});
    std::fill(m.axis_forces.begin(), m.axis_forces.end(), 0.0);
    std::fill(m.axis_friction.begin(), m.axis_friction.end(), 0.0);
    m.drive_count = 0;
    std::fill(m.sliding.begin(), m.sliding.end(), 0);
    realize_accelerations(m);
    compute_joint_reactions(m, m.current);
  }
}

void read_bodies(const Multibody::Impl& m, const SimTK::State& s, Pose* poses, Twist* twists) {
  poses[0] = Pose{};
  twists[0] = Twist{};
  m.dynamics->read_bodies(m, s, poses, twists);
  m.loose.read(poses, twists);
}

void Multibody::read(Pose* poses, Twist* twists, double* axis_position,
                     double* axis_velocity) const {
  const Impl& m = *impl_;
  const SimTK::State& s = m.state();
  realize_velocity(m, s);
  if (m.bodies_fresh) {
    std::copy(m.substep_poses.begin(), m.substep_poses.end(), poses);
    std::copy(m.substep_twists.begin(), m.substep_twists.end(), twists);
  } else {
    read_bodies(m, s, poses, twists);
  }
  for (std::size_t a = 0; a < m.axis_impl.size(); ++a) {
    axis_position[a] = axis_value(m, s, a);
    axis_velocity[a] = axis_rate(m, s, a);
  }
}

double Multibody::kinetic_energy_J() const {
  const SimTK::State& s = impl_->state();
  impl_->system.realize(s, SimTK::Stage::Velocity);
  return impl_->matter.calcKineticEnergy(s) + impl_->loose.kinetic_energy_J();
}

double Multibody::potential_energy_J() const {
  const SimTK::State& s = impl_->state();
  impl_->system.realize(s, SimTK::Stage::Dynamics);
  double energy = impl_->loose.potential_energy_J();
  for (const auto& w : impl_->weights) {
    const auto& mob = impl_->matter.getMobilizedBody(w.mobod);
    energy += w.mass_kg * kGravity * mob.findStationLocationInGround(s, w.com_m)[2];
  }
  return energy;
}

namespace {

/// A segment over a SimTK::Vector of the current state (q, u or z), written in place.
void add_state_vector(common::StateLayout& layout, const std::string& name, Multibody::Impl& m,
                      const SimTK::Vector& (SimTK::State::*get)() const,
                      SimTK::Vector& (SimTK::State::*upd)()) {
  layout.add(
      name, static_cast<std::size_t>((m.current.*get)().size()),
      [&m, get](double* out) {
        const SimTK::Vector& v = (m.current.*get)();
        const int n = v.size();  // a call into SimTKcommon: once
        for (int i = 0; i < n; ++i)
          out[i] = v[i];
      },
      [&m, upd](const double* in, std::size_t) {
        SimTK::Vector& v = (m.current.*upd)();
        const int n = v.size();
        for (int i = 0; i < n; ++i)
          v[i] = in[i];
      });
}

/// Calls f(double&) on every number of the M^-1 column cache, in the segment's order.
template <class M, class F>
void for_each_column_number(M& m, F&& f) {
  for (auto& valid : m.column_valid) {
    double v = valid;
    f(v);
    valid = static_cast<char>(v != 0.0);
  }
  for (auto& x : m.minv_column.values)
    f(x);
  for (auto& column : m.loop_unit_force) {
    // Through the data itself: an element access (and a size) per number is a call into
    // SimTKcommon, which made a snapshot of 16 robots cost 25 µs (run_ahead.cpp takes one
    // per stretch).
    const int n = column.size();
    if (n > 0 && column.hasContiguousData()) {
      double* x = column.updContiguousScalarData();
      for (int i = 0; i < n; ++i)
        f(x[i]);
    } else {
      for (int i = 0; i < n; ++i)
        f(column[i]);
    }
  }
  for (auto* values : {&m.columns_q, &m.column_root_quat, &m.axis_mobility})
    for (auto& x : *values)
      f(x);
  // The contact friction's M^-1 per range of speeds (contact_friction.cpp), kept the same way.
  for (auto& range : m.friction_ranges) {
    double v = range.valid;
    f(v);
    range.valid = v != 0.0;
  }
  for (auto* values : {&m.friction_minv, &m.friction_minv_q, &m.friction_minv_quat})
    for (auto& x : *values)
      f(x);
}

}  // namespace

void Multibody::declare_state(common::StateLayout& layout, const std::string& prefix) {
  Impl& m = *impl_;
  layout.add(
      prefix + "/time", 2,
      [&m](double* out) {
        out[0] = static_cast<double>(m.ticks);
        out[1] = m.half_kick_pending ? 1.0 : 0.0;
      },
      [&m](const double* in, std::size_t) {
        m.ticks = static_cast<std::int64_t>(in[0]);
        m.half_kick_pending = in[1] != 0.0;
      });
  add_state_vector(layout, prefix + "/q", m, &SimTK::State::getQ, &SimTK::State::updQ);
  add_state_vector(layout, prefix + "/u", m, &SimTK::State::getU, &SimTK::State::updU);
  add_state_vector(layout, prefix + "/z", m, &SimTK::State::getZ, &SimTK::State::updZ);
  // The M^-1 columns kept across steps decide what the next steps compute (which axes slide,
  // the implicit solve's columns, reused until q moves by 1e-7): part of the state.
  std::size_t column_numbers = 0;
  for_each_column_number(m, [&](double&) { ++column_numbers; });
  layout.add(
      prefix + "/columns", column_numbers,
      [&m](double* out) { for_each_column_number(m, [&](double& x) { *out++ = x; }); },
      [&m](const double* in, std::size_t) {
        for_each_column_number(m, [&](double& x) { x = *in++; });
      });
  // The last reactions: what a joint sensor reads before the next step.
  layout.add(
      prefix + "/reactions", 6 * m.joint_reactions.size(),
      [&m](double* out) {
        for (const Wrench& w : m.joint_reactions)
          for (const Vec3* v : {&w.torque_Nm, &w.force_N})
            for (double x : {v->x, v->y, v->z})
              *out++ = x;
      },
      [&m](const double* in, std::size_t) {
        for (Wrench& w : m.joint_reactions)
          for (Vec3* v : {&w.torque_Nm, &w.force_N}) {
            *v = {in[0], in[1], in[2]};
            in += 3;
          }
      });
  // The serial run's names stay `loose/…`; a part's, under its own prefix.
  if (prefix == "multibody")
    m.loose.declare_state(layout, "loose");
  else if (!m.loose.empty())
    m.loose.declare_state(layout, prefix + "/loose");
}

void Multibody::restored() {
  Impl& m = *impl_;
  m.bodies_fresh = false;
  m.substep = 0;
  try {
    m.system.realize(m.current, SimTK::Stage::Velocity);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {  // e.g. a zero quaternion: a NaN inertia
    throw Error(ErrorKind::usage,
                std::string("the snapshot's multibody state is not a valid one: ") + e.what());
  }
}

}  // namespace s2sim::model
