#include "point_cloud_overlay.hpp"

#include "camera_images.hpp"

#include <imgui.h>

#include <algorithm>

namespace s2sim::viewer {
namespace {
constexpr std::size_t kMaxPointsDrawn = 100000;
}  // namespace

void draw_point_cloud_overlay(ViewerState& state) {
  if (!state.windows.cameras || !state.cameras.cloud_in_world) return;
  const Rect& view = state.layout_rects.world;
  if (view.area() <= 0) return;
  sync_camera_images(state);
  const Mat4 vp =
      state.camera.projection(view.width / std::max(1.0f, view.height)) * state.camera.view();
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  draw->PushClipRect(ImVec2(view.x, view.y), ImVec2(view.x + view.width, view.y + view.height));
  const float half = 1.0f;  // a point is a square of two pixels
  for (CameraImage& c : state.cameras.images) {
    if (!c.shown || c.view != ImageView::points || c.sensor < 0) continue;
    // Also when the window's tab is hidden behind another: the cloud follows the scans.
    refresh_camera_image(*state.sim, c);
    // At most kMaxPointsDrawn dots a cloud (every k-th point beyond), bounding the frame's
    // draw data whatever the lidar's size.
    const std::size_t every = c.cloud_m.size() / kMaxPointsDrawn + 1;
    for (std::size_t i = 0; i < c.cloud_m.size(); i += every) {
      const Vec3f& p = c.cloud_m[i];
      const Vec4f h = vp * Vec4f{p.x, p.y, p.z, 1};
      if (h.w <= 1e-6f) continue;  // behind the eye
      const float x = view.x + (h.x / h.w * 0.5f + 0.5f) * view.width;
      const float y = view.y + (0.5f - h.y / h.w * 0.5f) * view.height;
      draw->AddRectFilled(ImVec2(x - half, y - half), ImVec2(x + half, y + half),
                          c.cloud_colours[i]);
    }
  }
  draw->PopClipRect();
}

}  // namespace s2sim::viewer
