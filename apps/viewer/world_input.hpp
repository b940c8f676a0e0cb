#pragma once
/// \file
/// Mouse and keyboard in the world view: left drag orbits, right (or shift + left) drag pans,
/// the wheel zooms, a click picks a body, ctrl + left drag moves a thing (or a robot by its
/// root body) over the floor; space plays or pauses, S or the right arrow steps, R resets.
/// Nothing happens while an ImGui window has the mouse or the keyboard.

#include "scene_drawables.hpp"
#include "viewer_state.hpp"

namespace s2sim::viewer {

class WorldInput {
 public:
  /// Reads this frame's input (call after ImGui::NewFrame) and acts on the state.
  void update(ViewerState& state, const SceneDrawables& drawables);

 private:
  void mouse(ViewerState& state, const SceneDrawables& drawables);
  void keys(ViewerState& state);
  void start_drag(ViewerState& state, const SceneDrawables& drawables);

  int dragged_body_ = -1;  ///< body under a ctrl-drag, -1 = none
  float drag_height_m_ = 0;
  Vec3f drag_offset_m_;  ///< body origin minus the grabbed point
};

/// The world-frame ray under a mouse position (pixels from the top left), unit direction.
void mouse_ray(const Camera& camera, float mouse_x_px, float mouse_y_px, float width_px,
               float height_px, Vec3f& origin, Vec3f& direction);

}  // namespace s2sim::viewer
