#pragma once
/// \file
/// A camera shot drawn offscreen and read back into the kernel's images (s2sim/image.hpp):
/// colour with the world view's look but one sample per pixel (edges follow pixel centres),
/// depth in metres along the optical axis, and body ids. Needs a current OpenGL 3.3 context.

#include "renderer.hpp"
#include "view.hpp"

#include <s2sim/image.hpp>

#include <cstdint>
#include <vector>

namespace s2sim::render {

/// The view of a shot: a symmetric pinhole of the shot's vertical field of view, aspect
/// width / height, near and far; the camera frame looks along its +Z with +Y up (its +X is
/// the image's left), OpenGL's eye along its -Z with +Y up, so eye = diag(-1, 1, -1) camera.
View camera_view(const CameraShot& shot);

class CameraImages {
 public:
  CameraImages() = default;
  ~CameraImages();
  CameraImages(const CameraImages&) = delete;
  CameraImages& operator=(const CameraImages&) = delete;

  /// Draws `items` (with `renderer`'s meshes, `settings`' look; multisampling off) from
  /// `shot` into the images given (null: not drawn), of the shot's size, the top row first:
  /// rgb8 colour; float32 depth in metres along the optical axis, +infinity where nothing is
  /// within the far plane; uint16 body ids (DrawItem::body; 0 for the floor, kNoBodyId where
  /// nothing is). Depth and ids see the items whose DrawItem::sensed is set and that are not
  /// fully transparent, whatever their opacity otherwise. Throws s2sim::Error (runtime) when
  /// the driver refuses the framebuffers.
  void render(Renderer& renderer, const std::vector<DrawItem>& items, const CameraShot& shot,
              RenderSettings settings, Image* rgb, Image* depth, Image* body_ids);

 private:
  /// (Re)creates the framebuffers for a shot of this size.
  void make_targets(int width_px, int height_px);
  void release_targets();
  void draw_colour(Renderer& renderer, const std::vector<DrawItem>& items, const View& view,
                   RenderSettings& settings, Image& rgb);
  void draw_depth_and_ids(Renderer& renderer, const std::vector<DrawItem>& items, const View& view,
                          float floor_half_size_m, Image* depth, Image* body_ids);

  int width_px_ = 0, height_px_ = 0;
  /// Colour: RGBA8 and depth + stencil (the floor-only shadows use the stencil).
  unsigned colour_framebuffer_ = 0, colour_ = 0, colour_depth_ = 0;
  /// Depth and ids: R32F linear depth, R16UI ids and a 32-bit float depth buffer.
  unsigned sensor_framebuffer_ = 0, linear_depth_ = 0, ids_ = 0, sensor_depth_ = 0;
  unsigned flat_program_ = 0;
  int model_location_ = -1, view_location_ = -1, view_projection_location_ = -1,
      body_location_ = -1;
  /// Rows as OpenGL reads them (bottom first), reused every shot.
  std::vector<std::uint8_t> rgb_rows_;
  std::vector<float> depth_rows_;
  std::vector<std::uint16_t> id_rows_;
};

}  // namespace s2sim::render
