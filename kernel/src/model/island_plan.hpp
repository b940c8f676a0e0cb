#pragma once
/// \file
/// The islands of the joint graph (the connected components: a tree with every loop joint
/// touching it) dealt into parts, each built as its own Simbody system (multibody_islands.hpp).

#include "model/multibody.hpp"

#include <s2sim/kernel/scene.hpp>

#include <vector>

namespace s2sim::model {

/// One part of the multibody: whole islands, planned like the whole scene.
struct PartPlan {
  /// The part's trees, loops, loose bodies and axes, each in the whole plan's order (a loose
  /// body is the part's whose jointed body stands nearest to it at load). joint_is_loop is
  /// the whole plan's.
  Topology topology;
  std::vector<double> axis_inertia;  ///< per part axis
  std::vector<int> global_axis;      ///< part axis -> the whole plan's axis
  std::vector<int> bodies;           ///< kernel bodies the part integrates, ascending
  std::vector<int> joints;           ///< scene joints the part realises, ascending
};

/// Deals the islands of `topology` into at most `parts` parts: islands in kernel order cut into
/// runs of about equal weight (bodies + axes), so that a part's bodies lie together, when no
/// part is then heavier than by the greedy deal; else the greedy deal: islands in decreasing
/// weight (ties: the island of the lower body first), each to the part with the least weight
/// so far (ties: the lower part). Each loose body then goes with the island of the jointed
/// body nearest to it at load. One part (the whole plan) when `parts` ≤ 1, the scene
/// has fewer than two islands, or it has a loop-closing joint anywhere (one system's
/// scene-wide policies then decide last bits: island_plan.cpp).
std::vector<PartPlan> plan_parts(const scene::Scene& scene, const Topology& topology,
                                 const std::vector<double>& axis_inertia, int parts);

}  // namespace s2sim::model
