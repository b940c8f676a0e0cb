/// \file
/// The project's SimTwo script and sheet (docs/scripting.md): which file SimTwo's editor would
/// open, whether SimTwo's control block starts on "Script", and `Global.S2Sheet`'s cells.
#include "scene/loading.hpp"
#include "scene/xml.hpp"

#include <cstdlib>

namespace s2sim::scene::detail {
namespace {

/// `LastProjectName` of `[Editor]` in `file`, or empty.
std::string last_project_name(const std::filesystem::path& file) {
  const auto ini = read_ini(file, "Editor");
  if (!ini) return {};
  const auto it = ini->find("LastProjectName");
  return it == ini->end() ? std::string() : it->second;
}

/// SimTwo's control block at start (0 None, 1 Script, 2 Remote): config_Params.ini, else
/// SimTwo.ini, as the other settings (settings.cpp).
int control_block(const std::filesystem::path& folder) {
  for (const char* name : {"config_Params.ini", "SimTwo.ini"}) {
    const auto ini = read_ini(folder / name, "Config");
    if (!ini) continue;
    const auto it = ini->find("RGControlBlock_ItemIndex");
    return it == ini->end() ? 0 : std::atoi(it->second.c_str());
  }
  return 0;
}

/// Whether `file` is there; an over-long name or an unreadable folder (not an exception of the
/// file system library) in `why`.
bool is_file(const std::filesystem::path& file, std::string& why) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(file, ec)) return true;
  if (ec && ec != std::errc::no_such_file_or_directory) why = ec.message();
  return false;
}

void load_sheet(LoadContext& ctx, const std::filesystem::path& file) {
  std::string why;
  if (!is_file(file, why)) return;
  const Element root = read_xml_file(file, ctx.display(file));
  const Element* cells = root.child("cells");
  if (!cells) return;
  for (const Element& c : cells->children) {
    if (c.name != "cell") continue;
    const std::string* r = c.attribute("r");
    const std::string* col = c.attribute("c");
    const std::string* text = c.attribute("text");
    if (!r || !col || !text) continue;
    const int row = std::atoi(r->c_str()), column = std::atoi(col->c_str());
    // Row 0 and column 0 are SimTwo's fixed headers: what a file stores there is not shown.
    if (row <= 0 || column <= 0) continue;
    ctx.scene.sheet.push_back({row, column, *text});
  }
}

}  // namespace

void load_script_and_sheet(LoadContext& ctx, const Reader& reader, const Element* s2sim_script) {
  Scene& scene = ctx.scene;
  const std::filesystem::path& folder = ctx.folder;
  load_sheet(ctx, folder / "Global.S2Sheet");
  if (s2sim_script) {
    const std::string name = reader.text(*s2sim_script, "file", "");
    if (name.empty()) reader.fail(*s2sim_script, "file", "missing script file name");
    const auto file = ctx.resolve(name);
    std::string why;
    if (!is_file(file, why))
      reader.fail(*s2sim_script, "file",
                  why.empty() ? "script file '" + name + "' not found"
                              : "cannot read the script file '" + name + "': " + why);
    scene.script = ScriptRef{file, reader.at(*s2sim_script, "file").str(), true};
    return;
  }
  std::string name, found_by;
  if (!(name = last_project_name(folder / "config_Editor.ini")).empty())
    found_by = "config_Editor.ini [Editor] LastProjectName";
  else if (!(name = last_project_name(folder / "SimTwo.ini")).empty())
    found_by = "SimTwo.ini [Editor] LastProjectName";
  else if (std::string why; is_file(folder / "control.pas", why)) {
    name = "control.pas";
    found_by = "control.pas in the scene folder";
  }
  if (name.empty()) return;
  const auto file = ctx.resolve(name);
  if (std::string why; !is_file(file, why)) {
    ctx.warn(Location{found_by, "", ""},
             "the script '" + name + "' " +
                 (why.empty() ? "does not exist" : "cannot be read: " + why) +
                 "; the project runs without a script");
    return;
  }
  scene.script = ScriptRef{file, found_by, control_block(folder) == 1};
}

}  // namespace s2sim::scene::detail
