#pragma once
/// \file
/// The equations of motion the integrator steps, behind one interface chosen once at load
/// (select_dynamics, dynamics.cpp):
///   - tree: S2Sim's own small-tree dynamics (tree_dynamics.hpp with loop_constraints.hpp,
///     tree_path.cpp), the model: every system of free, hinge, slider, universal, ball and
///     fixed joints with loop joints of any kind whose accelerations matched Simbody's at load;
///   - simbody: Simbody's realize chain (simbody_path.cpp), the reference, and the dynamics of
///     a system the tree cannot take (a mobilizer it does not know, a check at load that
///     failed, loops while joint reactions are read);
///   - checked: the tree steps, and at every substep Simbody computes the same accelerations
///     from the same state and loads; a difference beyond kDynamicsAgreement stops the run
///     (checked_dynamics.cpp), as MuJoCo's forward/inverse comparison does.
/// Only kernel/src/model/ includes this header (it pulls in Simbody through multibody_impl).

#include "model/multibody_impl.hpp"

namespace s2sim::model {

/// How far the tree's and Simbody's accelerations may differ on the same state and loads:
/// relative to the largest acceleration (at least 1). The check at load and the checked
/// dynamics both use it.
constexpr double kDynamicsAgreement = 1e-9;

/// A mobilized body's frame in Ground, and its velocity, as the loop axes read them.
struct BodyFrame {
  SimTK::Rotation R;  ///< body to Ground
  SimTK::Vec3 origin;
};
struct BodyVelocity {
  SimTK::Vec3 angular, linear;  ///< of the body origin, Ground
};

/// One implementation of the equations of motion. Each method works on the current state
/// `m.current` (or `s`, which is it) and Multibody::Impl's buffers; none allocates.
class Dynamics {
 public:
  virtual ~Dynamics() = default;
  virtual const char* name() const = 0;

  /// Makes the bodies' poses and velocities of `s` readable (body_frame, read_bodies).
  virtual void realize_velocity(const Multibody::Impl& m, const SimTK::State& s) const = 0;
  /// The poses and twists of the mobilized bodies (kernel indices), after realize_velocity.
  virtual void read_bodies(const Multibody::Impl& m, const SimTK::State& s, Pose* poses,
                           Twist* twists) const = 0;
  /// A mobilized body's frame (loop axes; `s` at least at Position).
  virtual BodyFrame body_frame(const Multibody::Impl& m, const SimTK::State& s,
                               SimTK::MobilizedBodyIndex body) const = 0;
  /// Its velocity, after realize_velocity.
  virtual BodyVelocity body_velocity(const Multibody::Impl& m, const SimTK::State& s,
                                     SimTK::MobilizedBodyIndex body) const = 0;
  /// A direction fixed in a mobilized body, in Ground (`s` at least at Position).
  virtual SimTK::Vec3 to_ground(const Multibody::Impl& m, const SimTK::State& s,
                                SimTK::MobilizedBodyIndex body, const SimTK::Vec3& v_B) const = 0;

  /// m.udot = M⁻¹·(f − c) under the substep's loads (add_applied_loads), constrained by the
  /// loops; the joint reactions too on the tick's last substep when they are read.
  virtual void accelerations(Multibody::Impl& m, bool last_substep) const = 0;
  /// M⁻¹·g for a unit load on tree axis `a` into m.minv_column's column a (`s` at Position).
  virtual void tree_axis_column(Multibody::Impl& m, const SimTK::State& s, int a) const = 0;
  /// For loop axis `a`, whose unit load is m.unit_body_forces: its generalized force g = Jᵀ·F
  /// into m.loop_unit_force[a], and M⁻¹·g into m.minv_column's column a.
  virtual void loop_axis_column(Multibody::Impl& m, const SimTK::State& s, int a) const = 0;
  /// For unit forces along `directions` (two) at `point` (Ground) on mobilized body `body`:
  /// their generalized forces g_j = Jᵀ·F_j over the speeds [u_begin, u_end), which hold the
  /// body's tree, into g[j] (each over every speed; the others are left as they are). `s` at
  /// Position.
  virtual void point_forces(Multibody::Impl& m, const SimTK::State& s,
                            SimTK::MobilizedBodyIndex body, const SimTK::Vec3& point,
                            const SimTK::Vec3* directions, int u_begin, int u_end,
                            double* const* g) const = 0;
  /// x = M⁻¹·g over [u_begin, u_end), g zero outside it and the range holding `body`'s tree
  /// (arrays over every speed); the mass matrix of this substep's accelerations.
  virtual void solve_speeds(Multibody::Impl& m, const SimTK::State& s,
                            SimTK::MobilizedBodyIndex body, int u_begin, int u_end, const double* g,
                            double* x) const = 0;
  /// q' = N(q)·u into m.qdot.
  virtual void qdot(Multibody::Impl& m) const = 0;
  /// The speeds projected onto the loops' velocity constraints (systems with constraints).
  virtual void project_speeds(Multibody::Impl& m) const = 0;
  /// The positions, then the speeds, projected onto the loop constraints; throws
  /// s2sim::Error (runtime) when the loops cannot be closed.
  virtual void project(Multibody::Impl& m) const = 0;
};

/// The implementations, stateless (what they keep is Multibody::Impl's): one instance each.
const Dynamics& tree_dynamics();
const Dynamics& simbody_dynamics();
const Dynamics& checked_dynamics();

/// The one place where the dynamics are chosen: from m.choice, whether the tree was built at
/// load (build_fast_path) and whether joint reactions are read with loops. Sets m.dynamics;
/// called at load and when a load-time setting changes the answer.
void select_dynamics(Multibody::Impl& m);

}  // namespace s2sim::model
