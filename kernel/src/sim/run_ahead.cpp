// Running ahead: with the components in the parts and every part's shapes apart
// from the others', the parts step a stretch of ticks each on its own thread, without the
// calling thread between their ticks. A tick stepped one by one makes both threads wait for
// the slower at every tick and pays the start of a pool run; a stretch pays them once.
//
// Exact, not approximate: each part's shapes are fenced (ContactWorld::fence_parts): each two
// parts may come only so close along the axis that parts them best, and go anywhere else.
// While every part's shapes stay inside their fence no pair of shapes joins two parts, and each
// part's substeps are those of the serial run bit for bit (the parts' contact is computed part by
// part exactly when no pair joins two parts). A part whose shapes leave their fence stops, the
// others stop at their next tick, and the state goes back to where the stretch began (the state
// layout, as a snapshot restores it); the stretch then runs tick by tick, which sees the parts meet
// as the serial run does.
#include "sim/simulation_impl.hpp"
#include "sim/step.hpp"

#include <algorithm>

namespace s2sim {

namespace {
/// A stretch's length: the first after a start or a loss, then doubled after each stretch
/// kept, up to the longest. What a stretch costs once (the saved state, about 10 µs for 16
/// robots; the start of the pool run; the wait for the slower part at its end) shrinks per
/// tick as stretches grow: on 16 robots, stretches of 1 000 ticks gave 0.93–0.96 of the
/// machine's two-thread ceiling, of 64 ticks 0.88–1.03, of 16 ticks 0.75–0.94
/// (bench/peers/results/history.md, "Tried and not kept").
/// A part leaving its fence loses the ticks its stretch ran, so the length starts short.
constexpr std::int64_t kFirstStretchTicks = 64;
constexpr std::int64_t kLongestStretchTicks = 1024;
/// After a stretch lost, ticks one by one before the next try: kFirstStretchTicks, doubled for
/// each stretch lost in a row up to 32 times as many (parts that keep meeting stop trying).
constexpr int kMaxBackoff = 5;
}  // namespace

void Simulation::Impl::advance(std::int64_t ticks) {
  while (ticks > 0) {
    if (ticks > 1 && ahead_wait_ticks == 0 && options.run_ahead) {
      const std::int64_t ran =
          step_ahead(std::min({ticks, kFirstStretchTicks << ahead_growth, kLongestStretchTicks}));
      ticks -= ran;
      if (ran > 0) continue;
    }
    step_once();
    --ticks;
    if (ahead_wait_ticks > 0) --ahead_wait_ticks;
  }
}

std::int64_t Simulation::Impl::step_ahead(std::int64_t ticks) {
  // Only the parts' own work may happen between the ticks: their components, their physics.
  if (component_parts.parts.empty() || !pending_places.empty() || !pending_moves.empty() ||
      !pending_velocities.empty() || !pending_things.empty() || !pending_obstacles.empty() ||
      !pending_body_changes.empty() || !sim::fence_parts(*multibody, contacts.get()))
    return 0;
  ahead_checkpoint.clear();  // keeps its capacity: after the first stretches, no allocation
  layout.save(ahead_checkpoint);
  multibody->applied_wrenches()[0] = Wrench{};  // the world's entry, as step_once() clears it
  bool ran = false;
  try {
    ran = sim::physics_ticks_ahead(*multibody, *contacts, profile.get(), part_hooks,
                                   static_cast<int>(ticks));
  } catch (...) {
    // Thrown again, with its tick and its names, when the stretch runs tick by tick.
  }
  if (ran) {
    tick += ticks;
    ahead_misses = 0;
    if ((kFirstStretchTicks << ahead_growth) < kLongestStretchTicks) ++ahead_growth;
    ++ahead_counts.stretches;
    ahead_counts.ticks += ticks;
    sim::StageTimer timer(profile.get(), sim::PipelineStage::read_out);
    refresh();
    return ticks;
  }
  layout.restore(layout.id(), layout.entries(), ahead_checkpoint);
  restored();
  ahead_wait_ticks = kFirstStretchTicks << std::min(ahead_misses, kMaxBackoff);
  ahead_growth = 0;
  ++ahead_misses;
  ++ahead_counts.lost;
  return 0;
}

Simulation::RunAheadCounts Simulation::run_ahead_counts() const {
  return impl_->ahead_counts;
}

}  // namespace s2sim
