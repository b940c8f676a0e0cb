// The Cameras window: the scene's images side by side, each brought up to date only when its
// component wrote a new frame (camera_images.hpp).
#include "camera_images.hpp"
#include "windows.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

namespace s2sim::viewer {
namespace {

/// The last part of a name, with its folder: `front/rgb` of `robots/r/sensors/front/rgb`.
std::string short_name(const std::string& name) {
  const std::size_t last = name.rfind('/');
  if (last == std::string::npos || last == 0) return name;
  const std::size_t before = name.rfind('/', last - 1);
  return before == std::string::npos ? name : name.substr(before + 1);
}

ImU32 packed(const std::array<std::uint8_t, 3>& c) {
  return IM_COL32(c[0], c[1], c[2], 255);
}

/// The false-colour scale beside a distance image, `height_px` tall: near at the top, far at
/// the bottom, and black for no hit. Returns the bar's rectangle.
Rect draw_legend(float near_m, float far_m, bool any_hit, float height_px) {
  ImGui::BeginGroup();
  const ImVec2 at = ImGui::GetCursorScreenPos();
  const float width = ImGui::GetFontSize();
  Rect bar;
  if (any_hit) {
    ImDrawList* draw = ImGui::GetWindowDrawList();
    constexpr int kSteps = 24;
    for (int i = 0; i < kSteps; ++i) {
      const float y0 = at.y + height_px * i / kSteps, y1 = at.y + height_px * (i + 1) / kSteps;
      const ImU32 top = packed(distance_colour(static_cast<float>(i) / kSteps));
      const ImU32 bottom = packed(distance_colour(static_cast<float>(i + 1) / kSteps));
      draw->AddRectFilledMultiColor(ImVec2(at.x, y0), ImVec2(at.x + width, y1), top, top, bottom,
                                    bottom);
    }
    bar = {at.x, at.y, width, height_px};
  }
  ImGui::Dummy(ImVec2(width, height_px));
  ImGui::EndGroup();
  ImGui::SameLine();
  ImGui::BeginGroup();
  if (any_hit) {
    // Near at the top, the scale's middle, far at the bottom (a logarithmic scale).
    const float line = ImGui::GetTextLineHeightWithSpacing();
    const float gap = std::max(0.0f, (height_px - 4 * line) / 2);
    ImGui::Text("%.2f m", near_m);
    ImGui::TextDisabled("near");
    ImGui::Dummy(ImVec2(1, gap - ImGui::GetStyle().ItemSpacing.y));
    ImGui::Text("%.2f m", distance_at_fraction(0.5f, near_m, far_m));
    ImGui::Dummy(ImVec2(1, gap - line - ImGui::GetStyle().ItemSpacing.y));
    ImGui::TextDisabled("far");
    ImGui::Text("%.2f m", far_m);
  } else {
    ImGui::TextUnformatted("nothing\nhit");
  }
  ImGui::EndGroup();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("a logarithmic scale; black: no hit (+infinity)");
  return bar;
}

/// Hovering a pixel: its distance, or the body it belongs to.
void pixel_tooltip(const Simulation& sim, const CameraImage& c, const ImVec2& min,
                   const ImVec2& size) {
  if (!ImGui::IsItemHovered()) return;
  const Image& image = sim.image(c.name);
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const int x = std::clamp(static_cast<int>((mouse.x - min.x) / size.x * image.width_px), 0,
                           image.width_px - 1);
  const int y = std::clamp(static_cast<int>((mouse.y - min.y) / size.y * image.height_px), 0,
                           image.height_px - 1);
  if (c.view == ImageView::ids) {
    const std::uint16_t id = id_at(image, x, y);
    if (id == kNoBodyId)
      ImGui::SetTooltip("(%d, %d) sky", x, y);
    else if (static_cast<int>(id) < sim.body_count())
      ImGui::SetTooltip("(%d, %d) body %u: %s", x, y, id, sim.body_path(id).c_str());
    else
      ImGui::SetTooltip("(%d, %d) body %u", x, y, id);
  } else if (c.view == ImageView::distance) {
    const float d = distance_at(image, x, y);
    if (std::isfinite(d))
      ImGui::SetTooltip("(%d, %d) %.3f m", x, y, d);
    else
      ImGui::SetTooltip("(%d, %d) no hit", x, y);
  }
}

/// One image: caption, the picture scaled to `height_px`, its legend.
void draw_image(const Simulation& sim, CameraImage& c, float height_px) {
  refresh_camera_image(sim, c);
  const ShownImage& s = c.shown_image;
  // A wide image (a lidar's range: thousands of steps by a few channels) is squeezed to at
  // most three times as wide as high: its pixels are then not square.
  const float aspect = static_cast<float>(s.width_px) / std::max(1, s.height_px);
  const float h = std::max(16.0f, height_px);
  const ImVec2 size(std::min(h * aspect, std::max(3 * h, 320.0f)), h);
  ImGui::BeginGroup();
  ImGui::Text("%s  frame %llu, %.2f s", short_name(c.name).c_str(),
              static_cast<unsigned long long>(c.frame), c.time_s);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", c.name.c_str());
  // Full opacity: the pixels as the camera gave them, not blended with the window.
  ImGui::PushStyleVar(ImGuiStyleVar_Alpha, 1.0f);
  ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(c.texture.id())), size);
  ImGui::PopStyleVar();
  const ImVec2 min = ImGui::GetItemRectMin();
  c.drawn = {min.x, min.y, size.x, size.y};
  pixel_tooltip(sim, c, min, size);
  if (c.view == ImageView::distance) {
    ImGui::SameLine();
    c.legend = draw_legend(s.near_m, s.far_m, s.any_hit, size.y);
  }
  ImGui::EndGroup();
}

void draw_cloud_entry(const Simulation& sim, CameraImage& c, bool in_world) {
  refresh_camera_image(sim, c);
  ImGui::BeginGroup();
  ImGui::Text("%s  frame %llu, %.2f s", short_name(c.name).c_str(),
              static_cast<unsigned long long>(c.frame), c.time_s);
  if (c.sensor < 0)
    ImGui::TextWrapped("a point cloud of a sensor with no place in the scene: not drawn");
  else if (!in_world)
    ImGui::TextDisabled("%zu points (not drawn: see the box on the left)", c.cloud_m.size());
  else
    ImGui::Text(
        "%zu points, drawn in the 3-D view\n%.2f m (red) to %.2f m (blue),\na logarithmic scale",
        c.cloud_m.size(), c.cloud_near_m, c.cloud_far_m);
  ImGui::EndGroup();
}

}  // namespace

void draw_camera_window(ViewerState& state) {
  sync_camera_images(state);
  CameraWindowState& cams = state.cameras;
  if (cams.images.empty()) {
    ImGui::TextWrapped("This scene has no camera or lidar images (docs/models/sensors.md).");
    return;
  }
  // The list on the left, the images shown to its right.
  const float list_width = ImGui::GetFontSize() * 13;
  ImGui::BeginChild("##camera images list", ImVec2(list_width, 0), true);
  for (CameraImage& c : cams.images) {
    ImGui::PushID(c.name.c_str());
    ImGui::Checkbox(short_name(c.name).c_str(), &c.shown);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", c.name.c_str());
    ImGui::PopID();
  }
  ImGui::Separator();
  ImGui::Checkbox("clouds in 3-D view", &cams.cloud_in_world);
  ImGui::EndChild();
  ImGui::SameLine();
  ImGui::BeginChild("##camera images", ImVec2(0, 0), false, ImGuiWindowFlags_HorizontalScrollbar);
  // Room for the caption above each image and the horizontal scroll bar.
  const float height = ImGui::GetContentRegionAvail().y - ImGui::GetTextLineHeightWithSpacing() -
                       ImGui::GetStyle().ScrollbarSize - ImGui::GetStyle().ItemSpacing.y;
  bool first = true;
  for (CameraImage& c : cams.images) {
    if (!c.shown) continue;
    if (!first) ImGui::SameLine(0, ImGui::GetStyle().ItemSpacing.x * 3);
    first = false;
    if (c.view == ImageView::points)
      draw_cloud_entry(*state.sim, c, cams.cloud_in_world);
    else
      draw_image(*state.sim, c, height);
  }
  if (first) ImGui::TextDisabled("tick an image on the left to show it");
  ImGui::EndChild();
}

}  // namespace s2sim::viewer
