#pragma once
/// \file
/// The world view's orbit camera: it turns around a target point (orbit), moves the target
/// (pan), changes its distance (zoom) and can follow a robot's main body. Z is up.

#include "gl_math.hpp"

namespace s2sim::viewer {

class Camera {
 public:
  Vec3f target_m{0, 0, 0.3f};
  float distance_m = 6;
  float yaw_rad = -1.2f;   ///< around Z, from +X
  float pitch_rad = 0.5f;  ///< above the horizon
  float fov_y_rad = 0.8f;
  int follow_robot = -1;  ///< index into scene robots, -1 = free

  Vec3f eye_m() const;
  Mat4 view() const;
  Mat4 projection(float aspect) const;

  /// Mouse drags in pixels; the factors make one window width about half a turn.
  void orbit(float dx_px, float dy_px);
  void pan(float dx_px, float dy_px, float viewport_height_px);
  /// Positive steps zoom in.
  void zoom(float wheel_steps);
};

}  // namespace s2sim::viewer
