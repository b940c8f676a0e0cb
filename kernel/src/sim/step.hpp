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

/// Advances `multibody` by one tick: per substep, collide (`contact`, may be null) → forces →
/// accelerations → kick → axes → drift → project; then the end-of-tick read-out and finite
/// check. Throws s2sim::Error (runtime) when the state becomes non-finite or Simbody refuses
/// it. `profile` (may be null) accumulates the time per stage.
void physics_tick(model::Multibody& multibody, model::SubstepForces* contact,
                  StageProfile* profile = nullptr);
/// The same tick over the scene's parts: one part is the call above; several run each
/// substep's collide serially, then every part's forces … project (and the finish on the last
/// substep) at once on the worker pool. `profile` then times collide and the stages of the parts
/// the calling thread took, not the wait for the other threads' parts. With `hooks` (several
/// parts: the components in the parts), each part runs their `start` before its first
/// substep, after the calling thread's pairs of that substep (the contact of the tick's start
/// does not depend on the components), or before the contact when the contact is computed
/// whole (it writes the contact list the components read); `end` after its last.
void physics_tick(model::MultibodyIslands& multibody, model::SubstepForces* contact,
                  StageProfile* profile = nullptr,
                  const model::MultibodyIslands::TickHooks* hooks = nullptr);

}  // namespace s2sim::sim
