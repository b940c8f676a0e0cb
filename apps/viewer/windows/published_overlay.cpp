#include "published_overlay.hpp"

#include <imgui.h>

#include <algorithm>

namespace s2sim::viewer {

void collect_published_lines(ViewerState& state) {
  const Annotations& published = state.sim->annotations();
  // A reset or a new simulation starts the numbering again.
  if (published.next_sequence < state.next_published_line) state.next_published_line = 0;
  if (published.next_sequence == state.next_published_line) return;
  for (const Annotations::Line& line : published.lines_from(state.next_published_line)) {
    const bool error = line.text.find("run-time error") != std::string::npos;
    state.log.push_back({line.time_s, line.source + ": " + line.text, error});
  }
  state.next_published_line = published.next_sequence;
  // The log is a window for people: the latest 5000 lines are plenty and bound its memory.
  if (state.log.size() > 5000) state.log.erase(state.log.begin(), state.log.end() - 5000);
}

void draw_published_overlay(ViewerState& state) {
  const Annotations& published = state.sim->annotations();
  const Rect& view = state.layout_rects.world;
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  draw->PushClipRect(ImVec2(view.x, view.y), ImVec2(view.x + view.width, view.y + view.height));

  // Trails: red 2 px polylines, as SimTwo draws them.
  const Mat4 vp =
      state.camera.projection(view.width / std::max(1.0f, view.height)) * state.camera.view();
  auto project = [&](const Vec3& p, ImVec2& out) {
    const Vec4f h =
        vp * Vec4f{static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z), 1};
    if (h.w <= 1e-6f) return false;
    out = ImVec2(view.x + (h.x / h.w * 0.5f + 0.5f) * view.width,
                 view.y + (0.5f - h.y / h.w * 0.5f) * view.height);
    return true;
  };
  for (const auto& trail : published.trails) {
    ImVec2 previous;
    bool has_previous = false;
    for (const Vec3& p : trail.points_m) {
      ImVec2 now;
      const bool visible = project(p, now);
      if (visible && has_previous) draw->AddLine(previous, now, IM_COL32(230, 30, 30, 255), 2.0f);
      previous = now;
      has_previous = visible;
    }
  }

  // HUD: white text at (20, 40) px from the view's corner, over a faint shadow for contrast.
  const std::string hud = published.hud_text();
  if (!hud.empty()) {
    const ImVec2 at(view.x + 20, view.y + 40);
    draw->AddText(ImVec2(at.x + 1, at.y + 1), IM_COL32(0, 0, 0, 200), hud.c_str());
    draw->AddText(at, IM_COL32(255, 255, 255, 255), hud.c_str());
  }
  draw->PopClipRect();
}

}  // namespace s2sim::viewer
