#include "camera.hpp"

#include <algorithm>
#include <cmath>

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

render::View Camera::render_view(const Rect& rect, int framebuffer_height_px) const {
  render::View v;
  v.width_px = std::max(1, static_cast<int>(std::lround(rect.width)));
  v.height_px = std::max(1, static_cast<int>(std::lround(rect.height)));
  // OpenGL counts rows from the bottom.
  v.x_px = static_cast<int>(std::lround(rect.x));
  v.y_px = framebuffer_height_px - static_cast<int>(std::lround(rect.y)) - v.height_px;
  v.view = view();
  v.projection = projection(static_cast<float>(v.width_px) / static_cast<float>(v.height_px));
  v.eye_m = eye_m();
  v.fov_y_rad = fov_y_rad;
  // The casters within 2.5 view distances of the point looked at (at least 3 m).
  v.focus_m = target_m;
  v.focus_radius_m = std::max(3.0f, 2.5f * distance_m);
  return v;
}

void Camera::look_from(const Vec3f& eye, const Vec3f& target) {
  const Vec3f d = eye - target;
  target_m = target;
  distance_m = std::clamp(std::sqrt(dot(d, d)), 0.05f, 500.0f);
  pitch_rad =
      std::clamp(std::asin(std::clamp(d.z / std::sqrt(dot(d, d)), -1.0f, 1.0f)), -1.55f, 1.55f);
  yaw_rad = std::atan2(d.y, d.x);
}

namespace {
/// Whether the box's corners all project inside the central `fill` of the view.
bool box_fits(const Camera& camera, const Vec3f& lo_m, const Vec3f& hi_m, float aspect,
              float fill) {
  const Mat4 vp = camera.projection(aspect) * camera.view();
  for (int corner = 0; corner < 8; ++corner) {
    const Vec4f h = vp * Vec4f{corner & 1 ? hi_m.x : lo_m.x, corner & 2 ? hi_m.y : lo_m.y,
                               corner & 4 ? hi_m.z : lo_m.z, 1};
    if (h.w <= 0 || std::abs(h.x / h.w) > fill || std::abs(h.y / h.w) > fill) return false;
  }
  return true;
}
}  // namespace

void Camera::back_off_to_fit(const Vec3f& lo_m, const Vec3f& hi_m, float aspect, float fill) {
  if (box_fits(*this, lo_m, hi_m, aspect, fill)) return;
  float near_m = distance_m, far_m = 500;
  distance_m = far_m;
  if (!box_fits(*this, lo_m, hi_m, aspect, fill)) return;
  for (int i = 0; i < 40; ++i) {
    distance_m = std::sqrt(near_m * far_m);
    (box_fits(*this, lo_m, hi_m, aspect, fill) ? far_m : near_m) = distance_m;
  }
  distance_m = far_m;
}

void Camera::frame_box(const Vec3f& lo_m, const Vec3f& hi_m, float aspect, float fill) {
  target_m = (lo_m + hi_m) * 0.5f;
  auto fits = [&](float distance) {
    distance_m = distance;
    return box_fits(*this, lo_m, hi_m, aspect, fill);
  };
  // Farther only shrinks the box on screen once the eye is outside it: bisect on the distance.
  float near_m = 0.05f, far_m = 500;
  if (!fits(far_m)) return;  // larger than anything the zoom reaches: stay at the farthest
  for (int i = 0; i < 40; ++i) {
    const float mid = std::sqrt(near_m * far_m);
    (fits(mid) ? far_m : near_m) = mid;
  }
  distance_m = far_m;
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
