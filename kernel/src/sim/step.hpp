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

/// One part's stages of substep `substep` of the leapfrog (docs/models/multibody.md): prepare
/// axes → accelerations → kick → axes → drift → project, and after the tick's last substep
/// finish (the multibody's end of tick: bodies read, finite check). What each part runs on its
/// thread; model and contact tests step a bare Multibody with it. `profile` (may be null)
/// accumulates the time per stage.
void multibody_substep(model::Multibody& multibody, int substep, StageProfile* profile = nullptr);

/// Advances `multibody` by one tick: per substep, collide (`contact`, may be null), then every
/// part's stages (multibody_substep) at once on the worker pool; one part runs on the calling
/// thread, the same code (the pool's serial mode). Contact is computed part by part, in the
/// parts, when it split by them and no two parts' bodies meet in the substep; else whole, on
/// the calling thread, before the parts. `profile` times collide and the stages of the parts
/// the calling thread took, not the wait for the other threads' parts. With `hooks` (the
/// components in the parts), each part runs their `start` before its first substep, after the
/// calling thread's pairs of that substep (the contact of the tick's start does not depend on
/// the components), or before the contact when the contact is computed whole (it writes the
/// contact list the components read); `end` after its last. Throws s2sim::Error (runtime)
/// when the state becomes non-finite or Simbody refuses it.
void physics_tick(model::MultibodyIslands& multibody, model::SubstepForces* contact,
                  StageProfile* profile = nullptr,
                  model::MultibodyIslands::TickHooks* hooks = nullptr);

/// Whether `multibody` can run ahead (sim/run_ahead.cpp) now: parts whose shapes are placed at the
/// current poses, `contact` split by them and each part's shapes apart from the others'
/// (SubstepForces::fence_parts(), which then fences them).
bool fence_parts(model::MultibodyIslands& multibody, model::SubstepForces* contact);
/// After fence_parts(): `ticks` whole ticks of the parts, each part alone (its components by
/// `hooks`, its contact, its stages), stopping when a part's shapes leave their fence.
/// Returns whether all ran; if not, or if it throws, the state is only good for a restore.
bool physics_ticks_ahead(model::MultibodyIslands& multibody, model::SubstepForces& contact,
                         StageProfile* profile, model::MultibodyIslands::TickHooks& hooks,
                         int ticks);

}  // namespace s2sim::sim
