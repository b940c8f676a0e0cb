#pragma once
/// \file
/// The scene's multibody as P parts stepped in parallel: each part is its own Simbody system
/// holding whole islands of the joint graph (island_plan.hpp), and a persistent worker pool
/// runs the parts' stages of a substep at once. The kernel still sees one body numbering and
/// one axis table: the parts read their slices of the scene-wide load arrays and write their
/// slices of the scene-wide poses, twists and axis values. P = 1 is the serial step and the
/// same code: one Multibody over the whole plan, whose arrays are the scene-wide ones, run by
/// a pool of one thread that calls it in place. An island's numbers do not depend on the
/// others in its system (AxisTrees.ARobotMovesBitForBitAsAloneBesideOthersThatDoNotTouchIt), so
/// the results do not depend on P (tests/kernel/sim/parallel_islands_test.cpp).

#include "model/island_plan.hpp"
#include "model/multibody.hpp"
#include "model/substep_forces.hpp"
#include "model/worker_pool.hpp"

#include <atomic>
#include <memory>
#include <string>
#include <vector>

namespace s2sim::model {

class MultibodyIslands {
 public:
  /// The work of one part in a substep (sim/step.cpp: its contact, prepare axes … project,
  /// and the tick's finish on its last substep), called on whichever thread takes the part.
  class PartStages {
   public:
    /// `calling_thread`: the part runs on the thread that called run_substep() or
    /// run_ticks(). Returns whether the part may go on alone (run_ticks(): its shapes are
    /// still inside their fence); run_substep() ignores it.
    virtual bool run(int part, Multibody& multibody, bool calling_thread, int substep) = 0;

   protected:
    ~PartStages() = default;
  };

  /// Builds the planned `topology` of `scene` as at most `threads` parts (fewer when the scene
  /// has fewer islands; threads ≤ 1: one). Throws what Multibody's constructor throws.
  MultibodyIslands(const scene::Scene& scene, const Topology& topology,
                   const std::vector<double>& axis_inertia, double tick_s, int substeps,
                   int threads);
  ~MultibodyIslands();
  MultibodyIslands(const MultibodyIslands&) = delete;
  MultibodyIslands& operator=(const MultibodyIslands&) = delete;

  /// The number of Simbody systems (and threads) stepping the scene.
  int parts() const { return static_cast<int>(parts_.size()); }
  Multibody& part(int p) { return *parts_[static_cast<std::size_t>(p)].multibody; }

  // --- Multibody's interface, scene-wide (multibody.hpp says what each does) -----------------
  int body_count() const { return body_count_; }
  const std::vector<AxisInfo>& axes() const { return axes_; }
  const std::vector<std::string>& warnings() const { return warnings_; }
  Wrench* applied_wrenches();
  double* applied_axis_forces();
  double* applied_axis_friction();
  AxisDrive* axis_drives();
  std::int32_t* axis_drive_count();
  std::int32_t axis_drive_capacity() const;
  const double* drive_force_applied() const;
  void request_joint_reactions();
  void choose_dynamics(DynamicsChoice choice);
  void set_dynamics_agreement(double relative);
  const char* dynamics_name() const;
  DynamicsCheck dynamics_check() const;
  const Wrench* joint_reactions() const;
  bool joint_is_loop(int joint) const;
  Wrench* use_contact_wrenches();
  /// Multibody's contact friction points, scene-wide (with several parts, each part solves the
  /// points on its own bodies; with one, the part's own list).
  void reserve_contact_friction(std::int32_t points);
  FrictionPoints* contact_friction();
  bool solves_contact_friction(int body) const;
  std::vector<double> apparent_mass_kg() const;
  std::vector<Multibody::Mobility> contact_mobility() const;
  void reset();
  double time_s() const { return parts_[0].multibody->time_s(); }
  int substeps() const { return parts_[0].multibody->substeps(); }
  double substep_s() const { return parts_[0].multibody->substep_s(); }
  void current_bodies(const Pose*& poses, const Twist*& twists);
  int first_non_finite_body() const;
  const std::string& body_name(int body) const { return parts_[0].multibody->body_name(body); }
  void read(Pose* poses, Twist* twists, double* axis_position, double* axis_velocity) const;
  /// The arrays read() will fill (the kernel's own): with several parts, each part writes its
  /// bodies and axes there itself at the end of a tick, on its own thread, and read() of the
  /// same arrays then only sets the world's entry.
  void bind_read(Pose* poses, Twist* twists, double* axis_position, double* axis_velocity);
  double kinetic_energy_J() const;
  double potential_energy_J() const;
  /// One part: Multibody's segments. Several: each part's, named `multibody/part<p>/…`
  /// (a snapshot restores only into a simulation with as many parts).
  void declare_state(common::StateLayout& layout);
  void restored();
  bool place_free_body(int body, const Pose& pose);
  bool set_loose_mass(int body, double mass_kg, const Vec3& com_m, const Mat3& inertia,
                      bool gravity, bool fixed = false);
  bool set_jointed_mass(int body, double mass_kg, const Vec3& com_m, const Mat3& inertia);
  /// Whether kernel body `body` is integrated as a loose body (it has no joint).
  bool is_loose(int body) const {
    return body > 0 && body < static_cast<int>(loose_.size()) &&
           loose_[static_cast<std::size_t>(body)] != 0;
  }
  bool move_body(int body, const Pose& pose);
  bool set_body_velocity(int body, const Twist& twist);
  bool set_axis_state(std::size_t axis, double position, double velocity);

  /// What the kernel runs in each part at the tick's edges, on the part's thread, when its
  /// components are stepped in the parts (sim/component_parts.hpp).
  class TickHooks {
   public:
    /// Before the tick's first substep takes the loads: the part's components, which write
    /// its slices of the scene-wide load arrays and its own drive slots (part_drives()).
    /// `calling_thread` as for PartStages; `ahead`: the tick's distance from the kernel's
    /// current one (run_ticks(); 0 otherwise).
    virtual void start(int part, bool calling_thread, int ahead) = 0;
    /// After the last substep's read-out.
    virtual void end(int part) = 0;

   protected:
    ~TickHooks() = default;
  };

  /// Substep `substep` of the tick for every part at once (one part: on the calling thread,
  /// the same code): the part's loads
  /// taken from the scene-wide arrays (on the first substep) and the contact wrenches (unless
  /// `contact_in_parts`: `stages` then write the part's own, Multibody::use_contact_wrenches),
  /// then `stages`, then its bodies (and after the last substep its axes, drives and reactions)
  /// written back. Exceptions: the lowest part's; a non-finite state names the first body in
  /// kernel order, as the serial run does.
  /// With `hooks`: their `start` first on substep 0 unless `start_ran` (run_tick_starts()
  /// ran them already), their `end` last on the last substep.
  void run_substep(int substep, PartStages& stages, bool contact_in_parts = false,
                   TickHooks* hooks = nullptr, bool start_ran = false);
  /// Only the hooks' `start` of every part, at once (for a tick whose contact must be
  /// computed whole, between them and the substep).
  void run_tick_starts(TickHooks& hooks);
  /// Runs ahead (sim/run_ahead.cpp): `ticks` whole ticks of every part at once, each part on
  /// its own thread without waiting for the others between ticks: at each tick the hooks'
  /// `start`, then per substep its loads and `stages` (its contact computed in the part), then
  /// the read-out and the hooks' `end`. A part whose `stages` return false stops there, and so
  /// do the others at their next tick: returns false, and the state is then only good for a
  /// restore. Exceptions: as run_substep().
  bool run_ticks(int ticks, PartStages& stages, TickHooks& hooks);

  /// A part's kernel bodies (ascending) and its axes (scene-wide indices, the part's order).
  const std::vector<int>& part_bodies(int p) const {
    return parts_[static_cast<std::size_t>(p)].plan.bodies;
  }
  const std::vector<int>& part_axes(int p) const {
    return parts_[static_cast<std::size_t>(p)].plan.global_axis;
  }
  /// The part that steps a kernel body (0 for the world), a scene-wide axis, a scene joint.
  int part_of_body(int body) const { return owner(body); }
  int part_of_axis(int axis) const;
  int part_of_joint(int joint) const;
  /// Drives staged by part (the components' drives when they run in the parts): part `p`'s
  /// slots, axes scene-wide, taken at the tick's start instead of the scene-wide axis_drives().
  /// Each part has the scene's capacity (axis_drive_capacity()).
  void stage_drives_by_part(bool on);
  AxisDrive* part_drives(int p) { return parts_[static_cast<std::size_t>(p)].drives.data(); }
  std::int32_t* part_drive_count(int p) { return &parts_[static_cast<std::size_t>(p)].drive_count; }

  /// Lets `forces` (contact) be computed part by part (SubstepForces::split) with this
  /// object's parts; true if it accepted.
  bool split_forces(SubstepForces& forces);
  /// The forces split_forces() accepted, else null.
  SubstepForces* split_forces() const { return split_forces_; }
  /// Whether the state is the one the last run_substep() left (no body placed, moved or
  /// given a velocity since, no reset or restore): what the parts computed from it holds.
  bool untouched_since_substep() const { return untouched_; }

 private:
  struct alignas(64) Part {  // a cache line apart: each is written by its own thread
    std::unique_ptr<Multibody> multibody;
    PartPlan plan;
    bool is_scene = false;               // the only part: its arrays are the scene's (SceneArrays)
    Wrench* contact_wrenches = nullptr;  // the part's, when contact is used
    std::vector<AxisDrive> drives;       // staged by part (stage_drives_by_part)
    std::int32_t drive_count = 0;
    // Scratch for read(): the part's view of every body and of its axes (read() is const).
    mutable std::vector<Pose> poses;
    mutable std::vector<Twist> twists;
    mutable std::vector<double> axis_position, axis_velocity;
  };
  /// The pool's three kinds of run: each part's tick start, substep, stretch of ticks.
  struct StartsJob final : WorkerPool::Job {
    MultibodyIslands* self = nullptr;
    void run_task(int part, int thread) override;
  };
  struct SubstepJob final : WorkerPool::Job {
    MultibodyIslands* self = nullptr;
    void run_task(int part, int thread) override;
  };
  struct TicksJob final : WorkerPool::Job {
    MultibodyIslands* self = nullptr;
    void run_task(int part, int thread) override;
  };
  /// Part `p`'s substep on `thread` (run_substep(), run_ticks()): its loads, the stages, its
  /// bodies out, and on the tick's last substep its read-out and the hooks' `end`. Returns
  /// what the stages returned.
  bool step_part(Part& part, int p, int thread, int substep);
  /// The part's slice of the scene-wide loads (the tick's on its first substep, the contact
  /// wrenches on every one).
  void load_part(Part& part, int substep);
  /// The part's bodies into poses_/twists_.
  void copy_bodies(Part& part);
  /// After the tick's last substep: the part's read-out, drives applied and reactions.
  void publish_tick(Part& part);
  struct ReadTargets {
    Pose* poses = nullptr;
    Twist* twists = nullptr;
    double *axis_position = nullptr, *axis_velocity = nullptr;
  };
  /// The part's bodies and axes from its read scratch into `to`.
  void copy_read(const Part& part, const ReadTargets& to) const;
  /// Every part's joint reactions (or one part's) into the scene-wide reactions_.
  void gather_reactions();
  void gather_reactions(const Part& part);
  int owner(int body) const;

  int body_count_ = 0;
  std::vector<AxisInfo> axes_;
  std::vector<std::string> warnings_;
  std::vector<Part> parts_;
  std::vector<int> part_of_body_;   // kernel body -> part
  std::vector<int> part_of_joint_;  // scene joint -> part
  std::vector<int> part_of_axis_;   // scene-wide axis -> part
  std::vector<int> local_axis_;     // scene-wide axis -> its index in its part
  std::vector<char> loose_;         // kernel body -> integrated by LooseBodies
  std::unique_ptr<WorkerPool> pool_;
  /// The scene-wide arrays the kernel reads and writes: with one part that part's own, so that
  /// the copies between a part and the scene (load_part, copy_bodies, publish_tick,
  /// gather_reactions) vanish; with several, the storage below.
  struct SceneArrays {
    Wrench* wrenches;
    double* axis_forces;
    double* axis_friction;
    AxisDrive* drives;
    std::int32_t* drive_count;
    std::int32_t drive_capacity;
    const double* drive_applied;
    const Wrench* reactions;
    Wrench* contact_wrenches;  // set when contact is used (use_contact_wrenches)
    const Pose* poses;         // the current bodies (current_bodies)
    const Twist* twists;
  };
  SceneArrays scene_{};
  // The scene-wide arrays' storage when several parts share them.
  std::vector<Wrench> wrenches_, contact_wrenches_, reactions_;
  std::vector<FrictionPoint> friction_storage_;  // several parts: the scene-wide friction points
  FrictionPoints friction_;
  std::vector<double> axis_forces_, axis_friction_, drive_applied_;
  std::vector<AxisDrive> drives_;
  std::int32_t drive_count_ = 0;
  std::vector<Pose> poses_;
  std::vector<Twist> twists_;
  std::vector<double> axis_position_, axis_velocity_;
  bool contact_used_ = false;
  SubstepForces* split_forces_ = nullptr;
  bool untouched_ = false;
  bool contact_in_parts_ = false;  // the running substep's
  bool reactions_wanted_ = false;
  bool bodies_fresh_ = false;        // poses_/twists_ hold the current state (for contact)
  mutable bool read_fresh_ = false;  // the parts' read scratch holds it too (for read())
  ReadTargets bound_;                // bind_read()
  bool published_ = false;           // the parts wrote the current state into bound_
  // The running substep (run_substep).
  int substep_ = 0;
  PartStages* stages_ = nullptr;
  TickHooks* hooks_ = nullptr;
  StartsJob starts_job_;
  SubstepJob substep_job_;
  TicksJob ticks_job_;
  bool run_starts_ = false;  // the substep runs the hooks' start
  // The running run_ticks(): how many, and whether a part stopped (read by every part).
  int ahead_ticks_ = 0;
  std::atomic<bool> ahead_stopped_{false};
  bool drives_by_part_ = false;
  bool fast_path_possible_ = true;  // every part's trees can take it (the constructor)
};

}  // namespace s2sim::model
