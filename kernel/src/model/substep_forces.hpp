#pragma once
/// \file
/// Loads that depend on the state inside a tick (contact): the multibody model calls them at
/// every substep with the current poses and velocities, then applies what they return.

#include <s2sim/math.hpp>

namespace s2sim::model {

class SubstepForces {
 public:
  virtual ~SubstepForces() = default;
  /// `poses`, `twists` per kernel body (0 = world); writes `wrenches` (about each body origin,
  /// world frame) for every body, zero where nothing acts. Must not allocate.
  virtual void compute(const Pose* poses, const Twist* twists, double step_s, Wrench* wrenches) = 0;

  // --- By parts (MultibodyIslands stepping parts on threads) --------------------------------
  /// The serial start of a substep whose parts run at once: when the loads can be computed
  /// part by part (what acts on a part's bodies depends on that part's alone), prepares that
  /// and returns true, and the caller then calls part(p) for every part, from any threads, and
  /// end_parts() after all of them; otherwise computes everything now, as compute(), and
  /// returns false. Either way the results are compute()'s to the bit. `bodies_unmoved`:
  /// nothing moved a body since the last pool run, whose place_part calls then hold.
  virtual bool begin_parts(const Pose* poses, const Twist* twists, double step_s, Wrench* wrenches,
                           bool /*bodies_unmoved*/) {
    compute(poses, twists, step_s, wrenches);
    return false;
  }
  /// Part `part`'s loads, into the wrenches of its bodies (after begin_parts returned true).
  virtual void part(int /*part*/) {}
  /// At the end of every pool run, from the part's thread: its bodies' new `poses`, to prepare
  /// the next substep with (the contact world places the part's shapes).
  virtual void place_part(int /*part*/, const Pose* /*poses*/) {}
  /// After every part's: what the parts found, gathered (serial).
  virtual void end_parts() {}
};

}  // namespace s2sim::model
