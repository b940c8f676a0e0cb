#include "script_session.hpp"

#include <s2sim/error.hpp>

#include <fstream>
#include <optional>
#include <regex>
#include <sstream>

namespace s2sim::viewer {
namespace {

constexpr const char* kRunningInput = "controllers/script/running";

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::filesystem::file_time_type mtime_of(const std::filesystem::path& path) {
  std::error_code ec;
  const auto t = std::filesystem::last_write_time(path, ec);
  return ec ? std::filesystem::file_time_type{} : t;
}

/// The script file the options and the scene name, empty without one.
std::filesystem::path script_path(const ViewerState& state) {
  const auto& scene = state.sim->scene();
  if (!state.options.script_file.empty()) {
    std::filesystem::path p = state.options.script_file;
    return p.is_absolute() ? p : scene.folder / p;
  }
  if (scene.script) return scene.script->file;
  return {};
}

void read_into_editor(ScriptEditorState& editor, const std::filesystem::path& file) {
  editor.file = file;
  editor.text = editor.on_disk = read_text(file);
  editor.mtime = mtime_of(file);
}

std::optional<std::size_t> running_input(const Simulation& sim) {
  for (std::size_t i = 0; i < sim.input_count(); ++i)
    if (sim.input_info(i).name == kRunningInput) return i;
  return std::nullopt;
}

}  // namespace

std::vector<ScriptMessage> parse_script_messages(const std::string& output) {
  static const std::regex located(R"(^(.*\.(?:pas|pp|inc)):(\d+):(\d+): (.*)$)", std::regex::icase);
  std::vector<ScriptMessage> out;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) {
    // The kernel may prefix the first line with the component that threw: keep the file part.
    std::smatch m;
    if (!std::regex_match(line, m, located)) continue;
    std::string file = m[1].str();
    if (const auto space = file.rfind(' '); space != std::string::npos)
      file = file.substr(space + 1);
    out.push_back({file, std::stoi(m[2].str()), std::stoi(m[3].str()), m[4].str()});
  }
  return out;
}

std::unique_ptr<Simulation> load_simulation_keeping_script_errors(ViewerState& state,
                                                                  const Options& options) {
  try {
    auto sim = load_simulation(options);
    state.script_editor.errors.clear();
    return sim;
  } catch (const Error& e) {
    auto messages = parse_script_messages(e.what());
    if (e.kind() != ErrorKind::scene || messages.empty() || options.script_mode == ScriptMode::off)
      throw;
    state.script_editor.errors = std::move(messages);
    state.script_editor.status = "the script does not compile: the scene runs without it";
    state.windows.script = state.windows.script || !state.options.hide_ui;
    state.log_message("script: " + std::string(e.what()), true);
    state.log_message("script: the scene runs without its script (fix it in the Script window)",
                      true);
    Options without = options;
    without.script_mode = ScriptMode::off;
    without.script_file.clear();
    return load_simulation(without);
  }
}

void open_scene_script(ViewerState& state) {
  ScriptEditorState& editor = state.script_editor;
  const std::filesystem::path file = script_path(state);
  if (file.empty()) {
    editor = ScriptEditorState{};
    return;
  }
  if (file != editor.file || editor.text == editor.on_disk) read_into_editor(editor, file);
}

void reload_script_if_changed(ViewerState& state) {
  ScriptEditorState& editor = state.script_editor;
  if (editor.file.empty()) return;
  const auto now = mtime_of(editor.file);
  if (now == editor.mtime) return;
  if (editor.text != editor.on_disk) {
    editor.status = "the file changed on disk; Save overwrites it, Revert reads it";
    editor.mtime = now;  // said once
    return;
  }
  read_into_editor(editor, editor.file);
  editor.status = "reloaded: the file changed on disk";
  state.log_message("script: " + editor.file.string() + " changed on disk, reloaded");
}

bool save_script(ViewerState& state) {
  ScriptEditorState& editor = state.script_editor;
  if (editor.file.empty()) return false;
  std::ofstream out(editor.file, std::ios::binary);
  out << editor.text;
  out.close();
  if (!out) {
    editor.status = "cannot write " + editor.file.string();
    state.log_message("script: " + editor.status, true);
    return false;
  }
  editor.on_disk = editor.text;
  editor.mtime = mtime_of(editor.file);
  editor.status = "saved";
  return true;
}

bool compile_script(ViewerState& state) {
  ScriptEditorState& editor = state.script_editor;
  if (editor.file.empty()) return false;
  if (editor.text != editor.on_disk && !save_script(state)) return false;
  Options options = state.options;
  options.script_mode = ScriptMode::always;
  // The project's own script is found as the project names it (the messages say how).
  const auto& scene = state.sim->scene();
  if (!scene.script || scene.script->file != editor.file)
    options.script_file = editor.file.string();
  editor.errors.clear();
  editor.highlight_line = -1;
  try {
    auto sim = load_simulation(options);
    state.pending_simulation = std::move(sim);
    state.options = options;  // later reloads (scene editor, Configuration) keep the script
    editor.status = "compiled: the simulation restarted with it";
    state.log_message("script: compiled " + editor.file.string());
    return true;
  } catch (const std::exception& e) {
    editor.errors = parse_script_messages(e.what());
    if (editor.errors.empty())  // not a compile error: show the whole message
      editor.errors.push_back({editor.file.filename().string(), 0, 0, e.what()});
    else {
      editor.highlight_line = editor.errors.front().line;
      editor.scroll_to_line = editor.highlight_line;
    }
    editor.status = "not compiled: the running simulation is kept";
    state.log_message("script: " + std::string(e.what()), true);
    return false;
  }
}

bool script_loaded(const ViewerState& state) {
  return state.sim && running_input(*state.sim).has_value();
}

bool script_running(const ViewerState& state) {
  if (!state.sim) return false;
  const auto input = running_input(*state.sim);
  return input && state.sim->input(*input) != 0 &&
         state.sim->find_signal("controllers/script/error") &&
         state.sim->signal("controllers/script/error") == 0;
}

void run_script(ViewerState& state) {
  const auto input = state.sim ? running_input(*state.sim) : std::nullopt;
  if (!input) {
    compile_script(state);
    return;
  }
  // A new non-zero value starts the script afresh at its next tick (the plugin's Run).
  const double last = state.sim->input(*input);
  state.sim->set_input(*input, last >= 1 ? last + 1 : 1);
  state.script_editor.status = "running";
}

void stop_script(ViewerState& state) {
  if (const auto input = state.sim ? running_input(*state.sim) : std::nullopt) {
    state.sim->set_input(*input, 0);
    state.script_editor.status = "stopped";
  }
}

}  // namespace s2sim::viewer
