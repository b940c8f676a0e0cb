#pragma once
/// \file
/// The camera window's state (windows/camera_window.cpp): the scene's images, which of them
/// are shown, each one's texture and the frame it holds, and a lidar's point cloud in the
/// world frame for the world view (windows/point_cloud_overlay.cpp).

#include "image_colours.hpp"
#include "image_texture.hpp"
#include "layout.hpp"

#include <s2sim/math.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace s2sim {
class Simulation;
}

namespace s2sim::viewer {

struct CameraImage {
  std::string name;  ///< the image's full name (Simulation::image_names())
  ImageView view = ImageView::colour;
  bool shown = false;
  /// The frame and time of the image that the texture (or the cloud) holds; frame 0 is
  /// "none yet", so the sentinel differs from every real frame.
  std::uint64_t frame = ~std::uint64_t{0};
  double time_s = -1;
  std::uint64_t uploads = 0;  ///< texture uploads (or cloud rebuilds) so far, for tests
  ImageTexture texture;
  ShownImage shown_image;  ///< the RGB8 pixels last uploaded, with the legend's range
  Rect drawn;              ///< where the image was drawn last frame, window pixels
  Rect legend;             ///< and its distance legend's colour bar
  /// A point cloud: the scene sensor whose frame it is in (-1: unknown, not drawn), its points
  /// in the world frame, each with its colour (by distance from the sensor).
  int sensor = -1;
  std::vector<Vec3f> cloud_m;
  std::vector<std::uint32_t> cloud_colours;  ///< ImGui's packed ABGR
  std::vector<float> cloud_ranges_m;         ///< each point's distance from the sensor
  float cloud_near_m = 0, cloud_far_m = 0;
};

struct CameraWindowState {
  const Simulation* sim = nullptr;  ///< whose images `images` lists; rebuilt when it changes
  std::vector<CameraImage> images;
  bool cloud_in_world = true;  ///< draw shown point clouds in the world view
};

}  // namespace s2sim::viewer
