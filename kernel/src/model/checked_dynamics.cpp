// The checked dynamics (dynamics.hpp): the small-tree dynamics step, and at every substep
// Simbody's realize chain computes the accelerations of the same state under the same loads
// first. With loops, where the two differ beyond the agreement both are first moved onto the
// loops' acceleration constraints (redundant loop rows leave the constraint forces open, and
// either solve a little off the loops). A difference beyond the agreement (kDynamicsAgreement
// unless set) then stops the run, naming the body; the largest difference within it, and the
// largest loop errors met, are kept for the report. The stepping is the tree's alone, so a
// checked run gives the unchecked run's numbers bit for bit.
#include "model/dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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

/// The largest difference between two accelerations, relative to the largest acceleration of
/// either (at least 1); a NaN counts as the worst.
struct Difference {
  double absolute = 0, relative = 0, scale = 1;
  int speed = -1;
};
Difference largest_difference(const SimTK::Vector& a, const SimTK::Vector& b) {
  Difference d;
  for (int i = 0; i < a.size(); ++i) {
    d.scale = std::max({d.scale, std::abs(a[i]), std::abs(b[i])});
    const double difference = std::abs(a[i] - b[i]);
    if (!(difference <= d.absolute)) {
      d.absolute = difference;
      d.speed = i;
    }
  }
  d.relative = d.absolute / d.scale;
  return d;
}

/// Accelerations moved onto the loops' acceleration constraints G·u̇ = b along M⁻¹·Gᵀ, the
/// directions of constraint forces (Gauss's principle): u̇ += M⁻¹·Gᵀ·λ with
/// W·λ = −(G·u̇ − b), W = G·M⁻¹·Gᵀ solved by a pseudo-inverse. Accelerations that differ only by
/// constraint forces land on the same point, so this compares the constrained accelerations,
/// which are unique even where redundant rows leave the constraint forces open. The cutoff of
/// the singular values is numpy's (10·m·ε of the largest), not Simbody's own rank choice: as
/// the walker's parallelogram nears a singular pose, W keeps a direction at 1e-11 of the
/// largest that Simbody's solve drops, leaving its accelerations off the loops. It allocates:
/// it runs only where the two solves part.
class LoopProjection {
 public:
  explicit LoopProjection(Multibody::Impl& m) : m_(m) {
    m.matter.calcProjectedMInv(m.current, w_);
    const double cutoff = 10.0 * w_.nrow() * std::numeric_limits<double>::epsilon();
    svd_.factor(w_, cutoff);
  }
  /// Moves `udot` onto the loops; returns its RMS loop acceleration error before the move.
  double move(SimTK::Vector& udot) {
    m_.matter.calcConstraintAccelerationErrors(m_.current, udot, m_.constraint_errors);
    const double error = m_.constraint_errors.normRMS();
    m_.constraint_errors *= -1;
    svd_.solve(m_.constraint_errors, m_.constraint_impulses);
    m_.matter.multiplyByGTranspose(m_.current, m_.constraint_impulses, m_.constraint_forces);
    m_.matter.multiplyByMInv(m_.current, m_.constraint_forces, m_.constraint_du);
    udot += m_.constraint_du;
    return error;
  }

 private:
  Multibody::Impl& m_;
  SimTK::Matrix w_;
  SimTK::FactorSVD svd_;
};

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
    Difference difference = largest_difference(m.reference_udot, m.udot);
    const double t_s =
        (static_cast<double>(m.ticks) + static_cast<double>(m.substep) / m.substeps) * m.tick_s;
    ++m.check.compared;
    const SimTK::Vector* tree_udot = &m.udot;
    if (!(difference.relative <= m.check.agreement) && m.has_constraints) {
      // Where loop rows are redundant (a planar parallelogram) the constraint forces are not
      // unique, and the two constrained solves can part, each a little off the loops: judge
      // the constrained accelerations, which are unique, by moving both onto the loops.
      m.projected_udot = m.udot;
      const double scale = difference.scale;
      LoopProjection onto_loops(m);
      const double tree_error = onto_loops.move(m.projected_udot) / scale;
      const double reference_error = onto_loops.move(m.reference_udot) / scale;
      difference = largest_difference(m.reference_udot, m.projected_udot);
      tree_udot = &m.projected_udot;
      ++m.check.judged_on_loops;
      m.check.worst_loop_error = std::max(m.check.worst_loop_error, tree_error);
      m.check.worst_reference_loop_error =
          std::max(m.check.worst_reference_loop_error, reference_error);
    }
    if (difference.relative <= m.check.agreement) {
      if (difference.relative > m.check.worst_relative) {
        m.check.worst_relative = difference.relative;
        m.check.worst_time_s = t_s;
      }
      return;
    }
    const int u = difference.speed;
    std::ostringstream out;
    out << "the dynamics check failed at t = " << t_s << " s: the small-tree dynamics and "
        << "Simbody's differ by " << difference.absolute << " in acceleration " << u << " (body "
        << body_of_speed(m, u) << "; tree " << (*tree_udot)[u] << ", Simbody "
        << m.reference_udot[u] << "), " << difference.relative
        << " of the largest acceleration, beyond the agreement of " << m.check.agreement;
    if (tree_udot != &m.udot) out << ", both moved onto the loop constraints";
    throw Error(ErrorKind::runtime, out.str());
  }

  void tree_axis_column(Multibody::Impl& m, const SimTK::State& s, int a) const override {
    tree().tree_axis_column(m, s, a);
  }
  void loop_axis_column(Multibody::Impl& m, const SimTK::State& s, int a) const override {
    tree().loop_axis_column(m, s, a);
  }
  void point_forces(Multibody::Impl& m, const SimTK::State& s, SimTK::MobilizedBodyIndex body,
                    const SimTK::Vec3& point, const SimTK::Vec3* directions, int u_begin, int u_end,
                    double* const* g) const override {
    tree().point_forces(m, s, body, point, directions, u_begin, u_end, g);
  }
  void solve_speeds(Multibody::Impl& m, const SimTK::State& s, SimTK::MobilizedBodyIndex body,
                    int u_begin, int u_end, const double* g, double* x) const override {
    tree().solve_speeds(m, s, body, u_begin, u_end, g, x);
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
