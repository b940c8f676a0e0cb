#include "../script_session.hpp"
#include "windows.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdio>

namespace s2sim::viewer {
namespace {

int count_lines(const std::string& text) {
  return 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

/// The script with a line-number gutter. The text box is as tall as the whole text, so it
/// never scrolls itself: the child around both scrolls them together, and a line's place is
/// its number times the line height.
void draw_text_with_line_numbers(ScriptEditorState& editor) {
  const float line_height = ImGui::GetTextLineHeight();
  const int lines = count_lines(editor.text);
  ImGui::BeginChild("##script text", ImVec2(0, 0), true, ImGuiWindowFlags_HorizontalScrollbar);
  const float padding_y = ImGui::GetStyle().FramePadding.y;
  if (editor.scroll_to_line > 0) {
    const float y = padding_y + (editor.scroll_to_line - 1) * line_height;
    ImGui::SetScrollY(std::max(0.0f, y - ImGui::GetWindowHeight() * 0.3f));
    editor.scroll_to_line = -1;
  }
  const float gutter = ImGui::CalcTextSize("00000").x;
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const float scroll = ImGui::GetScrollY();
  const float visible = ImGui::GetWindowHeight();
  const int first = std::max(1, static_cast<int>((scroll - padding_y) / line_height) + 1);
  const int last = std::min(lines, static_cast<int>((scroll + visible - padding_y) / line_height));
  editor.first_visible_line = first;
  editor.last_visible_line = last;
  for (int line = first; line <= last; ++line) {
    const float y = origin.y + padding_y + (line - 1) * line_height;
    const bool error_line = line == editor.highlight_line;
    if (error_line)
      draw->AddRectFilled(ImVec2(origin.x, y), ImVec2(origin.x + 4000, y + line_height),
                          IM_COL32(150, 40, 40, 110));
    char number[16];
    std::snprintf(number, sizeof number, "%4d", line);
    draw->AddText(ImVec2(origin.x, y),
                  error_line ? IM_COL32(255, 120, 110, 255) : IM_COL32(130, 130, 130, 255), number);
  }
  ImGui::SetCursorScreenPos(ImVec2(origin.x + gutter + 6, origin.y));
  ImGui::PushStyleColor(ImGuiCol_FrameBg, IM_COL32(0, 0, 0, 0));
  const float width = std::max(ImGui::GetContentRegionAvail().x, 800.0f);
  ImGui::InputTextMultiline("##script", &editor.text,
                            ImVec2(width, lines * line_height + 2 * padding_y + line_height),
                            ImGuiInputTextFlags_AllowTabInput);
  ImGui::PopStyleColor();
  ImGui::EndChild();
}

}  // namespace

void draw_script_window(ViewerState& state) {
  // Drawn inside its tab (windows/panels.cpp places it).
  ScriptEditorState& editor = state.script_editor;
  if (editor.file.empty()) {
    ImGui::TextWrapped(
        "This scene has no SimTwo script. A SimTwo project's control.pas (or the file its "
        "config_Editor.ini names, or <s2sim><script file>) opens here; --script-file FILE "
        "names another (docs/scripting.md).");
    return;
  }
  const bool loaded = script_loaded(state);
  const bool running = script_running(state);
  if (button(state, "Compile")) compile_script(state);
  ImGui::SameLine();
  if (button(state, "Run")) run_script(state);
  ImGui::SameLine();
  if (button(state, "Stop")) stop_script(state);
  ImGui::SameLine();
  if (button(state, "Save")) save_script(state);
  ImGui::SameLine();
  if (button(state, "Revert")) {
    editor.text = editor.on_disk;
    editor.status = "reverted";
  }
  ImGui::SameLine();
  ImGui::TextDisabled("%s%s  |  %s", editor.file.filename().string().c_str(),
                      editor.text != editor.on_disk ? " *" : "",
                      running  ? "running"
                      : loaded ? "stopped"
                               : "not running (Compile or Run starts it)");
  if (!editor.status.empty()) ImGui::TextDisabled("%s", editor.status.c_str());
  if (!editor.errors.empty()) {
    const float rows = static_cast<float>(std::min<std::size_t>(editor.errors.size(), 4));
    ImGui::BeginChild(
        "##script errors",
        ImVec2(0, rows * ImGui::GetTextLineHeightWithSpacing() + ImGui::GetStyle().WindowPadding.y),
        false);
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1));
    for (std::size_t i = 0; i < editor.errors.size(); ++i) {
      const ScriptMessage& m = editor.errors[i];
      const std::string label = std::filesystem::path(m.file).filename().string() + ":" +
                                std::to_string(m.line) + ":" + std::to_string(m.column) + ": " +
                                m.text + "##" + std::to_string(i);
      if (ImGui::Selectable(label.c_str(), m.line == editor.highlight_line) && m.line > 0) {
        editor.highlight_line = m.line;
        editor.scroll_to_line = m.line;
      }
    }
    ImGui::PopStyleColor();
    ImGui::EndChild();
  }
  draw_text_with_line_numbers(editor);
}

}  // namespace s2sim::viewer
