#include "camera.hpp"

#include <algorithm>

namespace s2sim::viewer {

Vec3f Camera::eye_m() const {
  const float c = std::cos(pitch_rad);
  return target_m +
         Vec3f{c * std::cos(yaw_rad), c * std::sin(yaw_rad), std::sin(pitch_rad)} * distance_m;
}

Mat4 Camera::view() const {
  return look_at(eye_m(), target_m, {0, 0, 1});
}

Mat4 Camera::projection(float aspect) const {
  // Near and far scale with the distance so that both a close-up and a field view keep depth
  // precision.
  return perspective(fov_y_rad, aspect, std::max(0.01f, distance_m * 0.01f),
                     std::max(100.0f, distance_m * 50));
}

void Camera::orbit(float dx_px, float dy_px) {
  yaw_rad -= dx_px * 0.005f;
  pitch_rad = std::clamp(pitch_rad + dy_px * 0.005f, -1.55f, 1.55f);
}

void Camera::pan(float dx_px, float dy_px, float viewport_height_px) {
  const Vec3f forward = normalized(target_m - eye_m());
  const Vec3f right = normalized(cross(forward, {0, 0, 1}));
  const Vec3f up = cross(right, forward);
  // One viewport height of drag moves the target by the visible height at the target.
  const float metres_per_px =
      2 * distance_m * std::tan(fov_y_rad / 2) / std::max(1.0f, viewport_height_px);
  target_m = target_m - right * (dx_px * metres_per_px) + up * (dy_px * metres_per_px);
  follow_robot = -1;
}

void Camera::zoom(float wheel_steps) {
  distance_m = std::clamp(distance_m * std::pow(0.9f, wheel_steps), 0.05f, 500.0f);
}

}  // namespace s2sim::viewer
