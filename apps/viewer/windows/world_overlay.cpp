#include "world_overlay.hpp"

#include <imgui.h>

#include <cmath>
#include <cstdio>

namespace s2sim::viewer {
namespace {

/// World point to window pixels through the 3-D view; false behind the eye.
struct Projector {
  Mat4 view_projection;
  Rect view;
  bool operator()(const Vec3f& p, ImVec2& out) const {
    const Vec4f h = view_projection * Vec4f{p.x, p.y, p.z, 1};
    if (h.w <= 1e-6f) return false;
    out = ImVec2(view.x + (h.x / h.w * 0.5f + 0.5f) * view.width,
                 view.y + (0.5f - h.y / h.w * 0.5f) * view.height);
    return true;
  }
};

ImU32 robot_colour(std::size_t r) {
  static const ImU32 palette[] = {IM_COL32(230, 60, 40, 255),  IM_COL32(40, 120, 230, 255),
                                  IM_COL32(40, 170, 60, 255),  IM_COL32(200, 140, 0, 255),
                                  IM_COL32(150, 60, 200, 255), IM_COL32(0, 160, 170, 255)};
  return palette[r % std::size(palette)];
}

/// 1, 2 or 5 times a power of ten, the largest not over `limit`.
double nice_length(double limit) {
  const double power = std::pow(10.0, std::floor(std::log10(limit)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * power <= limit) return m * power;
  return power;
}

}  // namespace

void record_trails(ViewerState& state) {
  const auto& robots = state.sim->scene().robots;
  if (state.trails.robots() != robots.size()) state.trails.reset(robots.size());
  for (std::size_t r = 0; r < robots.size(); ++r)
    if (robots[r].main_body >= 0)
      state.trails.add(r, state.sim->time_s(),
                       to_f(state.sim->body_pose(robots[r].main_body + 1).position));
}

void draw_world_overlay(const ViewerState& state) {
  const OverlaySettings& o = state.overlay;
  const Rect& view = state.layout_rects.world;
  if (view.area() <= 0) return;
  const Projector project{
      state.camera.projection(view.width / std::max(1.0f, view.height)) * state.camera.view(),
      view};
  // Under every window, over the 3-D view, clipped to it.
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  draw->PushClipRect(ImVec2(view.x, view.y), ImVec2(view.x + view.width, view.y + view.height));
  const auto& robots = state.sim->scene().robots;

  if (o.trails)
    for (std::size_t r = 0; r < state.trails.robots(); ++r) {
      const std::size_t n = state.trails.count(r, o.trail_length_s);
      ImVec2 previous;
      bool have_previous = false;
      for (std::size_t i = 0; i < n; ++i) {
        ImVec2 p;
        const bool visible = project(state.trails.point(r, n, i), p);
        if (visible && have_previous) draw->AddLine(previous, p, robot_colour(r), 2.0f);
        previous = p;
        have_previous = visible;
      }
    }

  if (o.axes) {  // the world's axes at the origin, 1 m long
    ImVec2 origin, tip;
    const Vec3f axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const ImU32 colours[3] = {IM_COL32(220, 40, 40, 255), IM_COL32(30, 160, 40, 255),
                              IM_COL32(40, 70, 230, 255)};
    if (project({0, 0, 0}, origin))
      for (int a = 0; a < 3; ++a)
        if (project(axes[a], tip)) {
          draw->AddLine(origin, tip, colours[a], 2.5f);
          draw->AddText(ImVec2(tip.x + 3, tip.y - 8), colours[a], &"X\0Y\0Z"[2 * a]);
        }
  }

  if (o.labels)
    for (std::size_t r = 0; r < robots.size(); ++r) {
      if (robots[r].main_body < 0) continue;
      ImVec2 p;
      const Vec3f at = to_f(state.sim->body_pose(robots[r].main_body + 1).position);
      if (!project(at + Vec3f{0, 0, 0.05f}, p)) continue;
      const char* id = robots[r].id.c_str();
      const ImVec2 size = ImGui::CalcTextSize(id);
      const ImVec2 corner(p.x - size.x / 2, p.y - size.y - 6);
      draw->AddRectFilled(ImVec2(corner.x - 3, corner.y - 1),
                          ImVec2(corner.x + size.x + 3, corner.y + size.y + 1),
                          IM_COL32(0, 0, 0, 150), 3.0f);
      draw->AddText(corner, IM_COL32(255, 255, 255, 255), id);
    }

  if (o.scale_bar) {  // metres at the distance of the point looked at
    const double metres_per_px = 2 * state.camera.distance_m *
                                 std::tan(state.camera.fov_y_rad / 2) / std::max(1.0f, view.height);
    const double length_m = nice_length(120 * metres_per_px);
    const float length_px = static_cast<float>(length_m / metres_per_px);
    const ImVec2 a(view.x + 16, view.y + view.height - 16);
    const ImVec2 b(a.x + length_px, a.y);
    const ImU32 ink = IM_COL32(20, 20, 20, 255);
    draw->AddLine(a, b, ink, 2.0f);
    draw->AddLine(ImVec2(a.x, a.y - 5), ImVec2(a.x, a.y + 1), ink, 2.0f);
    draw->AddLine(ImVec2(b.x, b.y - 5), ImVec2(b.x, b.y + 1), ink, 2.0f);
    char text[32];
    if (length_m >= 1)
      std::snprintf(text, sizeof text, "%g m", length_m);
    else
      std::snprintf(text, sizeof text, "%g cm", length_m * 100);
    draw->AddText(ImVec2(a.x, a.y - 20), ink, text);
  }
  draw->PopClipRect();
}

}  // namespace s2sim::viewer
