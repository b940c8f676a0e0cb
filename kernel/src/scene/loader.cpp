/// \file
/// `load_scene`: scene.xml (simtwo-format.md §3) and everything it references, with the
/// scopes of §2.2: robot, things and track files get a copy of G; scene-level robot/things
/// defines and obstacle files write into G.

#include "common/closest_names.hpp"
#include "scene/import_model.hpp"
#include "scene/loading.hpp"
#include "scene/rotation.hpp"
#include "scene/xml.hpp"

#include <algorithm>
#include <cctype>

namespace s2sim::scene {
namespace detail {

std::filesystem::path LoadContext::resolve(std::string_view name) const {
  std::string s(name);
  for (char& c : s)
    if (c == '\\') c = '/';  // SimTwo projects come from Windows
  const std::filesystem::path p(s);
  return (p.is_absolute() ? p : folder / p).lexically_normal();
}

std::string LoadContext::display(const std::filesystem::path& absolute) const {
  const auto rel = absolute.lexically_relative(folder);
  if (!rel.empty() && *rel.begin() != "..") return rel.generic_string();
  return absolute.generic_string();
}

void LoadContext::warn(const Location& where, const std::string& message) {
  scene.warnings.push_back(where.str().empty() ? message : where.str() + ": " + message);
}

namespace {

/// `<ID name>` wins over `<ID value>`.
std::string element_id(const Reader& r, const Element& el, std::string fallback) {
  if (const Element* id = el.child("ID")) {
    if (r.has(*id, "name")) return r.text(*id, "name", "");
    if (r.has(*id, "value")) return r.text(*id, "value", "");
  }
  return fallback;
}

/// The `file` of a things/track/sensors element; a missing one reuses the previous element's
/// (quirk 25, kept with a warning). Empty when there is nothing to load.
std::string file_or_previous(LoadContext& ctx, const Reader& r, const Element& el) {
  std::string& last = ctx.last_file[el.name];
  if (const std::string* f = el.attribute("file")) {
    last = *f;
    return *f;
  }
  if (last.empty()) {
    ctx.warn(r.at(el, "file"), "missing file attribute; element ignored");
  } else {
    ctx.warn(r.at(el, "file"), "missing file attribute; reusing '" + last + "' (as SimTwo)");
  }
  return last;
}

/// Whether `file` exists; warns and returns false otherwise (SimTwo skips silently).
bool exists_or_warn(LoadContext& ctx, const Reader& r, const Element& el, const std::string& attr,
                    const std::string& name, const std::filesystem::path& file,
                    const std::string& what) {
  // The error_code form: an over-long name or a folder we may not read is a located scene
  // error, not an exception from the file system library.
  std::error_code ec;
  if (std::filesystem::is_regular_file(file, ec)) return true;
  if (ec && ec != std::errc::no_such_file_or_directory)
    r.fail(el, attr, "cannot read '" + name + "': " + ec.message());
  ctx.warn(r.at(el, attr), "file '" + name + "' not found; " + what + " skipped");
  return false;
}

void load_scene_robot(LoadContext& ctx, const Reader& r, const Element& el, ConstantTable& g) {
  RobotPlacement placement;
  placement.id = "robot" + std::to_string(ctx.scene.robots.size());
  placement.where = r.at(el);
  const Element* body = nullptr;
  // Defines go into G before the robot file loads, wherever they stand in the element.
  for (const Element& c : el.children) {
    if (c.name == "defines") {
      apply_defines(c, r, g);
    } else if (c.name == "pos") {
      placement.offset_m = r.xyz(c);
    } else if (c.name == "rot_deg") {
      placement.yaw_deg = r.number(c, "z", 0);
      if (r.number(c, "x", 0) != 0 || r.number(c, "y", 0) != 0)
        ctx.warn(r.at(c), "robot rot_deg x and y are ignored (SimTwo places robots by yaw only)");
    } else if (c.name == "body") {
      body = &c;
    }
  }
  placement.id = element_id(r, el, placement.id);
  // Robot IDs name every signal and input of the robot: two robots cannot share one.
  for (const Robot& other : ctx.scene.robots)
    if (other.id == placement.id) {
      const Element* id = el.child("ID");
      r.fail(id ? *id : el, id && r.has(*id, "name") ? "name" : (id ? "value" : ""),
             "duplicate robot ID '" + placement.id + "' (the robot at " + other.where.str() +
                 " has it already)");
    }
  if (!body || !r.has(*body, "file")) {
    ctx.warn(r.at(body ? *body : el, "file"),
             "robot '" + placement.id + "' has no <body file>; skipped");
    return;
  }
  const std::string name = r.text(*body, "file", "");
  const auto file = ctx.resolve(name);
  if (!exists_or_warn(ctx, r, *body, "file", name, file, "robot '" + placement.id + "'")) return;
  if (const std::string format = robot_format(file); !format.empty()) {
    load_imported_robot(ctx, file, format, placement);
    return;
  }
  load_robot_file(ctx, file, g, placement);
}

void load_scene_obstacles(LoadContext& ctx, const Reader& r, const Element& el, ConstantTable& g) {
  const Element* source = &el;
  if (!r.has(el, "file")) {
    if (const Element* body = el.child("body")) source = body;
  }
  if (!r.has(*source, "file")) {
    ctx.warn(r.at(el, "file"), "obstacles without a file; skipped");
    return;
  }
  const std::string name = r.text(*source, "file", "");
  Vec3 pos, rot_deg;
  if (const Element* p = el.child("pos")) pos = r.xyz(*p);
  if (const Element* rd = el.child("rot_deg")) rot_deg = r.xyz(*rd);
  const auto file = ctx.resolve(name);
  if (!exists_or_warn(ctx, r, *source, "file", name, file, "obstacles")) return;
  load_obstacles_file(ctx, file, g, element_id(r, el, ""),
                      Pose{pos, rotation_from_rot_deg(rot_deg)});
}

/// Every outside constant (`--define NAME=VALUE`, Python's `defines=`) must name an `<arg>` of
/// the scene or of one of its files: a misspelt name would change nothing, silently.
void check_outside_constants(const LoadOptions& options, const ConstantTable& g,
                             const std::string& display) {
  auto same = [](std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
             return std::toupper(static_cast<unsigned char>(x)) ==
                    std::toupper(static_cast<unsigned char>(y));
           });
  };
  for (const auto& [name, value] : options.constants) {
    bool arg = false, constant = false;
    for (const auto& d : g.declared())
      if (same(d.name, name)) (d.arg ? arg : constant) = true;
    if (arg) continue;
    if (constant)
      throw Error(ErrorKind::usage, Location{display, "", ""},
                  "the constant '" + name +
                      "' given from outside (--define, defines=) is a <const> of the scene, "
                      "which overwrites any outside value: declare it as <arg> to let it be set");
    std::vector<std::string> names;
    for (const auto& d : g.declared())
      if (d.arg) names.push_back(d.name);
    throw Error(ErrorKind::usage, Location{display, "", ""},
                common::unknown_name_message("constant (--define, defines=)", name, names) +
                    " (no <arg> of the scene or of its files has that name, so it would "
                    "change nothing)");
  }
}

}  // namespace
}  // namespace detail

Scene load_scene(const std::filesystem::path& path, const LoadOptions& options) {
  using namespace detail;
  namespace fs = std::filesystem;
  const fs::path p = fs::absolute(path).lexically_normal();
  std::error_code ec;
  const fs::path file = fs::is_directory(p, ec) ? p / "scene.xml" : p;
  if (!fs::is_regular_file(file, ec))
    throw Error(ErrorKind::scene, Location{file.generic_string(), "", ""},
                ec && ec != std::errc::no_such_file_or_directory
                    ? "cannot read the scene: " + ec.message()
                    : std::string("scene file not found"));
  if (const std::string format = robot_format(file); !format.empty()) {
    Scene robot = load_robot_scene(file, format, options);
    check_outside_constants(options, robot.globals, file.filename().string());
    return robot;
  }

  Scene scene;
  scene.file = file;
  scene.folder = file.parent_path();
  LoadContext ctx{scene, scene.folder, {}, {}, model_search_path(options.model_path)};
  scene.settings = load_settings(scene.folder);

  ConstantTable& g = scene.globals;
  for (const auto& [name, value] : options.constants)
    g.set(name, value);

  const std::string display = ctx.display(file);
  const Element root = read_xml_file(file, display);
  if (root.name != "scene")
    throw Error(ErrorKind::scene, Location{display, root.path, ""},
                "expected a <scene> file, found <" + root.name + ">");
  const Reader r(display, g);

  const Element* s2sim_script = nullptr;
  for (const Element& el : root.children) {
    const std::string& n = el.name;
    if (n == "defines") {
      apply_defines(el, r, g);
    } else if (n == "robot") {
      load_scene_robot(ctx, r, el, g);
    } else if (n == "obstacles" || n == "obstacle") {
      load_scene_obstacles(ctx, r, el, g);
    } else if (n == "things") {
      const std::string name = file_or_previous(ctx, r, el);
      for (const Element& c : el.children)
        if (c.name == "defines") apply_defines(c, r, g);  // into G (quirk 16, kept)
      if (name.empty()) continue;
      const auto f = ctx.resolve(name);
      if (exists_or_warn(ctx, r, el, "file", name, f, "things")) load_things_file(ctx, f, g);
    } else if (n == "track") {
      const std::string name = file_or_previous(ctx, r, el);
      if (name.empty()) continue;
      const auto f = ctx.resolve(name);
      if (exists_or_warn(ctx, r, el, "file", name, f, "track")) load_track_file(ctx, f, g);
    } else if (n == "sensors" || n == "tools") {
      const std::string name = file_or_previous(ctx, r, el);
      if (name.empty()) continue;
      const auto f = ctx.resolve(name);
      if (exists_or_warn(ctx, r, el, "file", name, f, n)) load_sensors_file(ctx, f, g, n);
    } else if (n == "plugin") {
      load_plugin(ctx, r, el, -1);
    } else if (n == "s2sim") {
      apply_s2sim_settings(r, el, scene.settings);
      if (const Element* script = el.child("script")) s2sim_script = script;
    } else {
      ctx.warn(r.at(el), "unknown scene element <" + n + "> ignored");
    }
  }
  load_script_and_sheet(ctx, r, s2sim_script);
  check_outside_constants(options, g, display);
  return scene;
}

}  // namespace s2sim::scene
