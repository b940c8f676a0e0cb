#include "windows.hpp"

#include <imgui.h>

namespace s2sim::viewer {

void draw_log_window(ViewerState& state) {
  // Drawn inside its tab (windows/panels.cpp places it).
  if (button(state, "Clear log")) state.log.clear();
  ImGui::Separator();
  // Lines wrap at the window's width: a narrow column shows every word of them.
  ImGui::BeginChild("lines", ImVec2(0, 0), false);
  ImGui::PushTextWrapPos(0.0f);
  for (const auto& line : state.log) {
    const ImVec4 colour = line.error ? ImVec4(1.0f, 0.45f, 0.4f, 1) : ImVec4(0.9f, 0.9f, 0.9f, 1);
    ImGui::PushStyleColor(ImGuiCol_Text, colour);
    ImGui::Text("[%8.3f s] %s", line.time_s, line.text.c_str());
    ImGui::PopStyleColor();
  }
  ImGui::PopTextWrapPos();
  // Follow new lines unless the user scrolled up to read older ones.
  if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY()) ImGui::SetScrollHereY(1.0f);
  ImGui::EndChild();
}

}  // namespace s2sim::viewer
