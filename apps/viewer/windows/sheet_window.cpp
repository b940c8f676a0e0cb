#include "windows.hpp"

#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <map>
#include <optional>

namespace s2sim::viewer {
namespace {

constexpr std::string_view kPrefix = "sheet/";

struct CellAddress {
  int column;  ///< 0 = A
  int row;     ///< 1-based
};

/// "B3" -> column 1, row 3; nullopt for anything else.
std::optional<CellAddress> parse_cell(std::string_view name) {
  std::size_t i = 0;
  int column = 0;
  while (i < name.size() && std::isalpha(static_cast<unsigned char>(name[i])))
    column = column * 26 + (std::toupper(static_cast<unsigned char>(name[i++])) - 'A' + 1);
  if (i == 0 || i == name.size() || column > 26 * 27) return std::nullopt;
  int row = 0;
  for (; i < name.size(); ++i) {
    if (!std::isdigit(static_cast<unsigned char>(name[i])) || row > 100000) return std::nullopt;
    row = row * 10 + (name[i] - '0');
  }
  if (row < 1) return std::nullopt;
  return CellAddress{column - 1, row};
}

std::string column_name(int column) {
  std::string s;
  for (int c = column + 1; c > 0; c = (c - 1) / 26)
    s.insert(s.begin(), static_cast<char>('A' + (c - 1) % 26));
  return s;
}

/// One cell: a button for a `button` input (pressing sets 1; the controller sets it back to
/// 0 when it has acted), an editable number otherwise.
void cell_widget(ViewerState& state, std::size_t input, const std::string& label) {
  Simulation& sim = *state.sim;
  const SignalInfo& info = sim.input_info(input);
  ImGui::PushID(static_cast<int>(input));
  if (info.unit == "button") {
    // Pressed and not yet acted on: highlighted (the script's RCButtonPressed clears it).
    const bool down = sim.input(input) != 0;
    if (down) ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.8f, 0.5f, 0.1f, 1));
    if (button(state, label.c_str())) sim.set_input(input, sim.input(input) + 1);
    if (down) ImGui::PopStyleColor();
  } else {
    double value = sim.input(input);
    ImGui::SetNextItemWidth(-1);
    if (ImGui::InputDouble("##v", &value, 0, 0, "%.6g", ImGuiInputTextFlags_EnterReturnsTrue)) {
      try {
        sim.set_input(input, value);
      } catch (const std::exception& e) {  // outside the input's range: said, nothing set
        state.log_message(e.what(), true);
      }
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s [%s]", info.name.c_str(), info.unit.c_str());
  }
  ImGui::PopID();
}

bool is_number(const std::string& text) {
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  while (end && *end == ' ')
    ++end;
  return end != text.c_str() && end && *end == '\0';
}

/// SimTwo's caption of a button cell: "[Set]" -> "Set".
std::string button_caption(const std::string& text) {
  const auto open = text.find('['), close = text.rfind(']');
  if (open == std::string::npos || close == std::string::npos || close <= open) return text;
  return text.substr(open + 1, close - open - 1);
}

}  // namespace

void draw_sheet_window(ViewerState& state) {
  // Drawn inside its tab (windows/panels.cpp places it).
  Simulation& sim = *state.sim;
  std::vector<std::pair<CellAddress, std::size_t>> cells;
  std::vector<std::size_t> others;
  int columns = 0, rows = 0;
  // SimTwo's Global.S2Sheet: the texts of its cells (numbers and buttons are also inputs).
  std::map<std::pair<int, int>, std::string> texts;  // (row, column from 0)
  for (const scene::SheetCell& cell : sim.scene().sheet) {
    if (cell.row < 1 || cell.col < 1 || cell.text.empty()) continue;
    texts[{cell.row, cell.col - 1}] = cell.text;
    columns = std::max(columns, cell.col);
    rows = std::max(rows, cell.row);
  }
  for (std::size_t i = 0; i < sim.input_count(); ++i) {
    const std::string& name = sim.input_info(i).name;
    if (name.compare(0, kPrefix.size(), kPrefix) != 0) continue;
    if (const auto cell = parse_cell(std::string_view(name).substr(kPrefix.size()))) {
      cells.push_back({*cell, i});
      columns = std::max(columns, cell->column + 1);
      rows = std::max(rows, cell->row);
    } else {
      others.push_back(i);
    }
  }
  if (cells.empty() && others.empty() && texts.empty()) {
    ImGui::TextWrapped(
        "No sheet cells in this scene. A controller makes a cell by declaring the input "
        "`sheet/<cell>` (e.g. `sheet/B3`) with declare_input_at(); it reads and writes it with "
        "ctx.input()/ctx.set_input(). Unit \"button\" shows a button (see docs/viewer.md).");
    return;
  }
  columns = std::min(columns, 26);
  rows = std::min(rows, 200);
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                ImGuiTableFlags_ScrollX | ImGuiTableFlags_ScrollY;
  if (columns > 0 && ImGui::BeginTable("cells", columns + 1, flags)) {
    ImGui::TableSetupScrollFreeze(1, 1);
    ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed, 30);
    for (int c = 0; c < columns; ++c)
      ImGui::TableSetupColumn(column_name(c).c_str(), ImGuiTableColumnFlags_WidthFixed, 90);
    ImGui::TableHeadersRow();
    for (int r = 1; r <= rows; ++r) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextDisabled("%d", r);
      for (int c = 0; c < columns; ++c) {
        ImGui::TableNextColumn();
        const std::string name = column_name(c) + std::to_string(r);
        const auto text = texts.find({r, c});
        bool drawn = false;
        // A text that is not a number (a label) is shown as text, not as its input's 0.
        const bool label = text != texts.end() && !is_number(text->second) &&
                           text->second.find('[') == std::string::npos;
        for (const auto& [address, input] : cells)
          if (!label && address.column == c && address.row == r) {
            // A button shows SimTwo's caption; "##B3" keeps equal captions apart.
            const bool is_button = sim.input_info(input).unit == "button";
            cell_widget(state, input,
                        is_button && text != texts.end()
                            ? button_caption(text->second) + "##" + name
                            : name);
            drawn = true;
          }
        if (!drawn && text != texts.end()) ImGui::TextUnformatted(text->second.c_str());
      }
    }
    ImGui::EndTable();
  }
  for (std::size_t input : others) {
    ImGui::TextUnformatted(sim.input_info(input).name.c_str() + kPrefix.size());
    ImGui::SameLine(160);
    cell_widget(state, input, sim.input_info(input).name.substr(kPrefix.size()));
  }
}

}  // namespace s2sim::viewer
