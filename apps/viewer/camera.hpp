#pragma once
/// \file
/// The world view's orbit camera: it turns around a target point (orbit), moves the target
/// (pan), changes its distance (zoom) and can follow a robot's main body. Z is up.

#include "layout.hpp"
#include "render_names.hpp"
#include "view.hpp"

namespace s2sim::viewer {

class Camera {
 public:
  Vec3f target_m{0, 0, 0.3f};
  float distance_m = 6;
  float yaw_rad = -1.2f;   ///< around Z, from +X
  float pitch_rad = 0.5f;  ///< above the horizon
  float fov_y_rad = 0.8f;
  int follow_robot = -1;  ///< index into scene robots, -1 = free
  /// Follow a robot that flies or floats when it would leave the view (keep_in_view.hpp).
  bool keep_in_view = true;

  Vec3f eye_m() const;
  Mat4 view() const;
  Mat4 projection(float aspect) const;
  /// What the renderer draws for the world view in `rect` of a framebuffer
  /// `framebuffer_height_px` high (the window's).
  render::View render_view(const Rect& rect, int framebuffer_height_px) const;

  /// Looks from `eye_m` at `target_m` (a SimTwo project's saved camera).
  void look_from(const Vec3f& eye_m, const Vec3f& target_m);

  /// Keeps the yaw and pitch, looks at the box's centre and sets the distance at which every
  /// corner of the box lies inside the central `fill` of the view (e.g. 0.85 of its width
  /// and height) for the view's `aspect` (width / height).
  void frame_box(const Vec3f& lo_m, const Vec3f& hi_m, float aspect, float fill = 0.85f);

  /// Keeps the target, yaw and pitch and moves back (never closer) until every corner of the
  /// box lies inside the central `fill` of the view: a saved camera that shows the whole scene.
  void back_off_to_fit(const Vec3f& lo_m, const Vec3f& hi_m, float aspect, float fill = 0.9f);

  /// Mouse drags in pixels; the factors make one window width about half a turn.
  void orbit(float dx_px, float dy_px);
  void pan(float dx_px, float dy_px, float viewport_height_px);
  /// Positive steps zoom in.
  void zoom(float wheel_steps);
};

}  // namespace s2sim::viewer
