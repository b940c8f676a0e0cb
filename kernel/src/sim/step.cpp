// What happens in a tick, and in which order (docs/architecture.md, "The tick"). Read
// Simulation::Impl::step_once() below top to bottom:
//
//   1. scheduled stages   sense → control → motor control → actuate
//                         (each component whose period is due; they read the state of the
//                         tick's start and write loads, inputs and published signals)
//   2. physics, per substep, part by part (one part unless --threads)
//                         collide → prepare axes → accelerations → kick → axes → drift
//                         → project
//   3. finish             the multibody's end of tick: drives' means, bodies read, finite check
//   4. read out           the kernel's poses, twists and axes, the components' view refreshed
//
// A motor's torque is computed in `actuate` (the dc_motor component), contact forces in
// `collide` (contact::ContactWorld), sensor readings in `sense` of the next tick, from the
// state this tick ends with.
#include "sim/step.hpp"
#include "sim/names.hpp"
#include "sim/running_component.hpp"

#include "sim/simulation_impl.hpp"

#include <algorithm>
#include <cmath>
#include <new>
#include <string>

namespace s2sim {
namespace sim {

const char* stage_name(PipelineStage stage) {
  static constexpr const char* kNames[] = {
      "sense", "control", "motor control", "actuate", "collide", "prepare axes", "accelerations",
      "kick",  "axes",    "drift",         "project", "finish",  "read out"};
  static_assert(std::size(kNames) == StageProfile::kStages);
  return kNames[static_cast<std::size_t>(stage)];
}

namespace {

/// Contact at the substep's poses, computed whole, written as the bodies' contact wrenches.
void collide(model::MultibodyIslands& mb, model::SubstepForces* contact, StageProfile* profile) {
  if (!contact) return;
  StageTimer timer(profile, PipelineStage::collide);
  const Pose* poses = nullptr;
  const Twist* twists = nullptr;
  mb.current_bodies(poses, twists);
  contact->compute(poses, twists, mb.substep_s(), mb.use_contact_wrenches(), mb.contact_friction());
}

}  // namespace

void multibody_substep(model::Multibody& mb, int substep, StageProfile* profile) {
  {
    StageTimer timer(profile, PipelineStage::prepare_axes);
    mb.prepare_axes();
  }
  {
    StageTimer timer(profile, PipelineStage::accelerations);
    mb.accelerations(substep == mb.substeps() - 1);
  }
  {
    StageTimer timer(profile, PipelineStage::kick);
    mb.kick();
  }
  {
    StageTimer timer(profile, PipelineStage::axes);
    mb.solve_axes();
  }
  {
    StageTimer timer(profile, PipelineStage::drift);
    mb.drift(substep);
  }
  {
    StageTimer timer(profile, PipelineStage::project);
    mb.project();
  }
  if (substep == mb.substeps() - 1) {
    StageTimer timer(profile, PipelineStage::finish);
    mb.finish_tick();
  }
}

namespace {

/// One part's substep (MultibodyIslands::run_substep, run_ticks): its contact when the substep
/// is split, its stages, and the placing of its shapes for the next substep's contact. Only
/// the parts the calling thread takes are profiled (StageProfile is not shared between
/// threads).
class PartStages final : public model::MultibodyIslands::PartStages {
 public:
  PartStages(StageProfile* profile, model::SubstepForces* contact, bool fenced)
      : profile_(profile), contact_(contact), fenced_(fenced) {}
  /// This substep's contact is computed in the parts.
  void set_contact_in_parts(bool in_parts) { contact_in_parts_ = in_parts; }

  /// Returns whether the part's shapes are still inside their fence (running ahead).
  bool run(int part, model::Multibody& mb, bool calling_thread, int substep) override {
    StageProfile* profile = calling_thread ? profile_ : nullptr;
    const Pose* poses = nullptr;
    const Twist* twists = nullptr;
    if (contact_in_parts_) {
      StageTimer timer(profile, PipelineStage::collide);
      mb.current_bodies(poses, twists);
      contact_->compute_part(part, poses, twists, mb.substep_s(), mb.use_contact_wrenches(),
                             mb.contact_friction());
    }
    multibody_substep(mb, substep, profile);
    if (contact_) {  // placed here, on the part's thread, for the next substep's contact
      StageTimer timer(profile, PipelineStage::collide);
      mb.current_bodies(poses, twists);
      contact_->place_part(part, poses, twists, mb.substep_s());
    }
    return !fenced_ || contact_->part_inside_fence(part);
  }

 private:
  StageProfile* profile_;
  model::SubstepForces* contact_;  // split part by part (MultibodyIslands::split_forces), or null
  bool fenced_;                    // running ahead: each part keeps to its fence
  bool contact_in_parts_ = false;
};

/// The calling thread's share of a substep's contact split part by part (the pairs, unless
/// each part finds its own): whether the parts compute the rest (false when two parts'
/// bodies touch or may within the step: the contact is then computed whole).
bool begin_contact_in_parts(model::MultibodyIslands& mb, model::SubstepForces& contact,
                            StageProfile* profile) {
  StageTimer timer(profile, PipelineStage::collide);
  const Pose* poses = nullptr;
  const Twist* twists = nullptr;
  const bool placed = mb.untouched_since_substep();  // the parts placed their shapes
  if (!placed) mb.current_bodies(poses, twists);
  return contact.begin_parts(placed, poses, twists, mb.substep_s());
}

/// Simbody refused a state that went non-finite inside the tick (a blow-up): say where.
[[noreturn]] void throw_diverged(const model::MultibodyIslands& mb, const std::exception& e) {
  const int body = mb.first_non_finite_body();
  throw Error(ErrorKind::runtime,
              "the simulation diverged at t = " + std::to_string(mb.time_s()) + " s" +
                  (body > 0 ? ", first at body " + mb.body_name(body) : std::string()) + " (" +
                  e.what() +
                  "); the scene may need a smaller step, more substeps or saner parameters");
}

std::uint64_t fnv1a(std::string_view s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : s) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

}  // namespace

void physics_tick(model::MultibodyIslands& mb, model::SubstepForces* contact, StageProfile* profile,
                  model::MultibodyIslands::TickHooks* hooks) {
  const bool split = contact && mb.split_forces() == contact;
  PartStages stages(profile, split ? contact : nullptr, false);
  try {
    for (int k = 0; k < mb.substeps(); ++k) {
      // Contact part by part in the parts where it can, else whole, here, after the parts'
      // components (a whole contact rewrites the contact list they read).
      const bool contact_in_parts = split && begin_contact_in_parts(mb, *contact, profile);
      const bool start_ran = !contact_in_parts && hooks && k == 0;
      if (start_ran) mb.run_tick_starts(*hooks);
      if (!contact_in_parts) collide(mb, contact, profile);
      stages.set_contact_in_parts(contact_in_parts);
      mb.run_substep(k, stages, contact_in_parts, hooks, start_ran);
      // The friction the axes' solve found, into the contact list.
      if (contact && !contact_in_parts) contact->end_substep();
      if (contact_in_parts) {
        StageTimer timer(profile, PipelineStage::collide);
        contact->end_parts();
      }
    }
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;  // out of memory, not a diverged state
  } catch (const std::exception& e) {
    throw_diverged(mb, e);
  }
}

bool fence_parts(model::MultibodyIslands& mb, model::SubstepForces* contact) {
  return contact && mb.split_forces() == contact && mb.untouched_since_substep() &&
         contact->fence_parts();
}

bool physics_ticks_ahead(model::MultibodyIslands& mb, model::SubstepForces& contact,
                         StageProfile* profile, model::MultibodyIslands::TickHooks& hooks,
                         int ticks) {
  PartStages stages(profile, &contact, true);
  stages.set_contact_in_parts(true);
  if (!mb.run_ticks(ticks, stages, hooks)) return false;
  contact.end_parts_ahead(static_cast<std::int64_t>(ticks) * mb.substeps());
  return true;
}

}  // namespace sim

void Simulation::Impl::step_once() {
  // The components: in the parts (each part's hooks' start), else the whole scene's here.
  const bool in_parts = !component_parts.parts.empty();
  if (in_parts) {
    multibody->applied_wrenches()[0] = Wrench{};  // the world's entry, which no part clears
  } else {
    run_component_group(component_parts.whole, true, 0);
  }
  try {
    sim::physics_tick(*multibody, contacts.get(), profile.get(), in_parts ? &part_hooks : nullptr);
  } catch (const Error& e) {
    // A divergence names its first body: add where that body last was, finite (the kernel's
    // poses and twists still hold the previous tick's).
    const int body = e.kind() == ErrorKind::runtime ? multibody->first_non_finite_body() : -1;
    if (body <= 0 || static_cast<std::size_t>(body) >= poses.size()) throw;
    const Pose& p = poses[static_cast<std::size_t>(body)];
    const Twist& v = twists[static_cast<std::size_t>(body)];
    auto vec = [](const Vec3& x) {
      return "(" + sim::exact_decimal(x.x) + ", " + sim::exact_decimal(x.y) + ", " +
             sim::exact_decimal(x.z) + ")";
    };
    throw Error(e.kind(), e.where(),
                e.message() + "; its last finite state, at t = " +
                    std::to_string(static_cast<double>(tick) * tick_s) + " s: position " +
                    vec(p.position) + " m, velocity " + vec(v.linear_m_s) +
                    " m/s, angular velocity " + vec(v.angular_rad_s) + " rad/s");
  } catch (const collision::TooManyPairs& too_many) {
    const auto& body = contacts->shapes().bodies();
    throw Error(ErrorKind::runtime,
                "at t = " + std::to_string(multibody->time_s()) + " s more than " +
                    std::to_string(too_many.limit) +
                    " pairs of collision shapes overlap (the limit: " + too_many.rule() +
                    "), "
                    "among them bodies " +
                    multibody->body_name(body[static_cast<std::size_t>(too_many.shape_a)]) +
                    " and " +
                    multibody->body_name(body[static_cast<std::size_t>(too_many.shape_b)]) +
                    ": bodies are placed into one another");
  }
  // What the axes carried over the tick (in the parts, each part's hooks' end).
  if (!in_parts) record_group_axis_loads(component_parts.whole);
  ++tick;
  sim::StageTimer timer(profile.get(), sim::PipelineStage::read_out);
  refresh();
}

bool Simulation::Impl::update_if_due(int c, sim::LocalView* local) {
  const sim::ComponentSlot& slot = components[static_cast<std::size_t>(c)];
  const std::int64_t since = (local ? local->view.tick : tick) - slot.phase_ticks;
  if (since < 0 || since % slot.period_ticks != 0) return false;
  if (local) local->component = c;
  StepContext ctx(local ? &local->view : &world, c, slot.period_ticks);
  try {  // free unless something is thrown
    const sim::RunningComponent running(slot.crash_label.c_str());
    slot.component->update(ctx);
  } catch (...) {
    sim::rethrow_from_component(slot, "update", ErrorKind::runtime);
  }
  return true;
}

namespace {
/// Within the reserve (one per body) a request does not allocate; a later one replaces.
template <class T>
void add_request(std::vector<std::pair<std::int32_t, T>>& list, std::int32_t body, const T& v) {
  for (auto& [b, p] : list)
    if (b == body) {
      p = v;
      return;
    }
  list.emplace_back(body, v);
}
Simulation::Impl& impl_of(const void* impl) {
  return *const_cast<Simulation::Impl*>(static_cast<const Simulation::Impl*>(impl));
}
}  // namespace

void Simulation::Impl::request_place(const void* impl, std::int32_t body, const Pose& pose) {
  add_request(impl_of(impl).pending_places, body, pose);
}
void Simulation::Impl::request_move(const void* impl, std::int32_t body, const Pose& pose) {
  add_request(impl_of(impl).pending_moves, body, pose);
}
void Simulation::Impl::request_velocity(const void* impl, std::int32_t body, const Twist& twist) {
  add_request(impl_of(impl).pending_velocities, body, twist);
}

namespace {
bool finite(const Pose& p) {
  double sum = p.position.x + p.position.y + p.position.z;
  for (const auto& row : p.rotation.m)
    for (double v : row)
      sum += v;
  return std::isfinite(sum);
}
bool finite(const Twist& t) {
  return std::isfinite(t.linear_m_s.x + t.linear_m_s.y + t.linear_m_s.z + t.angular_rad_s.x +
                       t.angular_rad_s.y + t.angular_rad_s.z);
}
}  // namespace

std::string Simulation::Impl::body_label(int body) const {
  const auto& bodies = scene.bodies;
  return body > 0 && body <= static_cast<int>(bodies.size())
             ? "'" + bodies[static_cast<std::size_t>(body - 1)].id + "'"
             : "index " + std::to_string(body);
}

void Simulation::Impl::apply_pending_places() {
  // Each list is emptied before a refusal is thrown, so that a caught error leaves no request
  // behind for the next tick.
  auto refuse = [&](const std::string& message) {
    pending_places.clear();
    pending_moves.clear();
    pending_velocities.clear();
    throw Error(ErrorKind::runtime, message);
  };
  // Things first, so that a thing added in this stage can be placed or pushed in it too.
  apply_pending_things();
  apply_pending_body_changes();
  auto apply = [&](auto& list, const char* verb, const char* not_finite, const char* refused,
                   auto&& act) {
    for (const auto& [body, value] : list) {
      auto asked = [&, b = body] {
        return std::string("a component asked to ") + verb + " body " + body_label(b);
      };
      if (!finite(value)) refuse(asked() + not_finite);
      if (!act(body, value)) refuse(asked() + refused);
    }
    list.clear();
  };
  apply(pending_places, "place", " at a non-finite pose",
        ", which is not free on the world (only a thing or a robot's root body can be placed)",
        [&](int body, const Pose& pose) { return multibody->place_free_body(body, pose); });
  apply(pending_moves, "move", " to a non-finite pose", ", which is not a body of the scene",
        [&](int body, const Pose& pose) { return multibody->move_body(body, pose); });
  apply(pending_velocities, "set the velocity of", " to a non-finite value",
        ", which is not a body of the scene",
        [&](int body, const Twist& twist) { return multibody->set_body_velocity(body, twist); });
  refresh();
}

void Simulation::Impl::check_loads_finite(const std::vector<int>* bodies,
                                          const std::vector<int>* axes, const AxisDrive* drives,
                                          std::int32_t drive_count) const {
  // One sum: a NaN or an infinity anywhere poisons it. Only then look for where. Null bodies
  // or axes: all of them (the world's entry too).
  const Wrench* wrenches = multibody->applied_wrenches();
  const double* axis_force = multibody->applied_axis_forces();
  const double* axis_friction = multibody->applied_axis_friction();
  auto each = [](const std::vector<int>* list, std::size_t all, auto&& f) {
    if (list) {
      for (const int i : *list)
        if (!f(static_cast<std::size_t>(i))) return;
    } else {
      for (std::size_t i = 0; i < all; ++i)
        if (!f(i)) return;
    }
  };
  double sum = 0;
  each(bodies, poses.size(), [&](std::size_t b) {
    sum += wrenches[b].force_N.x + wrenches[b].force_N.y + wrenches[b].force_N.z +
           wrenches[b].torque_Nm.x + wrenches[b].torque_Nm.y + wrenches[b].torque_Nm.z;
    return true;
  });
  each(axes, axis_views.size(), [&](std::size_t a) {
    sum += axis_force[a] + axis_friction[a];
    return true;
  });
  for (std::int32_t d = 0; d < drive_count; ++d)  // the bounds may be infinite, not NaN
    sum += drives[d].force + drives[d].damping +
           (drives[d].min_force <= drives[d].max_force ? 0.0 : NAN);
  if (std::isfinite(sum)) return;
  std::string what;
  each(bodies, poses.size(), [&](std::size_t b) {
    const Wrench& w = wrenches[b];
    if (!std::isfinite(w.force_N.x + w.force_N.y + w.force_N.z + w.torque_Nm.x + w.torque_Nm.y +
                       w.torque_Nm.z))
      what = "a non-finite force or torque on body " + multibody->body_name(static_cast<int>(b));
    return what.empty();
  });
  if (what.empty())
    each(axes, axis_views.size(), [&](std::size_t a) {
      if (!std::isfinite(axis_force[a] + axis_friction[a]))
        what = "a non-finite force or friction on axis '" + axis_views[a].name + "'";
      return what.empty();
    });
  for (std::int32_t d = 0; d < drive_count && what.empty(); ++d)
    if (!std::isfinite(drives[d].force + drives[d].damping) ||
        !(drives[d].min_force <= drives[d].max_force))
      what = "a non-finite or inverted drive on axis '" + axis_views[drives[d].axis].name + "'";
  throw Error(ErrorKind::runtime, "at t = " + std::to_string(static_cast<double>(tick) * tick_s) +
                                      " s a component applied " + what +
                                      " (the components acting on it ran in this tick)");
}

void Simulation::Impl::refresh() {
  multibody->read(poses.data(), twists.data(), axis_position.data(), axis_velocity.data());
  world.time_s = static_cast<double>(tick) * tick_s;
  world.tick = tick;
  if (ray_caster) ray_caster->invalidate();
}

void Simulation::Impl::reset() {
  tick = 0;
  pending_places.clear();
  pending_moves.clear();
  pending_velocities.clear();
  annotations.clear();
  reset_images();
  multibody->reset();
  contacts->reset();
  reset_things();
  reset_body_shapes();
  reset_body_masses();
  pending_body_changes.clear();
  world.contacts = contacts->contacts();  // empty, for initialize()
  sync_local_views();
  // Copy in place: the WorldView points into these buffers.
  std::copy(inputs_initial.begin(), inputs_initial.end(), inputs.begin());
  std::copy(state_initial.begin(), state_initial.end(), state.begin());
  std::fill(published.begin(), published.end(), 0.0);
  std::fill(axis_force_applied.begin(), axis_force_applied.end(), 0.0);
  for (std::size_t c = 0; c < components.size(); ++c)
    RandomStream::seed(random.data() + 4 * c, options.seed ^ sim::fnv1a(components[c].prefix));
  refresh();
  for (std::size_t c = 0; c < components.size(); ++c) {
    StepContext ctx(&world, static_cast<std::int32_t>(c), components[c].period_ticks);
    try {
      const sim::RunningComponent running(components[c].crash_label.c_str());
      components[c].component->initialize(ctx);
    } catch (...) {
      sim::rethrow_from_component(components[c], "initialize", ErrorKind::runtime);
    }
  }
}

void Simulation::step(std::int64_t ticks) {
  impl_->advance(ticks);
  impl_->changed();
}

void Simulation::run_until(double t_s) {
  const auto target = static_cast<std::int64_t>(std::llround(t_s / impl_->tick_s));
  if (impl_->tick < target) impl_->advance(target - impl_->tick);
  impl_->changed();
}

void Simulation::reset() {
  impl_->reset();
  impl_->changed();
}
void Simulation::reset(std::uint64_t seed) {
  impl_->options.seed = seed;
  reset();
}
std::uint64_t Simulation::seed() const {
  return impl_->options.seed;
}
void Simulation::set_profiling(bool on) {
  if (!on) {
    impl_->profile.reset();
  } else if (!impl_->profile) {
    impl_->profile = std::make_unique<sim::StageProfile>();
  }
}

std::vector<Simulation::StageTime> Simulation::stage_times() const {
  std::vector<StageTime> out;
  if (!impl_->profile) return out;
  for (std::size_t i = 0; i < sim::StageProfile::kStages; ++i)
    out.push_back({sim::stage_name(static_cast<sim::PipelineStage>(i)), impl_->profile->seconds[i],
                   impl_->profile->calls[i]});
  return out;
}

}  // namespace s2sim
