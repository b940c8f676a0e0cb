#pragma once
/// \file
/// Internals of the scene loader shared by its translation units: the loading context and
/// one function per SimTwo section. Every pose built here is in the frame of the file being
/// read (robot frame for robot files); robot placement happens last (robot_loader.cpp).

#include <s2sim/kernel/scene.hpp>

#include "scene/attributes.hpp"

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace s2sim::scene::detail {

/// Shared state of one `load_scene` call.
struct LoadContext {
  Scene& scene;
  std::filesystem::path folder;  ///< absolute scene folder
  /// Last `file` per scene element name, for SimTwo's reuse of a missing `file` (quirk 25).
  std::map<std::string, std::string> last_file;
  /// Plugin instances per kind so far, for default IDs `<kind><n>`.
  std::map<std::string, int> plugin_count;
  /// Where `package://` and `model://` URIs of imported robots are looked for.
  std::vector<std::filesystem::path> model_path;

  /// A file name from the XML (Windows separators accepted) resolved against the folder.
  std::filesystem::path resolve(std::string_view name) const;
  /// How messages name a file: relative to the scene folder when inside it.
  std::string display(const std::filesystem::path& absolute) const;
  void warn(const Location& where, const std::string& message);
};

using IniSection = std::map<std::string, std::string>;
/// The keys of `[section]` of an ini file, or of the whole file when it has no such section;
/// nullopt when the file cannot be read.
std::optional<IniSection> read_ini(const std::filesystem::path& file, const std::string& section);

/// `<defines>`: `<const>` sets, `<arg>` defines when absent, anything else is ignored.
void apply_defines(const Element& defines, const Reader& reader, ConstantTable& table);

/// Index in `list` (indices into scene.bodies) of the first or last body with `id`, or -1.
int find_body(const Scene& scene, const std::vector<int>& list, std::string_view id, bool last);

/// Whether `name` is one of SimTwo's solid elements (cuboid, cylinder, sphere, belt, propeller).
bool is_solid_element(std::string_view name);

/// Reads one solid (robot solid or thing); appends it to scene.bodies and returns its index,
/// or nullopt when SimTwo would not create it (no `<ID value>`). `list` holds the solids
/// that a `<solid id>` mother may name.
std::optional<int> load_solid(LoadContext& ctx, const Reader& reader, const Element& el, int robot,
                              const std::vector<int>& list);

/// Visual children shared by solids, shells and obstacles (colour, transparency, texture,
/// mesh, canvas, liquid, painting_target) and material flags. Returns true if handled.
bool read_visual_child(LoadContext& ctx, const Reader& reader, const Element& child,
                       ShapeType shape, Visual& visual, Material& material);

/// `<surface>` into `surface` (explicit when mu >= 0).
void read_surface(const Reader& reader, const Element& el, Surface& surface);
/// `softness` of a surface element: > 0, or a located error.
double read_softness(const Reader& reader, const Element& el, double fallback);

void load_shells(LoadContext& ctx, const Reader& reader, const Element& shells, int robot);
void load_wheels(LoadContext& ctx, const Reader& reader, const Element& wheels, int robot);
void load_articulations(LoadContext& ctx, const Reader& reader, const Element& list, int robot);
/// Sensors or tools of a robot (`robot` >= 0) or of a scene-level file (`robot` = -1).
/// A `<camera>` shell's `camera` sensor on `body`, looking along the shell's +Z (`shell_pose`
/// in the body frame), its parameters the shell element (`focal`, `frame`...).
void add_camera_shell(LoadContext& ctx, const Reader& reader, const Element& el, int robot,
                      int body, const Pose& shell_pose, const std::string& id);
void load_sensors(LoadContext& ctx, const Reader& reader, const Element& list, int robot,
                  bool is_tool);

/// An axis's drive-train elements before any is read: none, in `reader`'s file, evaluated
/// with `constants` (the scope of the section being read), located at `at`.
ParamSource drive_train_source(const Reader& reader, std::shared_ptr<const ConstantTable> constants,
                               const Element& at);
/// Drive-train children: `motor`, `gear`, `rotor`, `encoder`, `controller`, `friction`,
/// `spring` with the name suffix `suffix` ("" or "2"), stored under the name without it and
/// overlaid on what `drive` holds (the inherited attributes), not interpreted: the drive-train
/// plugin reads them. Returns whether `child` was one of them.
bool read_drive_child(const Element& child, std::string_view suffix, ParamSource& drive);

/// A `<plugin>` element at the top level of scene.xml (`robot` = -1) or a robot file.
void load_plugin(LoadContext& ctx, const Reader& reader, const Element& el, int robot);

/// Scene-level placement of a robot file (§9.3).
struct RobotPlacement {
  std::string id;
  Vec3 offset_m;
  double yaw_deg = 0;  ///< `rot_deg z`
  Location where;
  /// An imported robot run on its own: when nothing joins it to the world, it is lifted so
  /// that its lowest collision point rests on the floor (z = 0).
  bool rest_on_floor = false;
};
/// Robot placement: the main body ends at P0 + t, yawed by ψ about the vertical through P0;
/// bodies, joint anchors and axes move, geoms and sensors follow their bodies.
void place_robot(Scene& scene, Robot& robot, const Vec3& offset, double yaw_deg);
/// Loads a robot file into the scene and places it; `globals` is copied for its scope.
void load_robot_file(LoadContext& ctx, const std::filesystem::path& file,
                     const ConstantTable& globals, const RobotPlacement& placement);

/// Obstacle file, offset by `offset` (world pose of the file frame); defines go into G.
void load_obstacles_file(LoadContext& ctx, const std::filesystem::path& file,
                         ConstantTable& globals, const std::string& id_prefix, const Pose& offset);
void load_things_file(LoadContext& ctx, const std::filesystem::path& file,
                      const ConstantTable& globals);
void load_track_file(LoadContext& ctx, const std::filesystem::path& file,
                     const ConstantTable& globals);
/// Scene-level sensors/tools file; its root must be `root_name`.
void load_sensors_file(LoadContext& ctx, const std::filesystem::path& file,
                       const ConstantTable& globals, const std::string& root_name);

/// Settings of §10.1 from the ini files of `folder`.
Settings load_settings(const std::filesystem::path& folder);
/// `<s2sim>` overrides of scene.xml.
void apply_s2sim_settings(const Reader& reader, const Element& el, Settings& settings);
/// The project's script (ScriptRef) and sheet (`Global.S2Sheet`); `s2sim_script` is the
/// `<s2sim><script file>` element when the scene has one (scene/script.cpp).
void load_script_and_sheet(LoadContext& ctx, const Reader& reader, const Element* s2sim_script);

}  // namespace s2sim::scene::detail
