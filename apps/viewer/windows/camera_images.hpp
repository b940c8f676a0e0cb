#pragma once
/// \file
/// The camera window's bookkeeping, shared with the world view's point clouds and the UI
/// script: the list of the scene's images kept in step with the simulation, and each image
/// brought up to date only when its component wrote a new frame. Call them only where the
/// viewer reads the simulation: between frames' stepping, never while it runs (stepper.hpp).

#include "../viewer_state.hpp"

namespace s2sim::viewer {

/// Lists the images of the simulation now shown, when it changed (a load, a reload); the
/// images shown before stay shown by name. The first list shows every image.
void sync_camera_images(ViewerState& state);
/// The entry of image `name`, nullptr when the scene has none.
CameraImage* find_camera_image(ViewerState& state, const std::string& name);
/// Brings `entry`'s texture (colour, distance, ids) or world-frame cloud (points) up to the
/// image's frame; nothing when the frame has not changed.
void refresh_camera_image(const Simulation& sim, CameraImage& entry);

}  // namespace s2sim::viewer
