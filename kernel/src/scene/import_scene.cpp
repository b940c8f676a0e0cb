/// \file
/// Which format a robot file is, and imported robots in a scene: one placed by a SimTwo
/// scene's `<robot><body file='x.urdf'/>`, or a lone URDF, SDF or MJCF file run on the
/// default floor (docs/models/import.md, "Running a robot file").

#include "scene/import_model.hpp"

#include "scene/xml.hpp"

#include <algorithm>
#include <cctype>

namespace s2sim::scene::detail {
namespace {

namespace fs = std::filesystem;

std::string lower_extension(const fs::path& file) {
  std::string e = file.extension().string();
  std::transform(e.begin(), e.end(), e.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

}  // namespace

std::string robot_format(const fs::path& file) {
  const std::string e = lower_extension(file);
  if (e == ".urdf") return "urdf";
  if (e == ".sdf") return "sdf";
  if (e == ".mjcf") return "mjcf";
  if (e != ".xml") return {};
  // An .xml file: the root element says (a SimTwo robot file is a <robot> with <solids>).
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return {};
  Element root;
  try {
    root = read_xml_file(file, file.filename().string());
  } catch (const Error&) {
    return {};  // the SimTwo loader reports the syntax error, located
  }
  if (root.name == "mujoco") return "mjcf";
  if (root.name == "sdf") return "sdf";
  if (root.name == "robot" && root.child("link")) return "urdf";
  return {};
}

namespace {

/// The model of a robot file in `format`; `settings` takes what a lone file sets (MJCF's step).
ImportedModel read_model(const std::string& format, const fs::path& file,
                         const std::string& display, const std::vector<fs::path>& search_path,
                         Settings* settings) {
  if (format == "urdf") return read_urdf(file, display, search_path);
  if (format == "sdf") return read_sdf(file, display, search_path);
  return read_mjcf(file, display, search_path, settings);
}

}  // namespace

void load_imported_robot(LoadContext& ctx, const fs::path& file, const std::string& format,
                         const RobotPlacement& placement) {
  add_imported_robot(ctx, read_model(format, file, ctx.display(file), ctx.model_path, nullptr),
                     placement);
}

Scene load_robot_scene(const fs::path& path, const std::string& format,
                       const LoadOptions& options) {
  const fs::path file = fs::absolute(path).lexically_normal();
  Scene scene;
  scene.file = file;
  scene.folder = file.parent_path();
  // Not a SimTwo file: S2Sim's control semantics, the default step and friction, the floor.
  scene.settings.control_semantics = ControlSemantics::s2sim;
  scene.settings.source = "defaults (" + file.filename().string() + ")";
  for (const auto& [name, value] : options.constants)
    scene.globals.set(name, value);
  LoadContext ctx{scene, scene.folder, {}, {}, model_search_path(options.model_path)};
  RobotPlacement placement;
  placement.where = Location{ctx.display(file), "", ""};
  placement.rest_on_floor = true;
  ImportedModel model =
      read_model(format, file, ctx.display(file), ctx.model_path, &scene.settings);
  placement.id = model.name.empty() ? std::string("robot0") : model.name;
  add_imported_robot(ctx, std::move(model), placement);
  return scene;
}

}  // namespace s2sim::scene::detail
