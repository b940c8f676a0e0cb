// The checked dynamics (dynamics.hpp): the small-tree dynamics step, and at every substep
// Simbody's realize chain computes the accelerations of the same state under the same loads
// first. A difference beyond the agreement (kDynamicsAgreement unless set) stops the run,
// naming the body, unless Simbody's accelerations there break the loops' acceleration
// constraints that the tree's keep (counted, no verdict); the largest difference within the
// agreement is kept for the report. The stepping is the tree's alone, so a checked run gives
// the unchecked run's numbers bit for bit.
#include "model/dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace s2sim::model {
namespace {

/// The kernel body whose mobilizer owns speed `u`, for the message.
std::string body_of_speed(const Multibody::Impl& m, int u) {
  for (const auto& [b, mobod] : m.jointed_bodies) {
    const auto& mob = m.matter.getMobilizedBody(mobod);
    const int first = mob.getFirstUIndex(m.current);
    if (u >= first && u < first + mob.getNumU(m.current)) return m.body_names[b];
  }
  return "index " + std::to_string(u);
}

/// Whether Simbody's accelerations break the loops' acceleration constraints (RMS error beyond
/// the agreement times the largest acceleration) while the tree's keep them.
bool reference_off_constraints(Multibody::Impl& m, double scale) {
  const double limit = m.check.agreement * scale;
  m.matter.calcConstraintAccelerationErrors(m.current, m.reference_udot, m.constraint_errors);
  if (!(m.constraint_errors.normRMS() > limit)) return false;
  m.matter.calcConstraintAccelerationErrors(m.current, m.udot, m.constraint_errors);
  return m.constraint_errors.normRMS() <= limit;
}

class CheckedPath final : public Dynamics {
 public:
  const char* name() const override { return "checked"; }

  void realize_velocity(const Multibody::Impl& m, const SimTK::State& s) const override {
    tree().realize_velocity(m, s);
  }
  void read_bodies(const Multibody::Impl& m, const SimTK::State& s, Pose* poses,
                   Twist* twists) const override {
    tree().read_bodies(m, s, poses, twists);
  }
  BodyFrame body_frame(const Multibody::Impl& m, const SimTK::State& s,
                       SimTK::MobilizedBodyIndex body) const override {
    return tree().body_frame(m, s, body);
  }
  BodyVelocity body_velocity(const Multibody::Impl& m, const SimTK::State& s,
                             SimTK::MobilizedBodyIndex body) const override {
    return tree().body_velocity(m, s, body);
  }
  SimTK::Vec3 to_ground(const Multibody::Impl& m, const SimTK::State& s,
                        SimTK::MobilizedBodyIndex body, const SimTK::Vec3& v_B) const override {
    return tree().to_ground(m, s, body, v_B);
  }

  void accelerations(Multibody::Impl& m, bool last_substep) const override {
    // The reference first: Simbody's realize leaves q and u as they are, so the tree then
    // starts from the same state (its kinematics are its own; the loads are the same).
    realize_accelerations(m);
    m.reference_udot = 0.0;
    add_scaled(m.reference_udot, 1.0, m.current.getUDot());
    tree().accelerations(m, last_substep);
    double scale = 1, worst = 0;
    int worst_u = -1;
    for (int i = 0; i < m.udot.size(); ++i) {
      scale = std::max(scale, std::abs(m.reference_udot[i]));
      const double difference = std::abs(m.reference_udot[i] - m.udot[i]);
      if (!(difference <= worst)) {  // a NaN counts as the worst
        worst = difference;
        worst_u = i;
      }
    }
    const double relative = worst / scale;
    const double t_s =
        (static_cast<double>(m.ticks) + static_cast<double>(m.substep) / m.substeps) * m.tick_s;
    ++m.check.compared;
    if (relative <= m.check.agreement) {
      if (relative > m.check.worst_relative) {
        m.check.worst_relative = relative;
        m.check.worst_time_s = t_s;
      }
      return;
    }
    // A reference that breaks its own loop constraints cannot judge: where loop rows are
    // redundant (a planar parallelogram) Simbody's constrained solve can leave them, while
    // the tree's holds them.
    if (m.has_constraints && reference_off_constraints(m, scale)) {
      ++m.check.reference_off_constraints;
      return;
    }
    std::ostringstream out;
    out << "the dynamics check failed at t = " << t_s << " s: the small-tree dynamics and "
        << "Simbody's differ by " << worst << " in acceleration " << worst_u << " (body "
        << body_of_speed(m, worst_u) << "; tree " << m.udot[worst_u] << ", Simbody "
        << m.reference_udot[worst_u] << "), " << relative
        << " of the largest acceleration, beyond the agreement of " << m.check.agreement;
    throw Error(ErrorKind::runtime, out.str());
  }

  void tree_axis_column(Multibody::Impl& m, const SimTK::State& s, int a) const override {
    tree().tree_axis_column(m, s, a);
  }
  void loop_axis_column(Multibody::Impl& m, const SimTK::State& s, int a) const override {
    tree().loop_axis_column(m, s, a);
  }
  void qdot(Multibody::Impl& m) const override { tree().qdot(m); }
  void project_speeds(Multibody::Impl& m) const override { tree().project_speeds(m); }
  void project(Multibody::Impl& m) const override { tree().project(m); }

 private:
  static const Dynamics& tree() { return tree_dynamics(); }
};

}  // namespace

const Dynamics& checked_dynamics() {
  static const CheckedPath path;
  return path;
}

}  // namespace s2sim::model
