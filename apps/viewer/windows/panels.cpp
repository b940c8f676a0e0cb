#include "panels.hpp"

#include "../ui_script.hpp"
#include "windows.hpp"

#include <imgui.h>
#include <imgui_internal.h>  // ImGuiSettingsHandler: the layout is saved in the ImGui ini file

#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>

namespace s2sim::viewer {
namespace {

enum class Slot { left, bottom };

struct Panel {
  const char* name;   ///< as `--show-window` and the script's `show` name it
  const char* label;  ///< its tab
  Slot slot;
  bool WindowFlags::*open;
  void (*draw)(ViewerState&);
};

// The tab order.
constexpr Panel kPanels[] = {
    {"configuration", "Configuration", Slot::left, &WindowFlags::configuration,
     draw_configuration_window},
    {"body", "Body", Slot::left, &WindowFlags::body, draw_body_window},
    {"log", "Log", Slot::left, &WindowFlags::log, draw_log_window},
    {"chart", "Chart", Slot::bottom, &WindowFlags::chart, draw_chart_window},
    {"sheet", "Sheet", Slot::bottom, &WindowFlags::sheet, draw_sheet_window},
    {"editor", "Scene editor", Slot::bottom, &WindowFlags::editor, draw_scene_editor_window},
    {"script", "Script", Slot::bottom, &WindowFlags::script, draw_script_window},
    {"cameras", "Cameras", Slot::bottom, &WindowFlags::cameras, draw_camera_window},
};

constexpr ImGuiWindowFlags kFixed =
    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings |
    ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoTitleBar;

bool any_open(const WindowFlags& w, Slot slot) {
  for (const Panel& p : kPanels)
    if (p.slot == slot && w.*p.open) return true;
  return false;
}

void place(const Rect& r) {
  ImGui::SetNextWindowPos(ImVec2(r.x, r.y), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(r.width, r.height), ImGuiCond_Always);
}

/// One column's tab group; a tab opened since the last frame is brought to the front.
void draw_group(ViewerState& state, Slot slot, const Rect& rect, const char* window_name) {
  place(rect);
  // The inner edge resizes the column: the size the user drags to becomes the new fraction.
  if (!ImGui::Begin(window_name, nullptr, kFixed)) {
    ImGui::End();
    return;
  }
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const ImVec2 size = ImGui::GetWindowSize();
  if (slot == Slot::left && std::abs(size.x - rect.width) > 0.5f)
    state.layout.left = size.x / display.x;
  if (slot == Slot::bottom && std::abs(size.y - rect.height) > 0.5f)
    state.layout.bottom = size.y / std::max(1.0f, display.y - state.layout_rects.menu.height);
  state.layout.clamp();
  if (ImGui::BeginTabBar(window_name, ImGuiTabBarFlags_Reorderable)) {
    for (std::size_t i = 0; i < std::size(kPanels); ++i) {
      const Panel& p = kPanels[i];
      bool& open = state.windows.*p.open;
      if (p.slot != slot || !open) continue;
      const bool just_opened = !state.panels_open_last_frame[i];
      if (ImGui::BeginTabItem(p.label, &open, just_opened ? ImGuiTabItemFlags_SetSelected : 0)) {
        ImGui::BeginChild(p.name);
        p.draw(state);
        ImGui::EndChild();
        ImGui::EndTabItem();
      }
    }
    ImGui::EndTabBar();
  }
  ImGui::End();
}

void draw_menu(ViewerState& state) {
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("View")) {
    ImGui::MenuItem("Run", nullptr, &state.windows.run);
    for (const Panel& p : kPanels)
      ImGui::MenuItem(p.label, nullptr, &(state.windows.*p.open));
    ImGui::Separator();
    if (ImGui::MenuItem("Reset layout")) reset_layout(state);
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
}

// The layout in the ImGui ini file, section [S2SimLayout][main].
void* settings_open(ImGuiContext*, ImGuiSettingsHandler* handler, const char* name) {
  return std::strcmp(name, "main") == 0 ? handler->UserData : nullptr;
}
void settings_read_line(ImGuiContext*, ImGuiSettingsHandler*, void* entry, const char* line) {
  auto& state = *static_cast<ViewerState*>(entry);
  float value = 0;
  int flag = 0;
  if (std::sscanf(line, "left=%f", &value) == 1) state.layout.left = value;
  if (std::sscanf(line, "bottom=%f", &value) == 1) state.layout.bottom = value;
  state.layout.clamp();
  char name[32] = {};
  if (std::sscanf(line, "open_%31[a-z]=%d", name, &flag) == 2)
    set_window(state.windows, name, flag != 0);
}
void settings_write_all(ImGuiContext*, ImGuiSettingsHandler* handler, ImGuiTextBuffer* out) {
  const auto& state = *static_cast<const ViewerState*>(handler->UserData);
  out->appendf("[%s][main]\nleft=%.4f\nbottom=%.4f\nopen_run=%d\n", handler->TypeName,
               state.layout.left, state.layout.bottom, state.windows.run ? 1 : 0);
  for (const Panel& p : kPanels)
    out->appendf("open_%s=%d\n", p.name, state.windows.*p.open ? 1 : 0);
  out->append("\n");
}

}  // namespace

void register_layout_settings(ViewerState& state) {
  ImGuiSettingsHandler handler;
  handler.TypeName = "S2SimLayout";
  handler.TypeHash = ImHashStr("S2SimLayout");
  handler.ReadOpenFn = settings_open;
  handler.ReadLineFn = settings_read_line;
  handler.WriteAllFn = settings_write_all;
  handler.UserData = &state;
  ImGui::GetCurrentContext()->SettingsHandlers.push_back(handler);
}

void bring_to_front(ViewerState& state, const std::string& name) {
  for (std::size_t i = 0; i < std::size(kPanels); ++i)
    if (name == kPanels[i].name) state.panels_open_last_frame[i] = false;  // as if just opened
}

void reset_layout(ViewerState& state) {
  state.layout = LayoutFractions{};
  state.windows = WindowFlags{};
}

void update_layout(ViewerState& state, float width_px, float height_px) {
  const bool ui = !state.options.hide_ui;
  const float menu = ui ? ImGui::GetFrameHeight() : 0;
  // The Run window's rows: buttons, speed, time, factor, window toggles, with padding.
  const float run = 6 * ImGui::GetFrameHeightWithSpacing() + 2 * ImGui::GetStyle().WindowPadding.y;
  state.layout_rects =
      compute_layout(width_px, height_px, menu, run, state.layout, state.windows.run,
                     any_open(state.windows, Slot::left), any_open(state.windows, Slot::bottom));
}

void draw_panels(ViewerState& state) {
  const TiledLayout& l = state.layout_rects;
  if (!state.options.hide_ui) draw_menu(state);
  if (state.windows.run) {
    place(l.run);
    draw_run_window(state);
  }
  if (l.left.area() > 0) draw_group(state, Slot::left, l.left, "##left panels");
  if (l.bottom.area() > 0) draw_group(state, Slot::bottom, l.bottom, "##bottom panels");
  for (std::size_t i = 0; i < std::size(kPanels); ++i)
    state.panels_open_last_frame[i] = state.windows.*kPanels[i].open;
}

void print_layout(const ViewerState& state) {
  // What ImGui actually placed (not what the layout asked for), and the 3-D view.
  auto print = [](const char* what, const ImVec2& pos, const ImVec2& size) {
    std::printf("layout %s %.1f %.1f %.1f %.1f\n", what, pos.x, pos.y, size.x, size.y);
  };
  const std::pair<const char*, const char*> windows[] = {{"run", "Run"},
                                                         {"left", "##left panels"},
                                                         {"bottom", "##bottom panels"},
                                                         {"menu", "##MainMenuBar"}};
  for (const auto& [what, name] : windows)
    if (const ImGuiWindow* w = ImGui::FindWindowByName(name); w && w->Active)
      print(what, w->Pos, w->Size);
  const Rect& world = state.layout_rects.world;
  print("world", ImVec2(world.x, world.y), ImVec2(world.width, world.height));
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  print("window", ImVec2(0, 0), display);
  std::fflush(stdout);
}

std::size_t panel_count() {
  return std::size(kPanels);
}

}  // namespace s2sim::viewer
