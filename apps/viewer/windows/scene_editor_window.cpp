#include "windows.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <s2sim/error.hpp>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

namespace s2sim::viewer {
namespace {

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  return static_cast<bool>(out);
}

/// "scene.xml:12" -> ("scene.xml", 12); no number -> (file, -1).
std::pair<std::string, int> split_line(const std::string& file) {
  const auto colon = file.rfind(':');
  if (colon == std::string::npos || colon + 1 == file.size()) return {file, -1};
  const std::string digits = file.substr(colon + 1);
  if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return {file, -1};
  return {file.substr(0, colon), std::stoi(digits)};
}

std::string line_of(const std::string& text, int line) {
  std::istringstream in(text);
  std::string s;
  for (int i = 1; std::getline(in, s); ++i)
    if (i == line) return s;
  return {};
}

}  // namespace

void load_editor_files(ViewerState& state) {
  const scene::Scene& scene = state.sim->scene();
  std::set<std::filesystem::path> paths;
  std::vector<std::filesystem::path> ordered{scene.file};
  paths.insert(scene.file);
  for (const auto& r : scene.robots)
    if (!r.file.empty() && paths.insert(r.file).second) ordered.push_back(r.file);
  // Things, obstacles, tracks... live in other XML files of the folder.
  std::vector<std::filesystem::path> others;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(scene.folder, ec))
    if (entry.path().extension() == ".xml" && paths.insert(entry.path()).second)
      others.push_back(entry.path());
  std::sort(others.begin(), others.end());
  ordered.insert(ordered.end(), others.begin(), others.end());

  EditorState& editor = state.editor;
  const std::string current =
      editor.files.empty() ? std::string() : editor.files[editor.current].path.string();
  editor.files.clear();
  editor.current = 0;
  for (const auto& p : ordered) {
    const std::string text = read_file(p);
    editor.files.push_back({p, text, text});
    if (p.string() == current) editor.current = static_cast<int>(editor.files.size()) - 1;
  }
}

bool apply_editor(ViewerState& state) {
  EditorState& editor = state.editor;
  std::vector<EditorFile*> changed;
  for (auto& f : editor.files)
    if (f.text != f.on_disk) changed.push_back(&f);
  for (EditorFile* f : changed)
    if (!write_file(f->path, f->text)) {
      editor.error = "cannot write " + f->path.string();
      state.log_message("scene editor: " + editor.error, true);
      return false;
    }
  try {
    state.pending_simulation = load_simulation(state.options);
    for (EditorFile* f : changed)
      f->on_disk = f->text;
    editor.error.clear();
    editor.error_line = -1;
    editor.error_file.clear();
    editor.status = "applied: scene reloaded";
    state.log_message("scene editor: scene reloaded");
    return true;
  } catch (const std::exception& e) {
    // Keep the running scene and the files it came from; the edited text stays in the editor
    // for fixing.
    for (EditorFile* f : changed)
      write_file(f->path, f->on_disk);
    editor.error = e.what();
    editor.error_message = e.what();
    editor.error_line = -1;
    editor.error_file.clear();
    if (const auto* error = dynamic_cast<const Error*>(&e)) {
      const auto [file, line] = split_line(error->where().file);
      editor.error_file = file;
      editor.error_line = line;
      if (line > 0) editor.error_message = error->message();
    }
    editor.status = "not applied: the running scene is kept";
    state.log_message("scene editor: " + editor.error, true);
    return false;
  }
}

void draw_scene_editor_window(ViewerState& state) {
  // Drawn inside its tab (windows/panels.cpp places it).
  EditorState& editor = state.editor;
  if (editor.files.empty()) load_editor_files(state);
  const auto& folder = state.sim->scene().folder;
  auto display = [&](const EditorFile& f) {
    const auto relative = f.path.lexically_relative(folder);
    std::string name = relative.empty() ? f.path.string() : relative.string();
    if (f.text != f.on_disk) name += " *";
    return name;
  };
  ImGui::SetNextItemWidth(300);
  if (ImGui::BeginCombo("file", display(editor.files[editor.current]).c_str())) {
    for (int i = 0; i < static_cast<int>(editor.files.size()); ++i)
      if (ImGui::Selectable(display(editor.files[i]).c_str(), i == editor.current))
        editor.current = i;
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  if (button(state, "Apply")) apply_editor(state);
  ImGui::SameLine();
  if (button(state, "Revert")) {
    for (auto& f : editor.files)
      f.text = f.on_disk;
    editor.error.clear();
    editor.status = "reverted";
  }
  if (!editor.error.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1));
    if (editor.error_line > 0)
      ImGui::TextWrapped("%s, line %d: %s", editor.error_file.c_str(), editor.error_line,
                         editor.error_message.c_str());
    else
      ImGui::TextWrapped("%s", editor.error.c_str());
    ImGui::PopStyleColor();
    if (editor.error_line > 0)
      for (const auto& f : editor.files)
        if (f.path.filename() == std::filesystem::path(editor.error_file).filename())
          ImGui::TextDisabled("%4d | %s", editor.error_line,
                              line_of(f.text, editor.error_line).c_str());
  }
  if (!editor.status.empty()) ImGui::TextDisabled("%s", editor.status.c_str());
  ImGui::InputTextMultiline("##text", &editor.files[editor.current].text, ImVec2(-1, -1),
                            ImGuiInputTextFlags_AllowTabInput);
}

}  // namespace s2sim::viewer
