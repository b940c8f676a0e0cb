// The kernel's loads as one Simbody force: gravity, body wrenches (controllers, contact), axis
// forces (motors), plain Coulomb friction on sliding axes and joint stops.
#include "model/dynamics.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::model {

namespace {

/// The rotation of body1 relative to body2 since load, about the axis (in (-pi, pi]).
double loop_angle(const AxisImpl& ax, const SimTK::Rotation& R1, const SimTK::Rotation& R2) {
  const SimTK::Rotation delta = (~R2 * R1) * ~ax.relative0;
  const SimTK::Mat33& D = delta.asMat33();
  const SimTK::Vec3 vee(D(2, 1) - D(1, 2), D(0, 2) - D(2, 0), D(1, 0) - D(0, 1));
  return std::atan2(0.5 * SimTK::dot(vee, ax.axis_in_body2), (D.trace() - 1.0) / 2.0);
}

}  // namespace

double axis_value(const Multibody::Impl& m, const SimTK::State& s, std::size_t a) {
  const AxisImpl& ax = m.axis_impl[a];
  if (!m.axes[a].loop) {
    // q by index, as MobilizedBody::getOneQ reads it (its look-ups cost more).
    return ax.sign * element(s.getQ(), m.axis_q[a]);
  }
  const BodyFrame b1 = m.dynamics->body_frame(m, s, m.mobod_of_body[ax.body1]);
  const BodyFrame b2 = m.dynamics->body_frame(m, s, m.mobod_of_body[ax.body2]);
  if (m.axes[a].linear)
    return SimTK::dot(~b2.R * (b1.origin - b2.origin) - ax.offset0_in_body2, ax.axis_in_body2);
  return loop_angle(ax, b1.R, b2.R);
}

double axis_rate(const Multibody::Impl& m, const SimTK::State& s, std::size_t a) {
  const AxisImpl& ax = m.axis_impl[a];
  if (!m.axes[a].loop) return ax.sign * element(s.getU(), m.axis_u[a]);  // by index
  const SimTK::MobilizedBodyIndex i1 = m.mobod_of_body[ax.body1], i2 = m.mobod_of_body[ax.body2];
  const BodyFrame b1 = m.dynamics->body_frame(m, s, i1), b2 = m.dynamics->body_frame(m, s, i2);
  const BodyVelocity v1 = m.dynamics->body_velocity(m, s, i1);
  const BodyVelocity v2 = m.dynamics->body_velocity(m, s, i2);
  const SimTK::Vec3 axis_G = b2.R * ax.axis_in_body2;
  if (m.axes[a].linear)
    return SimTK::dot(v1.linear - v2.linear - SimTK::cross(v2.angular, b1.origin - b2.origin),
                      axis_G);
  return SimTK::dot(v1.angular - v2.angular, axis_G);
}

/// A generalized force on one axis: a mobility force for a tree joint, equal and opposite
/// body loads about / along the axis for a loop joint (what Simbody's applyBodyTorque and
/// applyForceToBodyPoint add: a torque about the body origin, then the force).
void apply_axis_load(const Multibody::Impl& mb, const SimTK::State& state, std::size_t a, double f,
                     SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                     SimTK::Vector& mobility_forces) {
  const AxisImpl& ax = mb.axis_impl[a];
  if (!mb.axes[a].loop) {
    // What MobilizedBody::applyOneMobilityForce adds, by index (its look-ups cost more).
    mobility_forces[mb.axis_u[a]] += ax.sign * f;
    return;
  }
  const SimTK::MobilizedBodyIndex i1 = mb.mobod_of_body[static_cast<std::size_t>(ax.body1)];
  const SimTK::MobilizedBodyIndex i2 = mb.mobod_of_body[static_cast<std::size_t>(ax.body2)];
  const BodyFrame b1 = mb.dynamics->body_frame(mb, state, i1);
  const BodyFrame b2 = mb.dynamics->body_frame(mb, state, i2);
  const SimTK::Vec3 axis_G = b2.R * ax.axis_in_body2;
  if (mb.axes[a].linear) {
    const SimTK::Vec3 arm1 = b1.R * ax.anchor_in_body1;  // from body1's origin
    const SimTK::Vec3 arm2 = b1.origin + arm1 - b2.origin;
    const SimTK::Vec3 force = f * axis_G;
    body_forces[i1] += SimTK::SpatialVec(SimTK::cross(arm1, force), force);
    body_forces[i2] -= SimTK::SpatialVec(SimTK::cross(arm2, force), force);
  } else {
    body_forces[i1][0] += f * axis_G;
    body_forces[i2][0] -= f * axis_G;
  }
}

namespace {

/// Speed (rad/s or m/s) over which a loop axis's Coulomb friction ramps to its bound.
constexpr double kLoopFrictionSpeed = 1e-2;

/// Per-kernel-body wrenches (about each body origin, world frame) on Simbody's bodies; the
/// loose bodies take theirs in LooseBodies::kick.
void add_wrenches(const Multibody::Impl& mb, const std::vector<Wrench>& wrenches,
                  SimTK::Vector_<SimTK::SpatialVec>& body_forces) {
  for (const auto& [b, mobod] : mb.jointed_bodies) {
    const Wrench& w = wrenches[b];
    body_forces[mobod] += SimTK::SpatialVec(to_simtk(w.torque_Nm), to_simtk(w.force_N));
  }
}

/// The kernel's loads as a Simbody force, for the systems with constraints (without, the
/// loads go straight into the system's force arrays: realize_accelerations, integrator.cpp).
class AppliedLoads : public SimTK::Force::Custom::Implementation {
 public:
  explicit AppliedLoads(const Multibody::Impl* impl) : m_(impl) {}

  void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                 SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector& mobility_forces) const override {
    add_applied_loads(*m_, state, body_forces, mobility_forces);
  }

  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }

 private:
  const Multibody::Impl* m_;
};

}  // namespace

double loop_friction_speed() {
  return kLoopFrictionSpeed;
}

void add_applied_loads(const Multibody::Impl& mb, const SimTK::State& state,
                       SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                       SimTK::Vector& mobility_forces) {
  for (const auto& w : mb.weights) {
    const SimTK::Vec3 force(0, 0, -kGravity_m_s2 * w.mass_kg);
    const SimTK::Vec3 com_G = mb.dynamics->to_ground(mb, state, w.mobod, w.com_m);
    body_forces[w.mobod] += SimTK::SpatialVec(SimTK::cross(com_G, force), force);
  }
  add_wrenches(mb, mb.wrenches, body_forces);
  if (mb.contact_wrenches_used) add_wrenches(mb, mb.substep_wrenches, body_forces);
  for (std::size_t a = 0; a < mb.axis_impl.size(); ++a)
    if (mb.axis_forces[a] != 0.0)
      apply_axis_load(mb, state, a, mb.axis_forces[a], body_forces, mobility_forces);
  for (std::size_t a = 0; a < mb.axis_impl.size(); ++a)
    if (mb.sliding[a]) {  // clearly sliding: Coulomb's law as it is, no impulse needed
      const double v = axis_rate(mb, state, a);
      apply_axis_load(mb, state, a, v > 0 ? -mb.axis_friction[a] : mb.axis_friction[a], body_forces,
                      mobility_forces);
    }
  // The axis drives (motors, viscous friction, the loop axes' regularised Coulomb friction)
  // at their values for this substep; solve_axes (implicit_axes.cpp) makes them implicit after
  // the kick.
  for (const auto& row : mb.rows)
    if (row.applied != 0.0)
      apply_axis_load(mb, state, static_cast<std::size_t>(row.axis), row.applied, body_forces,
                      mobility_forces);
  for (std::size_t a = 0; a < mb.explicit_drive.size(); ++a)
    if (mb.explicit_drive[a] != 0.0)
      apply_axis_load(mb, state, a, mb.explicit_drive[a], body_forces, mobility_forces);
  for (const auto& stop : mb.stops) {
    const auto a = static_cast<std::size_t>(stop.axis);
    const double q = axis_value(mb, state, a);
    if (q <= stop.high && q >= stop.low) continue;
    const double limit = q > stop.high ? stop.high : stop.low;
    const double f = -stop.stiffness * (q - limit) - stop.damping * axis_rate(mb, state, a);
    // A stop pushes back into the range, never pulls toward the limit.
    const double push = q > stop.high ? std::min(0.0, f) : std::max(0.0, f);
    if (push != 0.0) apply_axis_load(mb, state, a, push, body_forces, mobility_forces);
  }
}

void register_applied_loads(Multibody::Impl& m) {
  m.applied_loads_force = SimTK::Force::Custom(m.forces, new AppliedLoads(&m)).getForceIndex();
}

}  // namespace s2sim::model
