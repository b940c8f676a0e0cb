#pragma once
/// \file
/// The physics part of a tick (sim/step.cpp): the substep pipeline over the multibody and the
/// contact layer. Simulation runs it after the scheduled components; model and contact tests
/// run it alone.

#include "model/multibody.hpp"
#include "model/multibody_islands.hpp"
#include "model/substep_forces.hpp"
#include "sim/stage_profile.hpp"

namespace s2sim::sim {

/// Advances `multibody` by one tick: per substep, collide (`contact`, may be null) → prepare
/// axes → accelerations → kick → axes → drift → project; after the last, finish (the
/// multibody's end of tick: bodies read, finite check). Throws s2sim::Error (runtime) when the
/// state becomes non-finite or Simbody refuses it. `profile` (may be null) accumulates the time per
/// stage.
void physics_tick(model::Multibody& multibody, model::SubstepForces* contact,
                  StageProfile* profile = nullptr);
/// The same tick over the scene's parts: one part is the call above; several run each
/// substep's collide serially, then every part's prepare axes … project (and the finish on the
/// last substep) at once on the worker pool. `profile` then times collide and the stages of the
/// parts the calling thread took, not the wait for the other threads' parts. With `hooks` (several
/// parts: the components in the parts), each part runs their `start` before its first
/// substep, after the calling thread's pairs of that substep (the contact of the tick's start
/// does not depend on the components), or before the contact when the contact is computed
/// whole (it writes the contact list the components read); `end` after its last.
void physics_tick(model::MultibodyIslands& multibody, model::SubstepForces* contact,
                  StageProfile* profile = nullptr,
                  model::MultibodyIslands::TickHooks* hooks = nullptr);

/// Whether `multibody` can run ahead (sim/run_ahead.cpp) now: several parts, whose shapes are
/// placed at the current poses, `contact` split by them and each part's shapes apart from the
/// others' (SubstepForces::fence_parts(), which then fences them).
bool fence_parts(model::MultibodyIslands& multibody, model::SubstepForces* contact);
/// After fence_parts(): `ticks` whole ticks of the parts, each part alone (its components by
/// `hooks`, its contact, its stages), stopping when a part's shapes leave their fence.
/// Returns whether all ran; if not, or if it throws, the state is only good for a restore.
bool physics_ticks_ahead(model::MultibodyIslands& multibody, model::SubstepForces& contact,
                         StageProfile* profile, model::MultibodyIslands::TickHooks& hooks,
                         int ticks);

}  // namespace s2sim::sim
