#include "world_input.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace s2sim::viewer {
namespace {

Vec3 to_d(const Vec3f& v) {
  return {v.x, v.y, v.z};
}

/// The ray under the mouse, from ImGui's display size and mouse position.
void ray_under_mouse(const ViewerState& state, Vec3f& origin, Vec3f& direction) {
  const ImGuiIO& io = ImGui::GetIO();
  const Rect& view = state.layout_rects.world;  // the 3-D view's region of the window
  mouse_ray(state.camera, io.MousePos.x - view.x, io.MousePos.y - view.y, view.width, view.height,
            origin, direction);
}

}  // namespace

void mouse_ray(const Camera& camera, float mouse_x_px, float mouse_y_px, float width_px,
               float height_px, Vec3f& origin, Vec3f& direction) {
  const float aspect = width_px / std::max(1.0f, height_px);
  const Mat4 inv = inverse(camera.projection(aspect) * camera.view());
  const float nx = 2 * mouse_x_px / std::max(1.0f, width_px) - 1;
  const float ny = 1 - 2 * mouse_y_px / std::max(1.0f, height_px);
  const Vec4f near_h = inv * Vec4f{nx, ny, -1, 1};
  const Vec4f far_h = inv * Vec4f{nx, ny, 1, 1};
  origin = {near_h.x / near_h.w, near_h.y / near_h.w, near_h.z / near_h.w};
  const Vec3f far_p{far_h.x / far_h.w, far_h.y / far_h.w, far_h.z / far_h.w};
  direction = normalized(far_p - origin);
}

void WorldInput::update(ViewerState& state, const SceneDrawables& drawables) {
  mouse(state, drawables);
  keys(state);
}

void WorldInput::mouse(ViewerState& state, const SceneDrawables& drawables) {
  const ImGuiIO& io = ImGui::GetIO();
  if (dragged_body_ > 0) {
    if (!io.MouseDown[0]) {
      dragged_body_ = -1;
      return;
    }
    Vec3f origin, direction;
    ray_under_mouse(state, origin, direction);
    if (std::abs(direction.z) < 1e-6f) return;  // looking along the drag plane
    const float t = (drag_height_m_ - origin.z) / direction.z;
    if (t <= 0) return;
    const Vec3f hit = origin + direction * t;
    if (!move_body(state, dragged_body_, to_d(hit + drag_offset_m_))) dragged_body_ = -1;
    return;
  }
  if (io.WantCaptureMouse) return;
  if (ImGui::IsMouseClicked(0) && io.KeyCtrl) {
    start_drag(state, drawables);
    return;
  }
  const bool pan = io.MouseDown[1] || io.MouseDown[2] || (io.MouseDown[0] && io.KeyShift);
  if (pan)
    state.camera.pan(io.MouseDelta.x, io.MouseDelta.y, state.layout_rects.world.height);
  else if (io.MouseDown[0])
    state.camera.orbit(io.MouseDelta.x, io.MouseDelta.y);
  if (io.MouseWheel != 0) state.camera.zoom(io.MouseWheel);
  // A click is a press and release that moved less than 3 pixels (else it was an orbit).
  if (ImGui::IsMouseReleased(0) && io.MouseDragMaxDistanceSqr[0] < 9) {
    Vec3f origin, direction;
    ray_under_mouse(state, origin, direction);
    float distance_m = 0;
    state.selected_body = drawables.pick(origin, direction, distance_m);
    if (state.selected_body >= 0) state.windows.body = true;
  }
}

void WorldInput::start_drag(ViewerState& state, const SceneDrawables& drawables) {
  Vec3f origin, direction;
  ray_under_mouse(state, origin, direction);
  float distance_m = 0;
  const int body = drawables.pick(origin, direction, distance_m);
  if (body <= 0) return;
  // Drag over the horizontal plane through the grabbed point, keeping the grab offset.
  const Vec3f hit = origin + direction * distance_m;
  drag_height_m_ = hit.z;
  drag_offset_m_ = to_f(state.sim->body_pose(body).position) - hit;
  dragged_body_ = body;
  state.selected_body = body;
}

void WorldInput::keys(ViewerState& state) {
  if (ImGui::GetIO().WantCaptureKeyboard) return;
  // Debian's ImGui 1.86 GLFW backend indexes keys by GLFW key code.
  if (ImGui::IsKeyPressed(GLFW_KEY_SPACE, false)) state.run.playing = !state.run.playing;
  if (ImGui::IsKeyPressed(GLFW_KEY_S) || ImGui::IsKeyPressed(GLFW_KEY_RIGHT))
    state.run.request_step(1);
  if (ImGui::IsKeyPressed(GLFW_KEY_R, false)) state.run.request_reset();
  if (ImGui::IsKeyPressed(GLFW_KEY_F, false)) state.frame_request = true;
  if (ImGui::IsKeyPressed(GLFW_KEY_C, false)) state.windows.cameras = !state.windows.cameras;
}

}  // namespace s2sim::viewer
