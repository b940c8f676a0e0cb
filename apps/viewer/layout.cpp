#include "layout.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::viewer {

void LayoutFractions::clamp() {
  left = std::clamp(left, min_fraction, max_fraction);
  bottom = std::clamp(bottom, min_fraction, max_fraction);
}

TiledLayout compute_layout(float width_px, float height_px, float menu_height_px,
                           float run_height_px, const LayoutFractions& requested, bool run_open,
                           bool left_open, bool bottom_open) {
  LayoutFractions f = requested;
  f.clamp();
  TiledLayout l;
  l.menu = {0, 0, width_px, menu_height_px};
  const float below_menu = std::max(0.0f, height_px - menu_height_px);
  // Whole pixels: ImGui places windows on whole pixels, and the 3-D view must meet them.
  const float left_width = run_open || left_open ? std::round(f.left * width_px) : 0;
  // The Run window keeps its height unless the column is too short, then shares it.
  const float run_height = !run_open   ? 0
                           : left_open ? std::round(std::min(run_height_px, below_menu * 0.5f))
                                       : below_menu;
  if (run_open) l.run = {0, menu_height_px, left_width, run_height};
  if (left_open) l.left = {0, menu_height_px + run_height, left_width, below_menu - run_height};
  const float bottom_height = bottom_open ? std::round(f.bottom * below_menu) : 0;
  if (bottom_open)
    l.bottom = {left_width, height_px - bottom_height, width_px - left_width, bottom_height};
  l.world = {left_width, menu_height_px, width_px - left_width, below_menu - bottom_height};
  return l;
}

}  // namespace s2sim::viewer
