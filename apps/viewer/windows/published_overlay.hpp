#pragma once
/// \file
/// What components publish for the people watching (Simulation::annotations(), SDK 0.9),
/// over the 3-D view: the HUD text at its top-left (SimTwo's `HUDStrings`) and the trails
/// (SimTwo's `AddTrailNode`), drawn with ImGui's background draw list like world_overlay.

#include "../viewer_state.hpp"

namespace s2sim::viewer {

/// Draws the HUD text and the published trails over the 3-D view.
void draw_published_overlay(ViewerState& state);
/// Copies the log lines published since the last call into the viewer's log.
void collect_published_lines(ViewerState& state);

}  // namespace s2sim::viewer
