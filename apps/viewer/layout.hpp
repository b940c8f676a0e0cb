#pragma once
/// \file
/// The tiled layout (Dear ImGui 1.86 has no docking): a menu bar on top, a left column with the
/// Run window over a tab group, a bottom row with another tab group, and the 3-D view in the
/// remaining central region. The columns resize with the window (they are fractions of it)
/// and are clamped so that the 3-D view always keeps at least half of the window.

namespace s2sim::viewer {

/// Pixels from the window's top left.
struct Rect {
  float x = 0, y = 0, width = 0, height = 0;
  float area() const { return width * height; }
  bool overlaps(const Rect& o) const {
    return x < o.x + o.width && o.x < x + width && y < o.y + o.height && o.y < y + height;
  }
};

/// What the user sets by dragging the column borders (saved in the ImGui ini file).
struct LayoutFractions {
  static constexpr float default_left = 0.25f, default_bottom = 0.30f;
  /// Limits keep the 3-D view at least (1 - 0.28) * (1 - 0.28) > 0.5 of what is under the menu.
  static constexpr float min_fraction = 0.12f, max_fraction = 0.28f;
  float left = default_left;      ///< left column width / window width
  float bottom = default_bottom;  ///< bottom row height / height under the menu bar
  void clamp();
};

struct TiledLayout {
  Rect menu, run, left, bottom, world;
};

/// The rectangles for a window of `width_px` x `height_px`. A column without panels takes no
/// room (`run_open`, `left_open`, `bottom_open`); `menu_height_px` 0 means no menu bar.
TiledLayout compute_layout(float width_px, float height_px, float menu_height_px,
                           float run_height_px, const LayoutFractions& fractions, bool run_open,
                           bool left_open, bool bottom_open);

}  // namespace s2sim::viewer
