// The multibody as parts stepped in parallel (multibody_islands.hpp). No Simbody here: the parts
// are Multibody objects seen through their public interface.
#include "model/multibody_islands.hpp"

#include "common/assert.hpp"

#include <s2sim/error.hpp>

#include <algorithm>
#include <string>

namespace s2sim::model {

MultibodyIslands::MultibodyIslands(const scene::Scene& scene, const Topology& topology,
                                   const std::vector<double>& axis_inertia, double tick_s,
                                   int substeps, int threads)
    : body_count_(static_cast<int>(scene.bodies.size()) + 1), axes_(topology.axes) {
  std::vector<PartPlan> plans = plan_parts(scene, topology, axis_inertia, threads);
  parts_.resize(plans.size());
  // The serial run's drive slots (four per axis of the scene), each part room for all of
  // them: however the components spread their drives, a part integrates implicitly every drive
  // the serial run would, and the SDK applies the same ones explicitly past that.
  const auto scene_drive_slots = static_cast<std::int32_t>(4 * topology.axes.size());
  for (std::size_t p = 0; p < plans.size(); ++p) {
    Part& part = parts_[p];
    part.plan = std::move(plans[p]);
    part.multibody =
        std::make_unique<Multibody>(scene, part.plan.topology, part.plan.axis_inertia, tick_s,
                                    substeps, plans.size() > 1 ? scene_drive_slots : 0);
    for (const auto& w : part.multibody->warnings())
      warnings_.push_back(w);
  }
  const auto bodies = static_cast<std::size_t>(body_count_);
  const std::size_t axes = axes_.size(), joints = scene.joints.size();
  part_of_body_.assign(bodies, 0);
  part_of_joint_.assign(joints, 0);
  part_of_axis_.assign(axes, 0);
  local_axis_.assign(axes, 0);
  for (std::size_t p = 0; p < parts_.size(); ++p) {
    Part& part = parts_[p];
    part.is_scene = parts_.size() == 1;
    for (int b : part.plan.bodies)
      part_of_body_[static_cast<std::size_t>(b)] = static_cast<int>(p);
    for (int j : part.plan.joints)
      part_of_joint_[static_cast<std::size_t>(j)] = static_cast<int>(p);
    for (std::size_t a = 0; a < part.plan.global_axis.size(); ++a) {
      const auto g = static_cast<std::size_t>(part.plan.global_axis[a]);
      part_of_axis_[g] = static_cast<int>(p);
      local_axis_[g] = static_cast<int>(a);
    }
    part.poses.assign(bodies, Pose{});
    part.twists.assign(bodies, Twist{});
    part.axis_position.assign(part.plan.global_axis.size(), 0.0);
    part.axis_velocity.assign(part.plan.global_axis.size(), 0.0);
  }
  loose_.assign(bodies, 0);
  for (int b : topology.loose)
    loose_[static_cast<std::size_t>(b) + 1] = 1;
  if (parts_.front().is_scene) {
    // The only part's arrays are the scene's: its bodies are numbered as the kernel's and
    // its axes are the scene's in order (plan_parts), so nothing is copied between them.
    Multibody& mb = *parts_.front().multibody;
    scene_ = {mb.applied_wrenches(),
              mb.applied_axis_forces(),
              mb.applied_axis_friction(),
              mb.axis_drives(),
              mb.axis_drive_count(),
              mb.axis_drive_capacity(),
              mb.drive_force_applied(),
              mb.joint_reactions(),
              nullptr,
              nullptr,
              nullptr};
    mb.current_bodies(scene_.poses, scene_.twists);
  } else {
    wrenches_.assign(bodies, Wrench{});
    contact_wrenches_.assign(bodies, Wrench{});
    reactions_.assign(joints, Wrench{});
    axis_forces_.assign(axes, 0.0);
    axis_friction_.assign(axes, 0.0);
    drive_applied_.assign(axes, 0.0);
    drives_.assign(static_cast<std::size_t>(scene_drive_slots), AxisDrive{});
    for (const Part& part : parts_)
      S2SIM_ASSERT(part.multibody->axis_drive_capacity() == scene_drive_slots,
                   "a part without room for every drive of the scene");
    poses_.assign(bodies, Pose{});
    twists_.assign(bodies, Twist{});
    scene_ = {wrenches_.data(),      axis_forces_.data(), axis_friction_.data(),
              drives_.data(),        &drive_count_,       scene_drive_slots,
              drive_applied_.data(), reactions_.data(),   contact_wrenches_.data(),
              poses_.data(),         twists_.data()};
    gather_reactions();
  }
  // One system takes the fast path only if every tree of it can (one whose check at load
  // fails: Simbody for all), and the two compute the same dynamics only to rounding. The parts do
  // as the whole scene would, or a part without that tree would take the fast path's last
  // bits where the serial run takes Simbody's (found by the differential fuzzing).
  for (const Part& part : parts_)
    fast_path_possible_ = fast_path_possible_ && !part.multibody->needs_simbody_dynamics();
  if (!fast_path_possible_)
    for (Part& part : parts_)
      part.multibody->choose_dynamics(DynamicsChoice::simbody);
  pool_ = std::make_unique<WorkerPool>(parts(), parts());
}

MultibodyIslands::~MultibodyIslands() = default;

Wrench* MultibodyIslands::applied_wrenches() {
  return scene_.wrenches;
}
double* MultibodyIslands::applied_axis_forces() {
  return scene_.axis_forces;
}
double* MultibodyIslands::applied_axis_friction() {
  return scene_.axis_friction;
}
AxisDrive* MultibodyIslands::axis_drives() {
  return scene_.drives;
}
std::int32_t* MultibodyIslands::axis_drive_count() {
  return scene_.drive_count;
}
std::int32_t MultibodyIslands::axis_drive_capacity() const {
  return scene_.drive_capacity;
}
const double* MultibodyIslands::drive_force_applied() const {
  return scene_.drive_applied;
}
void MultibodyIslands::request_joint_reactions() {
  for (auto& part : parts_)
    part.multibody->request_joint_reactions();
  reactions_wanted_ = true;
}
void MultibodyIslands::choose_dynamics(DynamicsChoice choice) {
  for (auto& part : parts_)
    part.multibody->choose_dynamics(fast_path_possible_ ? choice : DynamicsChoice::simbody);
  bodies_fresh_ = read_fresh_ = untouched_ = published_ = false;
}
void MultibodyIslands::set_dynamics_agreement(double relative) {
  for (auto& part : parts_)
    part.multibody->set_dynamics_agreement(relative);
}
const char* MultibodyIslands::dynamics_name() const {
  return parts_[0].multibody->dynamics_name();  // the parts choose alike (the constructor)
}
DynamicsCheck MultibodyIslands::dynamics_check() const {
  DynamicsCheck all;
  all.agreement = parts_[0].multibody->dynamics_check().agreement;  // the parts share it
  for (const auto& part : parts_) {
    const DynamicsCheck check = part.multibody->dynamics_check();
    all.compared += check.compared;
    all.judged_on_loops += check.judged_on_loops;
    all.worst_loop_error = std::max(all.worst_loop_error, check.worst_loop_error);
    all.worst_reference_loop_error =
        std::max(all.worst_reference_loop_error, check.worst_reference_loop_error);
    if (check.worst_relative > all.worst_relative) {
      all.worst_relative = check.worst_relative;
      all.worst_time_s = check.worst_time_s;
    }
  }
  return all;
}
const Wrench* MultibodyIslands::joint_reactions() const {
  return scene_.reactions;
}
bool MultibodyIslands::joint_is_loop(int joint) const {
  return parts_[static_cast<std::size_t>(part_of_joint_.at(static_cast<std::size_t>(joint)))]
      .multibody->joint_is_loop(joint);
}
Wrench* MultibodyIslands::use_contact_wrenches() {
  if (!contact_used_)
    for (auto& part : parts_) {
      part.contact_wrenches = part.multibody->use_contact_wrenches();
      if (part.is_scene) scene_.contact_wrenches = part.contact_wrenches;
    }
  contact_used_ = true;
  return scene_.contact_wrenches;
}

void MultibodyIslands::reserve_contact_friction(std::int32_t points) {
  for (auto& part : parts_)
    part.multibody->reserve_contact_friction(points);
  friction_storage_.assign(static_cast<std::size_t>(std::max(0, points)), FrictionPoint{});
  friction_.points = friction_storage_.data();
  friction_.count = 0;
  // A part solves at most its own list's room.
  friction_.capacity = points;
  for (const auto& part : parts_)
    friction_.capacity = std::min(friction_.capacity, part.multibody->contact_friction()->capacity);
}

FrictionPoints* MultibodyIslands::contact_friction() {
  if (parts_.size() == 1) return parts_[0].multibody->contact_friction();
  return &friction_;
}

bool MultibodyIslands::solves_contact_friction(int body) const {
  if (body <= 0 || static_cast<std::size_t>(body) >= part_of_body_.size()) return false;
  const int p = part_of_body_[static_cast<std::size_t>(body)];
  return p >= 0 && parts_[static_cast<std::size_t>(p)].multibody->solves_contact_friction(body);
}

std::vector<double> MultibodyIslands::apparent_mass_kg() const {
  std::vector<double> out(static_cast<std::size_t>(body_count_), 0.0);
  for (const auto& part : parts_) {
    const std::vector<double> mass = part.multibody->apparent_mass_kg();
    for (int b : part.plan.bodies)
      out[static_cast<std::size_t>(b)] = mass[static_cast<std::size_t>(b)];
  }
  return out;
}

std::vector<Multibody::Mobility> MultibodyIslands::contact_mobility() const {
  std::vector<Multibody::Mobility> out(static_cast<std::size_t>(body_count_));
  for (const auto& part : parts_) {
    const auto mobility = part.multibody->contact_mobility();
    for (int b : part.plan.bodies)
      out[static_cast<std::size_t>(b)] = mobility[static_cast<std::size_t>(b)];
  }
  return out;
}

void MultibodyIslands::reset() {
  for (auto& part : parts_)
    part.multibody->reset();
  drive_count_ = 0;
  std::fill(drive_applied_.begin(), drive_applied_.end(), 0.0);
  gather_reactions();
  bodies_fresh_ = read_fresh_ = untouched_ = published_ = false;
}

void MultibodyIslands::gather_reactions() {
  for (const auto& part : parts_)
    gather_reactions(part);
}

void MultibodyIslands::gather_reactions(const Part& part) {
  if (part.is_scene) return;  // the scene's reactions are the part's
  const Wrench* reactions = part.multibody->joint_reactions();
  for (int j : part.plan.joints)
    reactions_[static_cast<std::size_t>(j)] = reactions[j];
}

void MultibodyIslands::current_bodies(const Pose*& poses, const Twist*& twists) {
  if (!bodies_fresh_) {
    for (auto& part : parts_)
      copy_bodies(part);
    bodies_fresh_ = true;
  }
  poses = scene_.poses;
  twists = scene_.twists;
}

void MultibodyIslands::copy_bodies(Part& part) {
  const Pose* poses = nullptr;
  const Twist* twists = nullptr;
  part.multibody->current_bodies(poses, twists);
  if (part.is_scene) {  // the part's bodies are the scene's: hand its arrays out
    scene_.poses = poses;
    scene_.twists = twists;
    return;
  }
  for (int b : part.plan.bodies) {
    poses_[static_cast<std::size_t>(b)] = poses[b];
    twists_[static_cast<std::size_t>(b)] = twists[b];
  }
}

int MultibodyIslands::first_non_finite_body() const {
  // As one system would say: the first mobilized body in kernel order, else a loose one.
  int mobilized = -1, loose = -1;
  for (const auto& part : parts_) {
    const int b = part.multibody->first_non_finite_body();
    if (b <= 0) continue;
    int& first = loose_[static_cast<std::size_t>(b)] ? loose : mobilized;
    if (first < 0 || b < first) first = b;
  }
  return mobilized > 0 ? mobilized : loose;
}

void MultibodyIslands::read(Pose* poses, Twist* twists, double* axis_position,
                            double* axis_velocity) const {
  if (!read_fresh_) {
    for (const auto& part : parts_)
      part.multibody->read(part.poses.data(), part.twists.data(), part.axis_position.data(),
                           part.axis_velocity.data());
    read_fresh_ = true;
  }
  poses[0] = Pose{};
  twists[0] = Twist{};
  // The parts wrote the bound arrays themselves at the end of the tick (publish_tick).
  if (published_ && poses == bound_.poses && twists == bound_.twists &&
      axis_position == bound_.axis_position && axis_velocity == bound_.axis_velocity)
    return;
  const ReadTargets targets{poses, twists, axis_position, axis_velocity};
  for (const auto& part : parts_)
    copy_read(part, targets);
}

void MultibodyIslands::copy_read(const Part& part, const ReadTargets& to) const {
  for (int b : part.plan.bodies) {
    to.poses[b] = part.poses[static_cast<std::size_t>(b)];
    to.twists[b] = part.twists[static_cast<std::size_t>(b)];
  }
  for (std::size_t a = 0; a < part.plan.global_axis.size(); ++a) {
    to.axis_position[part.plan.global_axis[a]] = part.axis_position[a];
    to.axis_velocity[part.plan.global_axis[a]] = part.axis_velocity[a];
  }
}

void MultibodyIslands::bind_read(Pose* poses, Twist* twists, double* axis_position,
                                 double* axis_velocity) {
  bound_ = {poses, twists, axis_position, axis_velocity};
  published_ = false;
}

double MultibodyIslands::kinetic_energy_J() const {
  double energy = 0;
  for (const auto& part : parts_)
    energy += part.multibody->kinetic_energy_J();
  return energy;
}

double MultibodyIslands::potential_energy_J() const {
  double energy = 0;
  for (const auto& part : parts_)
    energy += part.multibody->potential_energy_J();
  return energy;
}

void MultibodyIslands::declare_state(common::StateLayout& layout) {
  for (std::size_t p = 0; p < parts_.size(); ++p)
    parts_[p].multibody->declare_state(
        layout, parts_[p].is_scene ? "multibody" : "multibody/part" + std::to_string(p));
}

void MultibodyIslands::restored() {
  for (auto& part : parts_)
    part.multibody->restored();
  gather_reactions();
  bodies_fresh_ = read_fresh_ = untouched_ = published_ = false;
}

int MultibodyIslands::owner(int body) const {
  return body > 0 && body < body_count_ ? part_of_body_[static_cast<std::size_t>(body)] : 0;
}

bool MultibodyIslands::place_free_body(int body, const Pose& pose) {
  bodies_fresh_ = read_fresh_ = untouched_ = published_ = false;
  return parts_[static_cast<std::size_t>(owner(body))].multibody->place_free_body(body, pose);
}
bool MultibodyIslands::set_loose_mass(int body, double mass_kg, const Vec3& com_m,
                                      const Mat3& inertia, bool gravity, bool fixed) {
  bodies_fresh_ = read_fresh_ = untouched_ = published_ = false;
  return parts_[static_cast<std::size_t>(owner(body))].multibody->set_loose_mass(
      body, mass_kg, com_m, inertia, gravity, fixed);
}
bool MultibodyIslands::set_jointed_mass(int body, double mass_kg, const Vec3& com_m,
                                        const Mat3& inertia) {
  bodies_fresh_ = read_fresh_ = untouched_ = published_ = false;
  return parts_[static_cast<std::size_t>(owner(body))].multibody->set_jointed_mass(body, mass_kg,
                                                                                   com_m, inertia);
}
bool MultibodyIslands::move_body(int body, const Pose& pose) {
  bodies_fresh_ = read_fresh_ = untouched_ = published_ = false;
  return parts_[static_cast<std::size_t>(owner(body))].multibody->move_body(body, pose);
}
bool MultibodyIslands::set_body_velocity(int body, const Twist& twist) {
  bodies_fresh_ = read_fresh_ = untouched_ = published_ = false;
  return parts_[static_cast<std::size_t>(owner(body))].multibody->set_body_velocity(body, twist);
}
bool MultibodyIslands::set_axis_state(std::size_t axis, double position, double velocity) {
  if (axis >= part_of_axis_.size()) return false;
  bodies_fresh_ = read_fresh_ = untouched_ = published_ = false;
  return parts_[static_cast<std::size_t>(part_of_axis_[axis])].multibody->set_axis_state(
      static_cast<std::size_t>(local_axis_[axis]), position, velocity);
}

// --- The parallel substep ----------------------------------------------------------------------

bool MultibodyIslands::split_forces(SubstepForces& forces) {
  if (!forces.split(part_of_body_, parts())) return false;
  split_forces_ = &forces;
  return true;
}

int MultibodyIslands::part_of_axis(int axis) const {
  return part_of_axis_.at(static_cast<std::size_t>(axis));
}
int MultibodyIslands::part_of_joint(int joint) const {
  return part_of_joint_.at(static_cast<std::size_t>(joint));
}

void MultibodyIslands::stage_drives_by_part(bool on) {
  S2SIM_ASSERT(!on || !parts_.front().is_scene, "drives staged by part with one part");
  drives_by_part_ = on;
  for (Part& part : parts_) {
    part.drives.assign(drives_by_part_ ? drives_.size() : 0, AxisDrive{});
    part.drive_count = 0;
  }
}

void MultibodyIslands::run_tick_starts(TickHooks& hooks) {
  hooks_ = &hooks;
  starts_job_.self = this;
  pool_->run(starts_job_, parts());
}

void MultibodyIslands::StartsJob::run_task(int p, int thread) {
  self->hooks_->start(p, thread == 0, 0);
}

void MultibodyIslands::run_substep(int substep, PartStages& stages, bool contact_in_parts,
                                   TickHooks* hooks, bool start_ran) {
  substep_ = substep;
  stages_ = &stages;
  contact_in_parts_ = contact_in_parts;
  hooks_ = hooks;
  run_starts_ = hooks && substep == 0 && !start_ran;
  bodies_fresh_ = read_fresh_ = untouched_ = published_ = false;
  try {
    substep_job_.self = this;
    pool_->run(substep_job_, parts());
  } catch (const Error& e) {
    // A part's finish found its state non-finite: name the first body of the whole scene.
    const int body = e.kind() == ErrorKind::runtime ? first_non_finite_body() : -1;
    if (body <= 0) throw;
    throw Error(ErrorKind::runtime,
                "the simulation state became non-finite at t = " + std::to_string(time_s()) +
                    " s, first at body " + body_name(body));
  }
  bodies_fresh_ = contact_used_ && split_forces_ == nullptr;
  untouched_ = true;
  read_fresh_ = substep == substeps() - 1;
  published_ = read_fresh_ && bound_.poses;
}

void MultibodyIslands::SubstepJob::run_task(int p, int thread) {
  MultibodyIslands& me = *self;
  Part& part = me.parts_[static_cast<std::size_t>(p)];
  if (me.run_starts_) me.hooks_->start(p, thread == 0, 0);
  me.step_part(part, p, thread, me.substep_);
}

bool MultibodyIslands::step_part(Part& part, int p, int thread, int substep) {
  load_part(part, substep);
  const bool inside = stages_->run(p, *part.multibody, thread == 0, substep);
  if (!part.is_scene && contact_used_ && !contact_in_parts_) {  // the forces solved, back
    const FrictionPoints& own = *part.multibody->contact_friction();
    for (std::int32_t i = 0; i < own.count; ++i)
      friction_.points[own.points[i].scene_index].force_N = own.points[i].force_N;
  }
  // For the next substep's contact (its realize runs here, in parallel); split forces read
  // each part's own (placed by the stages' callback), and current_bodies() copies on demand.
  if (contact_used_ && !split_forces_) copy_bodies(part);
  if (substep == substeps() - 1) {
    publish_tick(part);
    if (hooks_) hooks_->end(p);
  }
  return inside;
}

bool MultibodyIslands::run_ticks(int ticks, PartStages& stages, TickHooks& hooks) {
  stages_ = &stages;
  hooks_ = &hooks;
  contact_in_parts_ = true;
  ahead_ticks_ = ticks;
  ahead_stopped_.store(false, std::memory_order_relaxed);
  bodies_fresh_ = read_fresh_ = untouched_ = published_ = false;
  ticks_job_.self = this;
  pool_->run(ticks_job_, parts());
  if (ahead_stopped_.load(std::memory_order_relaxed)) return false;
  untouched_ = true;
  read_fresh_ = true;
  published_ = bound_.poses != nullptr;
  return true;
}

void MultibodyIslands::TicksJob::run_task(int p, int thread) {
  MultibodyIslands& me = *self;
  Part& part = me.parts_[static_cast<std::size_t>(p)];
  try {
    for (int k = 0; k < me.ahead_ticks_; ++k) {
      // Another part left its fence: what follows would be thrown away.
      if (me.ahead_stopped_.load(std::memory_order_relaxed)) return;
      me.hooks_->start(p, thread == 0, k);
      for (int substep = 0; substep < me.substeps(); ++substep) {
        if (!me.step_part(part, p, thread, substep)) {
          me.ahead_stopped_.store(true, std::memory_order_relaxed);
          return;
        }
      }
    }
  } catch (...) {
    me.ahead_stopped_.store(true, std::memory_order_relaxed);
    throw;
  }
}

void MultibodyIslands::load_part(Part& part, int substep) {
  if (part.is_scene) return;  // the part's loads are the scene's
  Multibody& mb = *part.multibody;
  if (substep == 0) {  // the tick's loads, held over its substeps
    Wrench* wrenches = mb.applied_wrenches();
    for (int b : part.plan.bodies)
      wrenches[b] = wrenches_[static_cast<std::size_t>(b)];
    double* forces = mb.applied_axis_forces();
    double* friction = mb.applied_axis_friction();
    for (std::size_t a = 0; a < part.plan.global_axis.size(); ++a) {
      forces[a] = axis_forces_[static_cast<std::size_t>(part.plan.global_axis[a])];
      friction[a] = axis_friction_[static_cast<std::size_t>(part.plan.global_axis[a])];
    }
    // The drives on the part's axes, in the components' order: the scene-wide list's, or
    // the part's own when the part's components staged them there.
    const int p = static_cast<int>(&part - parts_.data());
    const AxisDrive* staged = drives_by_part_ ? part.drives.data() : drives_.data();
    const std::int32_t staged_count = drives_by_part_ ? part.drive_count : drive_count_;
    AxisDrive* drives = mb.axis_drives();
    std::int32_t count = 0;
    for (std::int32_t d = 0; d < staged_count; ++d) {
      const auto g = static_cast<std::size_t>(staged[d].axis);
      if (g >= part_of_axis_.size() || part_of_axis_[g] != p) continue;
      AxisDrive drive = staged[d];
      drive.axis = local_axis_[g];
      drives[count++] = drive;  // room: a part has the scene's slots (the constructor)
    }
    *mb.axis_drive_count() = count;
  }
  if (contact_used_ && !contact_in_parts_) {
    for (int b : part.plan.bodies)
      part.contact_wrenches[b] = contact_wrenches_[static_cast<std::size_t>(b)];
    // The scene's friction points on the part's bodies, each remembering its entry.
    FrictionPoints& own = *mb.contact_friction();
    own.count = 0;
    const int p = static_cast<int>(&part - parts_.data());
    for (std::int32_t i = 0; i < friction_.count; ++i) {
      const FrictionPoint& point = friction_.points[i];
      if (part_of_body_[static_cast<std::size_t>(point.body)] != p) continue;
      own.points[own.count] = point;
      own.points[own.count++].scene_index = i;
    }
  }
}

void MultibodyIslands::publish_tick(Part& part) {
  Multibody& mb = *part.multibody;
  mb.read(part.poses.data(), part.twists.data(), part.axis_position.data(),
          part.axis_velocity.data());
  if (bound_.poses) copy_read(part, bound_);  // here, on the part's thread
  if (part.is_scene) return;                  // its drives and reactions are the scene's
  const double* applied = mb.drive_force_applied();
  for (std::size_t a = 0; a < part.plan.global_axis.size(); ++a)
    drive_applied_[static_cast<std::size_t>(part.plan.global_axis[a])] = applied[a];
  if (reactions_wanted_) gather_reactions(part);
}

}  // namespace s2sim::model
