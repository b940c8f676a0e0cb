#pragma once
/// \file
/// The scene's bodies and joints as a Simbody multibody system. Simbody never leaks out of
/// multibody.cpp: the rest of the kernel sees plain arrays of poses, twists and axis values,
/// and writes plain arrays of applied loads.

#include "model/substep_forces.hpp"

#include <s2sim/component.hpp>
#include <s2sim/kernel/scene.hpp>
#include <s2sim/math.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace s2sim::common {
class StateLayout;
}

namespace s2sim::model {

/// One degree of freedom of a joint.
struct AxisInfo {
  std::string name;  ///< the joint ID, `<ID>:2` for a Universal joint's second axis
  int robot = -1;
  int joint = -1;  ///< index into Scene::joints
  int which = 0;   ///< 0 or 1 (Universal second axis)
  bool linear = false;
  bool loop = false;  ///< closes a kinematic loop (realised by constraints, not a mobilizer)
};

/// The joint graph resolved before any Simbody object exists: the spanning forest the
/// multibody is built along and its axis table. The simulation configures its components
/// against these axes (they may declare axis inertias, e.g. a motor's reflected rotor inertia)
/// and builds the Multibody from the same plan afterwards.
struct Topology {
  struct Edge {
    int joint, parent, child;  ///< scene indices; parent -1 = the world, joint -1 = a Free root
  };
  std::vector<Edge> tree;           ///< parents first
  std::vector<int> loops;           ///< loop-closing joints (constraints), in the order met
  std::vector<int> loose;           ///< bodies with no joint, integrated outside Simbody
  std::vector<char> joint_is_loop;  ///< per scene joint
  std::vector<AxisInfo> axes;       ///< in joint order, then axis 1, axis 2
};

/// Plans the multibody of `scene`. Throws s2sim::Error (scene) for a joint Simbody cannot
/// realise in any tree (a joint from the world to itself). Bodies without any joint are loose
/// unless `lone_bodies_in_simbody` (for tests that compare the two).
Topology plan_topology(const scene::Scene& scene, bool lone_bodies_in_simbody = false);

/// Which equations of motion step a multibody (model/dynamics.hpp says what each is).
enum class DynamicsChoice {
  tree_where_possible,  ///< the small-tree dynamics wherever they were built, else Simbody's
  simbody,              ///< Simbody's realize chain for everything (the reference)
  checked,              ///< the tree steps, Simbody computes the same accelerations to compare
};

/// What the checked dynamics found: how many accelerations it compared, and the largest
/// difference relative to the largest acceleration of its substep (at least 1).
struct DynamicsCheck {
  std::int64_t compared = 0;
  double worst_relative = 0;
  double worst_time_s = 0;  ///< when the worst one was seen
  double agreement = 0;     ///< the largest relative difference allowed (kDynamicsAgreement)
  /// Substeps where the two parted beyond the agreement on a system with loops and were
  /// judged after moving both onto the loops' acceleration constraints, and the largest RMS
  /// loop acceleration errors (relative, as above) of the tree's and Simbody's found there.
  std::int64_t judged_on_loops = 0;
  double worst_loop_error = 0, worst_reference_loop_error = 0;
};

/// The scene's bodies and joints as a Simbody system, and the integrator's operations on it.
/// Body index 0 is the world; scene body i is body i + 1. The kernel writes the loads for the
/// coming tick into `applied_wrenches()` and `applied_axis_forces()`; they are held constant
/// over the tick's substeps. sim/step.cpp runs a tick as, per substep: current_bodies() (for
/// contact) → prepare_axes() → accelerations() → kick() → solve_axes() → drift() → project();
/// then finish_tick().
class Multibody {
 public:
  /// Throws s2sim::Error (scene) naming the joint or body Simbody refuses. Bodies without
  /// any joint are integrated by LooseBodies unless `lone_bodies_in_simbody` (for tests that
  /// compare the two).
  Multibody(const scene::Scene& scene, double tick_s, int substeps,
            bool lone_bodies_in_simbody = false);
  /// Builds the planned `topology` of `scene`. `axis_inertia` (per axis of the plan, kg·m²;
  /// shorter or empty: zero) adds to the mass matrix: on a hinge or Universal axis of the tree,
  /// as a massless disk on the axis carried by the joint's child body (exact for the spin of
  /// the axis when the parent does not turn about it, docs/models/multibody.md); on a slider
  /// or a loop-closing axis it is not carried, with a warning.
  /// `drive_slots`: room for that many axis drives per tick (0: four per axis); a part of a
  /// partitioned scene takes the whole scene's, so that it integrates implicitly every drive
  /// the serial run would (multibody_islands.hpp).
  Multibody(const scene::Scene& scene, const Topology& topology,
            const std::vector<double>& axis_inertia, double tick_s, int substeps,
            std::int32_t drive_slots = 0);
  ~Multibody();
  Multibody(const Multibody&) = delete;
  Multibody& operator=(const Multibody&) = delete;

  int body_count() const;
  const std::vector<AxisInfo>& axes() const;
  /// Things the builder had to simplify (e.g. a limit on a loop-closing joint).
  const std::vector<std::string>& warnings() const;

  Wrench* applied_wrenches();
  double* applied_axis_forces();
  /// Per axis, the Coulomb friction bound (N·m or N) for the coming tick, solved at velocity
  /// level after the other forces: an axis whose load stays under the bound sticks.
  double* applied_axis_friction();
  /// The velocity-dependent axis forces for the coming tick (the components' drives, written
  /// through the SDK): `axis_drive_capacity()` slots, `*axis_drive_count()` used; integrated
  /// implicitly (docs/models/multibody.md).
  AxisDrive* axis_drives();
  std::int32_t* axis_drive_count();
  std::int32_t axis_drive_capacity() const;
  /// Per axis, the mean force its drives applied over the last tick (N·m or N).
  const double* drive_force_applied() const;

  /// Turns on the joint reactions: from the next step on, `joint_reactions()` holds per scene
  /// joint the load body2 exerts on body1 through the joint (world frame, torque about the
  /// joint anchor as carried by body1), taken at the tick's last acceleration evaluation.
  /// Loop-closing joints read zero. Off by default: it costs one reaction sweep per tick.
  void request_joint_reactions();
  /// Per scene joint (Scene::joints order); zeros until requested and stepped.
  const Wrench* joint_reactions() const;
  /// Whether a scene joint closes a kinematic loop (constraints: no reaction reported).
  bool joint_is_loop(int joint) const;

  /// Which equations of motion step the system, chosen at load (model/dynamics.hpp).
  void choose_dynamics(DynamicsChoice choice);
  /// The checked dynamics' agreement (relative; kDynamicsAgreement unless set): a tighter one
  /// finds the rounding between the two, a looser one tolerates more.
  void set_dynamics_agreement(double relative);
  /// Whether the small-tree dynamics step the system (tree_dynamics.hpp; alone or checked): a
  /// system of free, hinge, slider, universal, ball and fixed joints, with loop joints of any
  /// kind, whose accelerations matched Simbody's at load; not a system with loops while joint
  /// reactions are read, nor one whose choice is DynamicsChoice::simbody.
  bool uses_tree_fast_path() const;
  /// "tree", "simbody" or "checked": the dynamics that step the system ("loose": it has no
  /// joint, its bodies are LooseBodies').
  const char* dynamics_name() const;
  /// Whether Simbody must compute this system's dynamics: it has mobilized bodies and the tree
  /// could not be built for them (its check at load failed, say), whatever the choice.
  bool needs_simbody_dynamics() const;
  /// What DynamicsChoice::checked compared so far (zeros otherwise).
  DynamicsCheck dynamics_check() const;

  /// The per-body wrenches recomputed from the state at every substep (contact), applied
  /// from now on; the caller writes them before each substep's forces().
  Wrench* use_contact_wrenches();
  /// Room for `points` contact friction points a substep (at load; stepping allocates nothing).
  void reserve_contact_friction(std::int32_t points);
  /// The substep's contact friction points (substep_forces.hpp): written by the contact before
  /// the substep's kick, solved by solve_axes() together with the axes, which writes each
  /// point's force.
  FrictionPoints* contact_friction();
  /// Whether solve_axes() takes friction points on kernel body `body`: a jointed body of a
  /// system without loops (the others' friction stays a force law of the contact).
  bool solves_contact_friction(int body) const;
  /// Per kernel body (0 = world, 0 kg): the smallest mass that a force at the body's centre
  /// of mass meets in the initial configuration, over the three world axes (a free body: its
  /// mass; a wheel: its share of the robot's). Infinite for a body welded to the world.
  std::vector<double> apparent_mass_kg() const;
  /// How a jointed body answers a push at its centre of mass, its joints free (contact's
  /// effective mass at a point): per kernel body, the 6×6 mobility Φ that maps a wrench at the
  /// COM (torque; force) to the body's (angular; COM linear) acceleration in the initial
  /// configuration, Φ = J M⁻¹ Jᵀ, expressed in the axes of its tree's base body (`root`, a
  /// kernel body), so that a robot turning carries it along. root = 0 for the world, loose
  /// bodies (their own mass and inertia say it) and trees whose base is not free.
  struct Mobility {
    int root = 0;
    double phi[6][6] = {};
  };
  std::vector<Mobility> contact_mobility() const;

  /// Back to the initial configuration at rest, t = 0.
  void reset();
  double time_s() const;

  // --- One tick, stage by stage (in this order; sim/step.cpp) ---------------------------------
  int substeps() const;
  double substep_s() const;
  /// Body poses and velocities at the current state, per kernel body (read once per state).
  void current_bodies(const Pose*& poses, const Twist*& twists);
  /// The substep's loads are final: the axis drives' rows and their explicit values
  /// (implicit_axes.cpp), and which axes slide clearly (their Coulomb friction as a force).
  void prepare_axes();
  /// M·u' = f under every load (the chosen dynamics); the joint reactions on the tick's last
  /// substep.
  void accelerations(bool last_substep);
  /// u += h·u' (half a substep on the first one after a reset: leapfrog); loose bodies too.
  void kick();
  /// The axis drives at the kick's end velocity, implicit, (M + h·C)·Δu = h·f within their
  /// bounds, with the axes' Coulomb friction as a velocity-level brake and the contact friction
  /// points' Coulomb friction; loops: velocities projected onto the constraints.
  void solve_axes();
  /// q += h·N(q)·u; the time of the substep's end.
  void drift(int substep);
  /// Loop constraints: q and u projected back onto the constraint manifold.
  void project();
  /// Ends the tick: reads the bodies, carries the joint reactions, checks that the state is
  /// finite (throws s2sim::Error, runtime, naming the first body that is not).
  void finish_tick();
  /// After a failed tick: the first kernel body whose coordinates or speeds are not finite
  /// (-1: none found), and its name for messages ("'id' of robot 'r'").
  int first_non_finite_body() const;
  const std::string& body_name(int body) const;

  /// Copies the current state into the kernel's buffers (sizes: body_count(), axes().size()).
  void read(Pose* poses, Twist* twists, double* axis_position, double* axis_velocity) const;

  /// Kinetic energy, J.
  double kinetic_energy_J() const;
  /// Gravitational potential energy relative to z = 0, J.
  double potential_energy_J() const;

  /// Registers the model's state segments (snapshots; docs/scheduling.md, "Snapshots"):
  /// `multibody/time` (ticks, pending half kick), `multibody/q`, `multibody/u`, `multibody/z`,
  /// `multibody/columns` (the M^-1 column cache: validity flags, columns, loop axes' unit
  /// forces, the q and root quaternions they were computed at, axis mobilities; then the
  /// contact friction's M^-1 per range of speeds, with its validity, q and root quaternion),
  /// `multibody/reactions` (6 per scene joint), then the loose bodies' segments (`loose/…`).
  /// After the layout restored them, call restored(). `prefix` replaces `multibody` in the
  /// names (one part of several, multibody_islands.hpp), and the loose bodies' are then
  /// `<prefix>/loose/…`, declared only by a part that has loose bodies.
  void declare_state(common::StateLayout& layout, const std::string& prefix = "multibody");
  /// Makes the restored segments the current state (time, realized; mid-tick caches dropped).
  void restored();

  /// Moves a body that hangs freely from the world (a loose body, or a Free mobilizer on the
  /// world: the root body of a robot with everything jointed to it) to `pose`, at rest.
  /// Returns false, changing nothing, for any other body. The other bodies' leapfrog goes on
  /// undisturbed; the placed body's zero speed is its mid-step speed.
  bool place_free_body(int body, const Pose& pose);
  /// New mass properties of a loose body (a thing added while running; LooseBodies::
  /// set_mass_properties). False, changing nothing, for any other body.
  bool set_loose_mass(int body, double mass_kg, const Vec3& com_m, const Mat3& inertia,
                      bool gravity, bool fixed = false);
  /// New mass properties of a body moved by a joint or a robot's free root: mass, centre of
  /// mass (body frame) and inertia about it (body axes); the inertia its joint's motors add
  /// stays. The dynamics, the weights, the stops and the caches follow; the coordinates and
  /// speeds are kept. False, changing nothing, for a loose body or an unknown index.
  bool set_jointed_mass(int body, double mass_kg, const Vec3& com_m, const Mat3& inertia);
  /// Moves any body to `pose` as closely as its joint allows, its speeds kept: a loose body
  /// or a robot's root body goes exactly there; a jointed body's mobilizer coordinates are
  /// fitted (a hinge keeps the rotation about its axis), its children following. False for
  /// the world or an unknown index.
  bool move_body(int body, const Pose& pose);
  /// Sets a body's velocity (world frame, of its origin) as closely as its joint allows, the
  /// same way; false for the world or an unknown index.
  bool set_body_velocity(int body, const Twist& twist);
  /// Sets a tree axis's coordinate and rate (axis units: rad or m, rad/s or m/s, with the
  /// axis's sign), the bodies outboard of it following; the other coordinates are kept. False,
  /// changing nothing, for a loop-closing axis (its value follows from the bodies it joins) or
  /// an unknown index.
  bool set_axis_state(std::size_t axis, double position, double velocity);

  struct Impl;  // Simbody's objects, defined in multibody.cpp

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace s2sim::model
