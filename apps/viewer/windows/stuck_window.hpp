#pragma once
/// \file
/// What the window shows while a component's call has not returned (state.stuck): the call,
/// how long it has been running, and a button to give the simulation up.

#include "../viewer_state.hpp"

namespace s2sim::viewer {

/// Draws the notice over the world view; true when "Stop the simulation" was pressed.
bool draw_stuck_window(ViewerState& state);

}  // namespace s2sim::viewer
