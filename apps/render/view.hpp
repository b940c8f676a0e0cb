#pragma once
/// \file
/// Where one frame is seen from and drawn into: the view and projection, and the framebuffer
/// rectangle. The viewer makes it from its orbit camera, a camera sensor from its shot.

#include "gl_math.hpp"

namespace s2sim::render {

struct View {
  Mat4 view;        ///< world to eye (OpenGL's eye: looks along its -Z, +Y up)
  Mat4 projection;  ///< eye to clip
  Vec3f eye_m;      ///< the eye in the world
  float fov_y_rad = 0.8f;
  /// The shadow map is fitted to the casters within `focus_radius_m` of `focus_m`.
  Vec3f focus_m;
  float focus_radius_m = 3;
  unsigned framebuffer = 0;  ///< drawn into; 0 = the window's
  /// The rectangle drawn, framebuffer pixels from its bottom left (OpenGL's viewport).
  int x_px = 0, y_px = 0, width_px = 1, height_px = 1;
};

}  // namespace s2sim::render
