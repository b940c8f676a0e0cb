#pragma once
/// \file
/// What the world view shows over the 3-D scene, drawn with ImGui's background draw list
/// (under the windows, clipped to the 3-D view): each robot's trail, the world's axes, the
/// robots' names and a scale bar.

#include "../viewer_state.hpp"

namespace s2sim::viewer {

/// Adds each robot's main body position to its trail (after the frame's stepping).
void record_trails(ViewerState& state);
/// Draws the trails, axes, labels and scale bar that `state.overlay` turns on.
void draw_world_overlay(const ViewerState& state);

}  // namespace s2sim::viewer
