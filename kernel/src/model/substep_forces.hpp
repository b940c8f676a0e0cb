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
};

}  // namespace s2sim::model
