#pragma once
/// \file
/// The shown lidar point clouds (the Cameras window's `points` images) drawn over the 3-D
/// view, in the world frame: each point where the lidar's frame puts it now, coloured by its
/// distance from the sensor (at most 100 000 dots a cloud: every k-th point of a larger
/// one). Nothing is done while the Cameras window is closed.

#include "../viewer_state.hpp"

namespace s2sim::viewer {

void draw_point_cloud_overlay(ViewerState& state);

}  // namespace s2sim::viewer
