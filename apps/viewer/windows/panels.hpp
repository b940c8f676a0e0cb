#pragma once
/// \file
/// The tiled layout's ImGui side: the menu bar, the Run window at the top of the left column,
/// and the panels grouped in tabs in the left column and the bottom row (layout.hpp).

#include "../viewer_state.hpp"

namespace s2sim::viewer {

/// Saves and restores the layout (column sizes, open panels) in the ImGui ini file. Call once
/// after ImGui::CreateContext, before the first frame.
void register_layout_settings(ViewerState& state);
/// Brings the panel NAME (as `show` names it) to the front of its tab group next frame.
void bring_to_front(ViewerState& state, const std::string& name);
/// The default layout: default column sizes, only the Run window open.
void reset_layout(ViewerState& state);
/// Computes this frame's rectangles (state.layout_rects) for the window size; after NewFrame.
void update_layout(ViewerState& state, float width_px, float height_px);
/// Draws the menu bar, the Run window and the tab groups.
void draw_panels(ViewerState& state);
/// Prints the rectangles ImGui gave the windows and the 3-D view (`print layout`, tests).
void print_layout(const ViewerState& state);
/// Number of tabbed panels (ViewerState::panels_open_last_frame's size).
std::size_t panel_count();

}  // namespace s2sim::viewer
