// Stepping on Simbody's realize chain (dynamics.hpp): the reference the small-tree dynamics are
// checked against, and the dynamics of a system the tree cannot take.
#include "model/dynamics.hpp"

namespace s2sim::model {

void realize_accelerations(Multibody::Impl& m) {
  SimTK::State& s = m.current;
  // The loads changed outside Simbody's knowledge: drop what was realized from them.
  s.invalidateAllCacheAtOrAbove(SimTK::Stage::Dynamics);
  if (!m.has_constraints) {
    // The system's force arrays are zeroed at Dynamics; the loads go straight in, as a force
    // subsystem would add them (its Force::Custom is disabled in these states).
    m.system.realize(s, SimTK::Stage::Dynamics);
    add_applied_loads(m, s, m.system.updRigidBodyForces(s, SimTK::Stage::Dynamics),
                      m.system.updMobilityForces(s, SimTK::Stage::Dynamics));
  }
  m.system.realize(s, SimTK::Stage::Acceleration);
}

namespace {

class SimbodyPath final : public Dynamics {
 public:
  const char* name() const override { return "simbody"; }

  void realize_velocity(const Multibody::Impl& m, const SimTK::State& s) const override {
    m.system.realize(s, SimTK::Stage::Velocity);
  }

  void read_bodies(const Multibody::Impl& m, const SimTK::State& s, Pose* poses,
                   Twist* twists) const override {
    for (const auto& [b, mobod] : m.jointed_bodies) {
      const auto& mob = m.matter.getMobilizedBody(mobod);
      const SimTK::Transform& X = mob.getBodyTransform(s);
      poses[b] = Pose{from_simtk(X.p()), from_simtk(X.R())};
      const SimTK::SpatialVec& V = mob.getBodyVelocity(s);
      twists[b] = Twist{from_simtk(V[0]), from_simtk(V[1])};
    }
  }

  BodyFrame body_frame(const Multibody::Impl& m, const SimTK::State& s,
                       SimTK::MobilizedBodyIndex body) const override {
    const auto& mob = m.matter.getMobilizedBody(body);
    return {mob.getBodyRotation(s), mob.getBodyOriginLocation(s)};
  }

  BodyVelocity body_velocity(const Multibody::Impl& m, const SimTK::State& s,
                             SimTK::MobilizedBodyIndex body) const override {
    const auto& mob = m.matter.getMobilizedBody(body);
    return {mob.getBodyAngularVelocity(s), mob.getBodyOriginVelocity(s)};
  }

  SimTK::Vec3 to_ground(const Multibody::Impl& m, const SimTK::State& s,
                        SimTK::MobilizedBodyIndex body, const SimTK::Vec3& v_B) const override {
    return m.matter.getMobilizedBody(body).getBodyRotation(s) * v_B;
  }

  void accelerations(Multibody::Impl& m, bool last_substep) const override {
    realize_accelerations(m);
    m.udot = 0.0;
    add_scaled(m.udot, 1.0, m.current.getUDot());  // a copy: updU() later invalidates UDot
    // The reactions of the tick's last acceleration evaluation: no extra realize, and the
    // same loads as the kick that follows (the implicit axis solve's corrections excepted).
    if (m.reactions_wanted && last_substep) compute_joint_reactions(m, m.current);
  }

  void tree_axis_column(Multibody::Impl& m, const SimTK::State& s, int a) const override {
    m.unit_force = 0.0;
    m.unit_force[m.axis_u[a]] = m.axis_impl[a].sign;
    m.matter.multiplyByMInv(s, m.unit_force, m.column_scratch_vector);
    keep_column(m, static_cast<std::size_t>(a), contiguous_data(m.column_scratch_vector), 0,
                m.column_scratch_vector.size());
  }

  void loop_axis_column(Multibody::Impl& m, const SimTK::State& s, int a) const override {
    SimTK::Vector& g = m.loop_unit_force[a];
    m.matter.multiplyBySystemJacobianTranspose(s, m.unit_body_forces, g);
    m.matter.multiplyByMInv(s, g, m.column_scratch_vector);
    keep_column(m, static_cast<std::size_t>(a), contiguous_data(m.column_scratch_vector), 0,
                m.column_scratch_vector.size());
  }

  void point_forces(Multibody::Impl& m, const SimTK::State& s, SimTK::MobilizedBodyIndex body,
                    const SimTK::Vec3& point, const SimTK::Vec3* directions, int u_begin, int u_end,
                    double* const* g) const override {
    const SimTK::Vec3 arm = point - m.matter.getMobilizedBody(body).getBodyOriginLocation(s);
    for (int j = 0; j < 2; ++j) {
      m.unit_body_forces.setToZero();
      m.unit_body_forces[body] = SimTK::SpatialVec(SimTK::cross(arm, directions[j]), directions[j]);
      m.matter.multiplyBySystemJacobianTranspose(s, m.unit_body_forces, m.unit_force);
      for (int k = u_begin; k < u_end; ++k)
        g[j][k] = m.unit_force[k];
    }
  }

  void solve_speeds(Multibody::Impl& m, const SimTK::State& s, SimTK::MobilizedBodyIndex,
                    int u_begin, int u_end, const double* g, double* x) const override {
    m.unit_force = 0.0;
    for (int k = u_begin; k < u_end; ++k)
      m.unit_force[k] = g[k];
    m.matter.multiplyByMInv(s, m.unit_force, m.friction_scratch);
    for (int k = u_begin; k < u_end; ++k)
      x[k] = m.friction_scratch[k];
  }

  void qdot(Multibody::Impl& m) const override {
    const SimTK::State& s = m.current;
    m.matter.multiplyByN(s, false, s.getU(), m.qdot);
  }

  void project_speeds(Multibody::Impl& m) const override {
    m.system.projectU(m.current, kLoopTolerance);
  }
  void project(Multibody::Impl& m) const override { m.system.project(m.current, kLoopTolerance); }
};

}  // namespace

const Dynamics& simbody_dynamics() {
  static const SimbodyPath path;
  return path;
}

}  // namespace s2sim::model
