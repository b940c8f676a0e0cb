#pragma once
/// \file
/// Which robot the camera should start following because it is leaving the view: one that
/// touches nothing and is jointed to nothing fixed (it flies or floats), whose main body
/// projects outside the view's central part. A robot on the floor, an arm or a pendulum is
/// left to leave the view: the user frames it or follows it.

#include "render_names.hpp"

#include <s2sim/kernel/simulation.hpp>

#include <vector>

namespace s2sim::viewer {

/// The share of the view (from its centre, in each direction) a robot may reach before it is
/// followed.
inline constexpr float kKeepInViewFill = 0.8f;

/// The first robot leaving the view (`view_projection`: world to clip space) while none of its
/// bodies touches anything or is jointed to the world, skipping those with `declined[r]` (the user
/// stopped following them); -1 when none.
int robot_leaving_view(const Simulation& sim, const Mat4& view_projection,
                       const std::vector<bool>& declined);

}  // namespace s2sim::viewer
