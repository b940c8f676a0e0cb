#include "windows.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <s2sim/error.hpp>

#include <unistd.h>

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

namespace {

/// A scratch copy of the scene's folder in which the edited files replace the originals and
/// every other entry is a symbolic link to the original (meshes, textures, SimTwo's ini
/// files): the edit is loaded there before anything is written. Removed on destruction.
struct ScratchScene {
  std::filesystem::path root, folder;
  ScratchScene(const std::filesystem::path& scene_folder,
               const std::vector<const EditorFile*>& changed) {
    namespace fs = std::filesystem;
    root = fs::temp_directory_path() /
           ("s2sim-view-edit-" + std::to_string(::getpid()) + "-" + std::to_string(++count()));
    folder = root / scene_folder.filename();
    fs::remove_all(root);
    fs::create_directories(folder);
    for (const auto& entry : fs::directory_iterator(scene_folder)) {
      const bool edited = std::any_of(changed.begin(), changed.end(),
                                      [&](const EditorFile* f) { return f->path == entry.path(); });
      if (!edited) fs::create_symlink(entry.path(), folder / entry.path().filename());
    }
    for (const EditorFile* f : changed) {
      // Files of the scene outside its folder (a robot file elsewhere) are checked in place
      // only after the write: the scratch copy holds the folder's files.
      if (f->path.parent_path() != scene_folder) continue;
      if (!write_file(folder / f->path.filename(), f->text))
        throw Error(ErrorKind::runtime, "cannot write the scratch copy in " + root.string());
    }
  }
  ~ScratchScene() {
    std::error_code ignored;
    std::filesystem::remove_all(root, ignored);
  }
  static int& count() {
    static int n = 0;
    return n;
  }
  /// The message with the scratch folder's paths turned back into the scene's.
  std::string unscratch(std::string text, const std::filesystem::path& scene_folder) const {
    const std::string from = folder.string(), to = scene_folder.string();
    for (std::size_t at; (at = text.find(from)) != std::string::npos;)
      text.replace(at, from.size(), to);
    return text;
  }
};

/// Writes `text` to `path` through a temporary file renamed over it, so a crash mid-write
/// never leaves half a file.
bool replace_file(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path temporary = path.string() + ".s2sim-new";
  if (!write_file(temporary, text)) return false;
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  return !ec;
}

void show_error(ViewerState& state, const std::exception& e, const std::string& text) {
  EditorState& editor = state.editor;
  editor.error = text;
  editor.error_message = text;
  editor.error_line = -1;
  editor.error_file.clear();
  if (const auto* error = dynamic_cast<const Error*>(&e)) {
    const auto [file, line] = split_line(error->where().file);
    editor.error_file = file;
    editor.error_line = line;
    if (line > 0) editor.error_message = error->message();
  }
  editor.status = "not applied: the files are untouched and the running scene is kept";
  state.log_message("scene editor: " + editor.error, true);
}

}  // namespace

bool apply_editor(ViewerState& state) {
  EditorState& editor = state.editor;
  std::vector<EditorFile*> changed;
  for (auto& f : editor.files)
    if (f.text != f.on_disk) changed.push_back(&f);
  const std::filesystem::path folder = state.sim->scene().folder;
  // 1. Load the edit in a scratch copy of the folder: a refused edit touches no file.
  try {
    const ScratchScene scratch(folder, {changed.begin(), changed.end()});
    Options options = state.options;
    options.scene = (scratch.folder / state.sim->scene().file.filename()).string();
    options.script_mode = ScriptMode::off;  // the script is the Script window's business
    options.script_file.clear();
    try {
      (void)load_simulation(options);
    } catch (const Error& e) {
      const std::string file = scratch.unscratch(e.where().file, folder);
      const Error located(e.kind(), Location{file, e.where().element, e.where().attribute},
                          scratch.unscratch(e.message(), folder));
      show_error(state, located, located.what());
      return false;
    }
  } catch (const std::exception& e) {
    show_error(state, e, e.what());
    return false;
  }
  // 2. Keep the previous version (`scene.xml~`), then write.
  for (EditorFile* f : changed) {
    std::error_code ec;
    std::filesystem::copy_file(f->path, f->path.string() + "~",
                               std::filesystem::copy_options::overwrite_existing, ec);
    if (ec || !replace_file(f->path, f->text)) {
      editor.error = "cannot write " + f->path.string() + (ec ? " (nor its backup)" : "");
      state.log_message("scene editor: " + editor.error, true);
      return false;
    }
  }
  // 3. Load it for real (it loaded in the scratch copy; a file outside the folder may differ).
  try {
    state.pending_simulation = load_simulation_keeping_script_errors(state, state.options);
    for (EditorFile* f : changed)
      f->on_disk = f->text;
    editor.error.clear();
    editor.error_line = -1;
    editor.error_file.clear();
    editor.status = "applied: scene reloaded (the previous files are kept as NAME~)";
    state.log_message("scene editor: scene reloaded");
    return true;
  } catch (const std::exception& e) {
    for (EditorFile* f : changed)
      replace_file(f->path, f->on_disk);
    show_error(state, e, e.what());
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
