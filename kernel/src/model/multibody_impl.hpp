#pragma once
/// \file
/// Multibody's Simbody objects and the helpers shared by model/'s translation units. Only
/// kernel/src/model/ includes this header (it pulls in Simbody: C++17, see kernel/CMakeLists).

#include "model/loop_constraints.hpp"
#include "model/loose_bodies.hpp"
#include "model/multibody.hpp"
#include "model/tree_dynamics.hpp"

#include <s2sim/component.hpp>

#include <Simbody.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace s2sim::model {

class Dynamics;

inline SimTK::Vec3 to_simtk(const Vec3& v) {
  return {v.x, v.y, v.z};
}
inline Vec3 from_simtk(const SimTK::Vec3& v) {
  return {v[0], v[1], v[2]};
}

inline SimTK::Rotation to_simtk(const Mat3& m) {
  SimTK::Mat33 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r(i, j) = m.m[i][j];
  return SimTK::Rotation(r);  // re-orthonormalised: scene rotations carry rounding
}
inline Mat3 from_simtk(const SimTK::Rotation& r) {
  Mat3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      m.m[i][j] = r.asMat33()(i, j);
  return m;
}
inline SimTK::Transform to_simtk(const Pose& p) {
  return SimTK::Transform(to_simtk(p.rotation), to_simtk(p.position));
}
/// A Simbody body's mass properties as the tree dynamics holds them: mass, centre of mass
/// and the inertia about it, body frame.
inline void central_mass_of(const SimTK::MassProperties& mp, double& mass_kg, Vec3& com_B,
                            Mat3& central_inertia_B) {
  mass_kg = mp.getMass();
  com_B = from_simtk(mp.getMassCenter());
  const SimTK::Mat33 I = mp.calcCentralInertia().toMat33();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      central_inertia_B.m[r][c] = I(r, c);
}

/// v[i] through raw storage where it is contiguous (a State's q and u are): Vector's element
/// access is a non-inline call into SimTKcommon.
inline double element(const SimTK::Vector& v, int i) {
  return v.hasContiguousData() ? v.getContiguousScalarData()[i] : v[i];
}

/// Gravity, m/s², along −Z: the SDK's one value.
constexpr double kGravity = kGravity_m_s2;
/// The loop constraints' projections: the RMS of the errors they leave (m, or the cosine's for
/// an angle; m/s for the speeds), Simbody's project() accuracy, and the corrections a
/// configuration gets before it is declared impossible.
constexpr double kLoopTolerance = 1e-10;
constexpr double kLoopOvershoot = 0.1;  // a projection aims at kLoopTolerance·kLoopOvershoot
constexpr int kLoopIterations = 20;
/// A joint stop rings at ω·h = this (h the substep), far inside the integrator's stability
/// limit.
constexpr double kStopRinging = 0.2;

/// How an axis's value is realised.
struct AxisImpl {
  // Tree joint: a mobilizer coordinate.
  SimTK::MobilizedBodyIndex mobod;
  int coordinate = 0;  // which q/u of the mobilizer
  double sign = 1;     // axis value = sign * q (ODE convention: body1 relative to body2)
  // Loop joint: measured from the two bodies.
  int body1 = -1, body2 = -1;     // kernel body indices (0 = world)
  SimTK::UnitVec3 axis_in_body2;  // rotation axis or slide direction, body2 frame
  SimTK::Rotation relative0;      // initial body1 orientation in body2 frame
  SimTK::Vec3 offset0_in_body2;   // initial body1 origin in body2 frame
  SimTK::Vec3 anchor_in_body1;    // slider force application point
};

/// The axes' M⁻¹ columns, each kept over its axis tree's speeds only (axis_trees.cpp): a
/// column is exactly zero in every other tree (M is block diagonal over them), so a scene's
/// columns grow with its robots, not with their square. Axis a's number for speed u is
/// of(a)[u − u_begin[a]], for u in [u_begin[a], u_end[a]).
struct AxisColumns {
  std::vector<double> values;
  std::vector<std::size_t> start;   // per axis: its first number in values
  std::vector<int> u_begin, u_end;  // per axis: its speeds
  double* of(std::size_t a) { return values.data() + start[a]; }
  const double* of(std::size_t a) const { return values.data() + start[a]; }
  int size(std::size_t a) const { return u_end[a] - u_begin[a]; }
  /// Axis a's number for speed u: zero outside its speeds.
  double at(std::size_t a, int u) const {
    return u >= u_begin[a] && u < u_end[a]
               ? values[start[a] + static_cast<std::size_t>(u - u_begin[a])]
               : 0.0;
  }
};

/// Multibody's data in three groups: the model (built at load, then only read), the state (what
/// a snapshot holds: every member of that group is reached by one of the segments that
/// Multibody::declare_state registers, multibody.cpp) and the scratch (preallocated buffers,
/// written and read within a tick, so that stepping does not allocate: never needed to
/// continue a run). The per-tick loads the kernel writes before every tick sit between
/// (sim/step.cpp clears them first: not state either).
struct Multibody::Impl {
  // === Model: built at load (multibody_build.cpp), then only read ===============================
  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter{system};
  SimTK::GeneralForceSubsystem forces{system};
  // Gravity is applied by AppliedLoads, not by a Force::Gravity: Simbody's costs a tenth of
  // a small robot's step in cache bookkeeping for three multiplications per body.
  struct Weight {
    SimTK::MobilizedBodyIndex mobod;
    double mass_kg;
    SimTK::Vec3 com_m;  // body frame
  };
  std::vector<Weight> weights;
  // Per kernel body, the inertia its joint's motors add about its centre of mass (axis_disks,
  // multibody_build.cpp): kept when the body's own mass properties change while running.
  std::vector<SimTK::Inertia> joint_disk_inertia;
  std::vector<SimTK::MobilizedBodyIndex> mobod_of_body;  // kernel body -> mobod (invalid: loose)
  // The kernel bodies this system moves with a mobilizer, ascending, with their mobods: what
  // the per-substep loops walk. A part of the island-parallel step holds the scene's kernel
  // indices but moves a fraction of them; walking mobod_of_body cost each part the whole scene.
  struct JointedBody {
    std::size_t body;
    SimTK::MobilizedBodyIndex mobod;
  };
  std::vector<JointedBody> jointed_bodies;
  std::vector<Pose> initial_pose;       // kernel body -> pose at load
  std::vector<std::string> body_names;  // kernel body -> "'id' of robot 'r'", for errors
  std::vector<AxisInfo> axes;
  std::vector<AxisImpl> axis_impl;
  std::vector<std::string> warnings;
  /// A joint stop: a linear spring-damper on one axis outside [low, high], never pulling.
  struct Stop {
    int axis;
    double low, high;
    double stiffness = 0, damping = 0;
  };
  std::vector<Stop> stops;
  // The joint couplings (scene::JointCoupling) as Simbody CoordinateCouplers, in mobilizer
  // coordinates (a Pin's or Slider's one q): q_follower = ratio·q_leader + offset.
  struct Coupler {
    SimTK::ConstraintIndex constraint;
    SimTK::MobilizedBodyIndex follower, leader;
    double ratio = 1, offset = 0;
  };
  std::vector<Coupler> couplers;
  std::vector<int> axis_u;          // per tree axis, its index in u (-1: loop axis)
  std::vector<int> axis_q;          // and in q (a Pin's, Slider's or Universal's q' = u)
  std::vector<char> q_shapes_mass;  // per q: whether M depends on it (axis_columns.cpp)
  struct Root {
    int q0, u0;  // a free root's quaternion and angular velocity indices
  };
  std::vector<Root> roots;
  std::vector<int> axis_root;  // per axis: its tree's free root (-1: none)
  // Joint reactions (request_joint_reactions): per scene joint, the mobilizer realising it
  // (invalid for a loop-closing joint) and whether its child is body1.
  struct JointReaction {
    SimTK::MobilizedBodyIndex mobod;
    bool child_is_body1 = true;
    int body1 = 0;  // kernel index
  };
  std::vector<JointReaction> joint_reaction_source;
  bool reactions_wanted = false;       // set at load by the components that read them
  bool contact_wrenches_used = false;  // substep_wrenches are written every substep (contact)
  SimTK::State initial_state;
  std::vector<int> quaternion_q;  // first q index of each quaternion (Free and Ball mobilizers)
  // q' = N(q)·u by hand when every mobilizer is Free, Ball (quaternion) or has q' = u:
  // Simbody's multiplyByN goes through its state digest for what is a copy plus one quaternion
  // rate per free body or ball.
  struct FreeCoordinates {
    int q, u;  // first indices: quaternion then position; angular then linear velocity
  };
  std::vector<FreeCoordinates> free_coordinates;
  std::vector<FreeCoordinates> ball_coordinates;        // a quaternion and an angular velocity
  std::vector<std::pair<int, int>> direct_coordinates;  // (q, u) of mobilizers with q' = u
  bool own_n = true;
  // The Force::Custom carrying the loads through Simbody's force subsystem: disabled in the
  // states of a system without constraints, whose loads realize_accelerations writes into the
  // system's force arrays itself.
  SimTK::ForceIndex applied_loads_force;
  bool has_constraints = false;
  bool has_mobilized_bodies = true;  // false: every body is loose (Simbody holds only Ground)
  double tick_s = 1e-3;
  int substeps = 1;
  // The small-tree dynamics (tree_dynamics.hpp, fast_path.cpp): built at load when every
  // mobilizer is Free, Pin, Slider, Universal, Ball or Weld and the constraints (if any) are
  // of the kinds loop_constraints.hpp knows, and it agreed with Simbody on a probe state.
  std::unique_ptr<TreeDynamics> tree;
  std::unique_ptr<LoopConstraints> loops;  // with the tree, when the system has constraints
  // The equations of motion stepped (dynamics.hpp), chosen once by select_dynamics from
  // `choice`, the tree above and the joint reactions wanted.
  DynamicsChoice choice = DynamicsChoice::tree_where_possible;
  const Dynamics* dynamics = nullptr;
  DynamicsCheck check;  // what the checked dynamics found so far (not state)
  // The checked dynamics' scratch: Simbody's accelerations, the tree's moved onto the loops,
  // and the loops' acceleration errors, impulses and their speed changes.
  SimTK::Vector reference_udot, projected_udot;
  SimTK::Vector constraint_errors, constraint_impulses, constraint_forces, constraint_du;

  // === State: what a snapshot holds (declare_state, multibody.cpp) ==============================
  // multibody/time
  std::int64_t ticks = 0;
  bool half_kick_pending = true;
  // multibody/q, multibody/u, multibody/z: the Simbody state's variables (its cache is rebuilt
  // by realize). Its time stays at zero: nothing in the system depends on time (no prescribed
  // motion, no time-dependent force or constraint; the loads are the kernel's), the kernel's
  // clock is `ticks`, and advancing Simbody's would cost a Time-stage realization per substep.
  SimTK::State current;
  // multibody/columns. Per axis: g, the generalized force of a unit load on the axis (tree axis:
  // ±e_u; loop axis: the torque or force pair on its bodies through Jᵀ), and M^-1·g, of the
  // implicit axis solve (axis_columns.cpp). A column is reused while the configuration stays
  // within 1e-7 of the one it was computed at (a robot at rest): M depends on q only.
  std::vector<char> column_valid;
  AxisColumns minv_column;
  std::vector<SimTK::Vector> loop_unit_force;  // g of the loop axes (empty for tree axes)
  std::vector<double> column_scratch;          // a column over every speed, being solved
  SimTK::Vector column_scratch_vector;         // the same for Simbody's operators
  std::vector<double> columns_q;               // the q the valid columns were computed at
  std::vector<double> column_root_quat;        // per axis: its root's orientation for its column
  std::vector<double> axis_mobility;  // per axis, its (M^-1)_aa at its last solve (0: none)
  // multibody/reactions: world frame, at the current state (what a joint sensor reads next).
  std::vector<Wrench> joint_reactions;
  // loose/position, loose/velocity: bodies with no joint, integrated outside Simbody (their
  // model, built at load, is LooseBodies' too).
  LooseBodies loose;

  // === Per-tick loads: written by the kernel before every tick (sim/step.cpp clears them) =======
  std::vector<Wrench> wrenches;
  std::vector<double> axis_forces;
  std::vector<double> axis_friction;
  // Axis drives (implicit_axes.cpp): the components' velocity-dependent axis forces for the tick
  // (written through the SDK).
  std::vector<AxisDrive> drives;
  std::int32_t drive_count = 0;

  // === Scratch: preallocated (stepping must not allocate), meaningful within a tick only =======
  // Velocity-level Coulomb friction on tree axes.
  std::vector<char> sliding;  // per axis: Coulomb friction as a plain force
  SimTK::Vector_<SimTK::SpatialVec> unit_body_forces;  // scratch for the loop axes' g
  // This substep's rows of the implicit solve: the drives with damping and the loop axes'
  // regularised Coulomb friction.
  struct DriveRow {
    int axis;
    double force, damping, rate0, low, high;  // f(v) = clamp(force − damping·(v − rate0))
    double applied;                           // its value in this substep
    bool component;                           // a component's (not the loop friction)
  };
  std::vector<DriveRow> rows;
  std::vector<int> first_row, next_row;  // the rows of each axis, as linked lists
  std::vector<int> solve_list;           // the axes solved this substep
  std::vector<double> friction_bound;    // per axis: its Coulomb bound in the solve (0: none)
  std::vector<double> friction_applied;  // per axis: the friction force found
  std::vector<char> axis_stuck;          // per axis: its friction holds it still
  std::vector<double> breakpoints;       // scratch: one axis's drive breakpoints
  std::vector<double> explicit_drive;    // per axis: the drives without damping, clamped
  std::vector<double> rate0;             // per axis: its rate at the tick's first substep
  std::vector<double> drive_sum;         // per axis: Σ over the tick's substeps of drive forces
  std::vector<double> drive_applied;     // per axis: their mean over the last tick (an output:
                                         // the kernel's axis_force_applied segment keeps it)
  // Scratch of one tree's solves, sized for the largest tree (axis_trees.cpp): its solved axes'
  // Delassus matrix W, and the matrix and right side of the Cholesky solve at hand.
  std::vector<double> tree_delassus, tree_matrix, tree_rhs;
  // Per solved axis of the tree, the drive rows' solve (implicit_axes.cpp, step 1): √C, its
  // speed now, C = Σc, R = Σ residuals; the axes with rows.
  std::vector<double> rows_scale, rows_rate, rows_damping, rows_residual;
  std::vector<int> rows_axes;
  // Per solved axis of the tree, the solve in modes (axis_modes.cpp).
  std::vector<double> mode_rhs, mode_force, mode_rate, mode_total, mode_friction;
  std::vector<int> mode_unknown;
  std::vector<char> mode_stuck;
  std::vector<signed char> mode_row_side;  // per row: -1 at its low bound, +1 at its high, 0 free
  // Independent trees (axis_trees.cpp): per axis its tree; per tree the ranges of its speeds
  // and coordinates; scratch: the solved axes ordered by tree, changed trees.
  std::vector<int> axis_tree;
  std::vector<int> tree_u_begin, tree_u_end, tree_q_begin, tree_q_end;
  std::vector<int> tree_cursor;
  std::vector<int> solve_order, tree_solve_start;  // solve_list ordered by tree, each's first
  std::vector<char> tree_changed;
  std::vector<char> tree_sweeps;  // per tree: a bound was hit or an axis has friction (solve_axes)
  // Contact friction on jointed bodies (contact_friction.cpp), solved with the axes. Per kernel
  // body: its tree's speed range [begin, end) (empty: it cannot take friction points) and the
  // axis tree its axes are solved in (-1: none). Per point of the substep, 2 rows: the
  // generalized force g of a unit force along each tangent and M^-1·g over the whole speed
  // vector (zero outside the tree's range), the impulses found; and the points ordered by
  // tree.
  std::vector<int> friction_u_begin, friction_u_end, friction_axis_tree;
  std::vector<FrictionPoint> friction_storage;
  FrictionPoints friction;
  std::vector<int> friction_group_key;  // per kernel body: its points' group (sort key)
  // M^-1 over each range of speeds that carries points, kept while the configuration that
  // shapes M stays within 1e-7 of the one it was computed at and turned with a free root as a
  // whole (T·M^-1·Tᵀ), as the axis columns are (axis_columns.cpp); ranges of more than
  // kMaxCachedSpeeds speeds solve each point's columns instead.
  struct FrictionRange {
    int u_begin = 0, u_end = 0, q_begin = 0, q_end = 0;
    int root = -1;                        // its free root (index into roots), turned with; -1: none
    std::size_t minv = 0, q = 0;          // offsets into friction_minv and friction_minv_q
    bool cached = false;                  // small enough to keep M^-1
    bool valid = false, checked = false;  // checked: this substep
  };
  std::vector<int> friction_range;  // per kernel body: its range (-1: none)
  std::vector<FrictionRange> friction_ranges;
  std::vector<double> friction_minv, friction_minv_q, friction_minv_quat;
  std::vector<char> friction_q_compared;  // per q: a cache compares it (shapes M, or a quaternion
                                          // not turned with)
  int friction_stride = 0;                // the longest speed range: a row's room in the lists
  std::vector<double> friction_g, friction_column, friction_impulse;
  // The columns and W the sweeps use: the raw ones with the tree's linear drives' implicit
  // response folded in (implicit_axes.cpp, couple_friction_to_drives), and that solve's
  // scratch: its axes, √C, the matrix I + κ·S·W·S, a right side; and the axes the current
  // group's columns were built with.
  std::vector<double> friction_effective_column, friction_effective_w;
  std::vector<int> friction_linear, friction_built_linear;
  std::vector<double> friction_scale, friction_coupling, friction_rhs;
  // Blocks: runs of a group's points in friction_order, up to kMaxBlockPoints, solved at once
  // while they stick. Per order position: the size of the block starting there (0 inside
  // one), whether its W was factored, and 64 numbers: its W and that factor; the scratch of its
  // solve.
  std::vector<int> friction_block_size;
  std::vector<char> friction_block_factored;
  std::vector<double> friction_block_w, friction_block_rhs;
  double friction_sweep_slip = 0;  // the last sweep's largest slip met (|v₁| + |v₂|, m/s)
  std::vector<double> friction_full_g, friction_full_column;  // rows over every speed
  SimTK::Vector friction_scratch;                             // Simbody's M^-1 of one row
  std::vector<int> friction_order, friction_group_start;
  int friction_groups = 0;
  int substep = 0;            // index of the current substep in the tick
  bool bodies_fresh = false;  // substep_poses/twists hold the current state
  SimTK::Vector unit_force;
  std::vector<double> unit_speed;  // zero but while a tree axis's column is solved (fast path)
  std::vector<Pose> substep_poses;
  std::vector<Twist> substep_twists;
  std::vector<Wrench> substep_wrenches;
  std::vector<Wrench> joint_reactions_in_body1;      // body1's frame, as computed
  SimTK::Vector_<SimTK::SpatialVec> reactions_at_M;  // preallocated, one per mobilized body
  SimTK::Vector udot, qdot;
  SimTK::Vector_<SimTK::SpatialVec> tree_body_loads;  // the tree dynamics' loads
  std::vector<Wrench> tree_reactions;                 // its mobilizer reactions, one per mobod
  SimTK::Vector tree_mobility_forces;
  std::vector<double> loop_q, loop_u, loop_du, loop_dq;  // the loop projections' (tree_path.cpp)
  double last_kick_s = 0;  // the kick of the current substep (the axis solve is implicit over it)

  const SimTK::State& state() const { return current; }
  const SimTK::MobilizedBody& mobod(int body) const {
    return matter.getMobilizedBody(mobod_of_body[body]);
  }
  SimTK::MobilizedBody& upd_mobod(int body) { return matter.updMobilizedBody(mobod_of_body[body]); }
};

/// An axis's value (rad or m), ODE convention; `state` realized to Position.
double axis_value(const Multibody::Impl& m, const SimTK::State& s, std::size_t a);
/// An axis's rate (rad/s or m/s); `state` realized to Velocity.
double axis_rate(const Multibody::Impl& m, const SimTK::State& s, std::size_t a);
/// Body poses and velocities (kernel indices); `state` realized to Velocity.
void read_bodies(const Multibody::Impl& m, const SimTK::State& s, Pose* poses, Twist* twists);
/// v += a·x, through raw storage where it is contiguous (element access goes through a
/// non-inline helper, and Vector expressions allocate).
void add_scaled(SimTK::Vector& v, double a, const SimTK::Vector& x);
/// v += a·(axis a's M⁻¹ column) over the column's speeds.
void add_column(SimTK::Vector& v, double a, const AxisColumns& columns, std::size_t axis);
/// Axis a's column from `solved`, a column over every speed whose numbers for speeds
/// [u_begin, u_end) were just written (the column's other speeds are zero).
void keep_column(Multibody::Impl& m, std::size_t a, const double* solved, int u_begin, int u_end);
/// The axes' columns sized by their axis trees, zero; after find_axis_trees.
void allocate_axis_columns(Multibody::Impl& m);
/// Partitions the axes into independent trees (axis_trees.cpp); after axis_u is known.
void find_axis_trees(Multibody::Impl& m);
/// Orders this substep's solve_list by tree (solve_order, tree_solve_start), stably.
void group_solve_list_by_tree(Multibody::Impl& m);
/// Adds a load `f` (N·m or N) on axis a: a mobility force for a tree axis, equal and opposite
/// body loads for a loop axis; `state` realized to Position.
void apply_axis_load(const Multibody::Impl& m, const SimTK::State& state, std::size_t a, double f,
                     SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                     SimTK::Vector& mobility_forces);
/// Adds the kernel's loads for this substep (gravity, wrenches, axis forces, sliding friction,
/// drives, stops) to `body_forces` (per mobilized body, world frame) and `mobility_forces`;
/// `state` realized to Velocity. Both the Simbody force below and the unconstrained systems
/// (realize_accelerations) apply them through this one function.
void add_applied_loads(const Multibody::Impl& m, const SimTK::State& state,
                       SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                       SimTK::Vector& mobility_forces);
/// Registers the kernel's loads as a Simbody Force::Custom (add_applied_loads).
void register_applied_loads(Multibody::Impl& m);
/// The bodies' kinematics of `s` made readable by the chosen dynamics (read_bodies,
/// axis_value, axis_rate).
void realize_velocity(const Multibody::Impl& m, const SimTK::State& s);
/// Realizes `m.current` to Acceleration with this substep's loads (Multibody::accelerations,
/// and reset for the first joint reactions): without constraints the loads go straight into
/// the system's force arrays after Dynamics, with constraints through the Force::Custom.
void realize_accelerations(Multibody::Impl& m);

/// The small-tree dynamics (fast_path.cpp). Builds m.tree where the system allows it and the
/// tree's accelerations match Simbody's on a probe state (else leaves it null, with a warning
/// when they disagree); after prepare_stepping's maps.
void build_fast_path(Multibody::Impl& m);
/// The tree's kinematics for the current state (kept while q and u are unchanged).
void update_tree_kinematics(const Multibody::Impl& m);
/// m.udot for this substep's loads, through the tree (tree_path.cpp).
void tree_accelerations(Multibody::Impl& m);
/// q' = N(q)·u (own_n: every mobilizer Free, Ball or with q' = u), over raw arrays.
void calc_qdot(const Multibody::Impl& m, const double* u, const double* q, double* qdot);
/// Normalises each quaternion of q (Free and Ball mobilizers).
void normalize_quaternions(const Multibody::Impl& m, double* q);
/// A state vector's contiguous storage (a State's q and u are: Simbody allocates them as one
/// block per subsystem).
const double* contiguous_data(const SimTK::Vector& v);

/// Axis Coulomb friction (implicit_axes.cpp): marks the axes that slide clearly, which get a
/// plain force, before the accelerations are computed.
void classify_sliding(Multibody::Impl& m, const SimTK::State& s, double h);
/// The regularisation speed of a loop axis's Coulomb friction (a force, not a brake).
double loop_friction_speed();

/// M^-1 columns (axis_columns.cpp): makes minv_column's column a current for every axis in `axes`;
/// `state` realized to Position.
void update_columns(Multibody::Impl& m, const SimTK::State& s, const std::vector<int>& axes);
/// g·x for axis a: the axis's rate for generalized speeds x, or its share of a generalized
/// force x.
double axis_dot(const Multibody::Impl& m, std::size_t a, const SimTK::Vector& x);
/// axis_dot for axis `b`'s M⁻¹ column: (M⁻¹)_ab for a tree axis a.
double axis_dot_column(const Multibody::Impl& m, std::size_t a, std::size_t b);
/// Marks the coordinates M does not depend on (a root's translation, a symmetric wheel's
/// angle): columns stay valid while only those change. After the initial state is built.
void find_mass_matrix_coordinates(Multibody::Impl& m);
/// Whether turning pin mobilizer `i` (no children) leaves the mass distribution unchanged: its
/// centre of mass on the axis, its inertia symmetric about it (a wheel, a rotor).
bool turning_keeps_mass(const Multibody::Impl& m, SimTK::MobilizedBodyIndex i,
                        const SimTK::State& s);
/// The system's default state (after realizeTopology) with the kernel's instance settings.
SimTK::State default_state(Multibody::Impl& m);
/// The joint stops' stiffness and damping from their axes' effective inertia in `state`, so
/// that each rings at `omega` (rad/s), critically damped.
void tune_stops(Multibody::Impl& m, const SimTK::State& state, double omega);
/// Forgets every column (reset).
void clear_columns(Multibody::Impl& m);

/// Axis drives (implicit_axes.cpp). Before the accelerations: the rows of this substep and
/// their explicit values, which the applied loads add.
void prepare_drives(Multibody::Impl& m, const SimTK::State& s);
/// After the explicit kick u += κ·u': the drives' forces at the kick's end velocity, implicit,
/// within their bounds, together with the tree axes' Coulomb friction (implicit_axes.cpp);
/// the drives' mean over the tick is recorded for the axis torque signals.
void solve_axes(Multibody::Impl& m, SimTK::State& s, double kick_s);

/// The most points of one tree solved as a block (friction_sweeps.cpp).
constexpr int kMaxBlockPoints = 8;
/// Contact friction on jointed bodies (contact_friction.cpp). At load: each body's speed range
/// and axis tree (after find_axis_trees).
void find_friction_ranges(Multibody::Impl& m);
/// Before the axes are solved: the columns and W of this substep's friction points (`s`
/// realized to Position), ordered and grouped by tree; false: there are none.
bool prepare_contact_friction(Multibody::Impl& m, const SimTK::State& s);
/// One Gauss–Seidel sweep over group `group`'s points at the kick's end speeds
/// (friction_sweeps.cpp): each point's impulses (or a body's block's, while it sticks) solved
/// for zero slip within κ times its bounds, the others held. Returns the largest speed change
/// it made at a point (m/s); friction_sweep_slip, the largest slip it met.
double sweep_contact_friction(Multibody::Impl& m, SimTK::Vector& u, int group, double kick_s);
/// Group `group`'s points' columns and W as the sweeps use them, uncoupled: the raw columns,
/// copied (copy_raw_friction), their W and their blocks built.
void copy_raw_friction(Multibody::Impl& m, int group);
void uncoupled_friction(Multibody::Impl& m, int group);
/// A pair of rows' 2×2 block of W, w_jk = g_j·c_k over `span` speeds: four sums in one pass,
/// each term in the order of its own dot product.
inline void friction_pair_w(const double* g0, const double* g1, const double* c0, const double* c1,
                            int span, double* w) {
  double w00 = 0, w01 = 0, w10 = 0, w11 = 0;
  for (int e = 0; e < span; ++e) {
    w00 += g0[e] * c0[e];
    w01 += g0[e] * c1[e];
    w10 += g1[e] * c0[e];
    w11 += g1[e] * c1[e];
  }
  w[0] = w00;
  w[1] = w01;
  w[2] = w10;
  w[3] = w11;
}
/// The W of group `group`'s blocks from the columns the sweeps use.
void build_friction_blocks(Multibody::Impl& m, int group);
/// The axis tree of friction group `group` (-1: its tree has no solved axes).
int friction_group_tree(const Multibody::Impl& m, int group);
/// The points' forces (impulse / κ) written out.
void finish_contact_friction(Multibody::Impl& m, double kick_s);

/// A drive row's law at an axis rate: clamp(force − damping·(rate − rate0), low, high).
inline double drive_law(const Multibody::Impl::DriveRow& r, double rate) {
  return std::clamp(r.force - r.damping * (rate - r.rate0), r.low, r.high);
}
/// One tree's tree axes solve_order[begin, end) solved exactly in the modes they are in now
/// (axis_modes.cpp): each axis stuck by its friction, or sliding with each of its drive rows
/// at a bound or on its slope, a linear system in the axes' Delassus matrix (tree_delassus, as
/// solve_axes built it). Applies the solution and returns true when it stays in those modes;
/// else changes nothing, false.
bool solve_tree_in_modes(Multibody::Impl& m, SimTK::State& s, int tree, int begin, int end,
                         double kick_s);

/// Joint reactions (joint_reactions.cpp) from a state realized to Acceleration.
void compute_joint_reactions(Multibody::Impl& m, const SimTK::State& s);
/// The same on the tree, from its kinematics, loads and accelerations (after
/// tree_accelerations: systems without constraints).
void compute_tree_joint_reactions(Multibody::Impl& m);
/// The reactions carried with body1 to its pose at the step's end.
void carry_joint_reactions(Multibody::Impl& m, const Pose* poses);

/// How bodies answer a wrench at their centre of mass with every joint free, from rest in a
/// state realized to Position: J M⁻¹ Jᵀ on the loads (apparent_mass_kg, contact_mobility; at
/// load only, its buffers are its own). Bodies of different trees (hanging from Ground) are
/// loaded at once: a tree answers its own loads only, with the same numbers as alone, so a
/// scene of n robots costs as much as its largest robot, n times over, not n² times. Defined
/// in contact_mobility.cpp.
class LoadResponse {
 public:
  explicit LoadResponse(const Multibody::Impl& m);
  /// The jointed bodies `wanted(b)` takes (kernel bodies), in rounds of at most one per tree:
  /// round r holds each tree's r-th such body, in body order.
  template <class Wanted>
  std::vector<std::vector<std::size_t>> rounds(Wanted&& wanted) const;
  /// Kernel body b's mobilized body.
  const SimTK::MobilizedBody& mobod(std::size_t b) const {
    return m_.matter.getMobilizedBody(m_.mobod_of_body[b]);
  }
  /// No load.
  void clear();
  /// Adds `torque` and `force` (ground axes) at the COM of kernel body `b`, the only loaded
  /// body of its tree.
  void add(const SimTK::State& s, std::size_t b, const SimTK::Vec3& torque,
           const SimTK::Vec3& force);
  /// The accelerations the loads give.
  void solve(const SimTK::State& s);
  /// After solve(): body b's angular acceleration and its COM's acceleration, ground axes.
  std::pair<SimTK::Vec3, SimTK::Vec3> at_com(const SimTK::State& s, std::size_t b) const;

 private:
  const Multibody::Impl& m_;
  SimTK::Vector_<SimTK::SpatialVec> load_, accel_;
  SimTK::Vector f_, udot_;

  /// Body b's COM from its origin, ground axes.
  SimTK::Vec3 com_G(const SimTK::State& s, std::size_t b) const {
    return mobod(b).getBodyRotation(s) * mobod(b).getBodyMassProperties(s).getMassCenter();
  }
};

template <class Wanted>
std::vector<std::vector<std::size_t>> LoadResponse::rounds(Wanted&& wanted) const {
  std::vector<std::vector<std::size_t>> out;
  std::vector<std::size_t> taken(static_cast<std::size_t>(m_.matter.getNumBodies()), 0);
  for (std::size_t b = 1; b < m_.mobod_of_body.size(); ++b) {
    if (!m_.mobod_of_body[b].isValid() || !wanted(b)) continue;
    const auto tree =
        static_cast<std::size_t>(mobod(b).getBaseMobilizedBody().getMobilizedBodyIndex());
    const std::size_t r = taken[tree]++;
    if (r == out.size()) out.emplace_back();
    out[r].push_back(b);
  }
  return out;
}

}  // namespace s2sim::model
