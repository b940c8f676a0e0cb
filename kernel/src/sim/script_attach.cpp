// The SimTwo script's controller (docs/scripting.md): a scene-level `pascal_script` component
// whose element carries what a SimTwo script indexes by number, in SimTwo's order
// (simtwo-script-api.md §2), as flat attributes the plugin reads through Params:
//   file, found_by, robots, things, obstacles, global_sensors, cells, constants
//   robot_<R>_id, _main (body path), _origin_x/y/z, _offset_x/y/z, _yaw, _solids, _axes, _sensors
//   robot_<R>_solid_<i>_id / _body / _canvas (its canvas image, when it has one),
//   robot_<R>_axis_<i> (axis path, '' for Fixed/Ball),
//   robot_<R>_shell_<i>_body / _geom (its index in the body's geoms) / _x / _y / _z / _r...,
//   robot_<R>_axis_<i>_joint, robot_<R>_sensor_<i>_id / _kind / _prefix
//   thing_<T>_id / _body / _r / _g / _b / _a, obstacle_<T>_id / _x / _y / _z / _canvas
//   global_sensor_<i>_id / _kind / _prefix, camera_shells, camera_shell_<i>_prefix,
//   cell_<k>_r / _c / _text, constant_<k>_name / _value
#include "sim/names.hpp"
#include "sim/simulation_impl.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <iterator>

namespace s2sim {
namespace {
using sim::exact_decimal;
}  // namespace

std::optional<std::filesystem::path> Simulation::Impl::script_path(std::string& found_by) const {
  if (options.script_mode == ScriptMode::off) return std::nullopt;
  std::filesystem::path file;
  if (options.script_file) {
    file = options.script_file->is_absolute() ? *options.script_file
                                              : scene.folder / *options.script_file;
    found_by = "the --script option";
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
      throw Error(ErrorKind::usage, "script file '" + file.string() + "' " +
                                        (ec && ec != std::errc::no_such_file_or_directory
                                             ? "cannot be read: " + ec.message()
                                             : std::string("not found")));
  } else if (scene.script &&
             (options.script_mode == ScriptMode::always || scene.script->runs_at_start)) {
    file = scene.script->file;
    found_by = scene.script->found_by;
  } else {
    return std::nullopt;
  }
  return file;
}

bool Simulation::Impl::script_adds_things() const {
  std::string found_by;
  const auto file = script_path(found_by);
  if (!file) return false;
  std::ifstream in(*file, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Pascal is case-insensitive: AddThingBox, addthingsphere, ADDTHINGCYLINDER...
  for (char& c : text)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text.find("addthing") != std::string::npos;
}

std::optional<scene::PluginInstance> Simulation::Impl::script_instance() const {
  std::string found_by;
  const auto script_file = script_path(found_by);
  if (!script_file) return std::nullopt;
  const std::filesystem::path& file = *script_file;

  scene::Element el;
  el.name = "script";
  el.path = "s2sim/script";
  auto set = [&](std::string key, std::string value) {
    el.attributes.emplace_back(std::move(key), std::move(value));
  };
  // A solid's or thing's colour (its own primitive's), size as SimTwo's GetSize gives it (a box
  // its edges; a cylinder r, r, length; a sphere r, r, r), mass and centre of mass (body frame).
  auto solid_look = [&](const std::string& k, const scene::Body& b) {
    const scene::Color c = b.geoms.empty() ? scene::Color{} : b.geoms[0].visual.color;
    const char* rgba[] = {"r", "g", "b", "a"};
    const double v[] = {c.r, c.g, c.b, c.a};
    for (int i = 0; i < 4; ++i)
      set(k + rgba[i], exact_decimal(v[i]));
    Vec3 size;
    if (!b.geoms.empty()) {
      const scene::Shape& shape = b.geoms[0].shape;
      switch (shape.type) {
        case scene::ShapeType::box:
        case scene::ShapeType::convex:  // its bounding box's edges
          size = shape.size_m;
          break;
        case scene::ShapeType::cylinder:
          size = {shape.radius_m, shape.radius_m, shape.length_m};
          break;
        case scene::ShapeType::sphere:
          size = {shape.radius_m, shape.radius_m, shape.radius_m};
          break;
      }
    }
    const bool has = !b.geoms.empty();
    const scene::ShapeType type = has ? b.geoms[0].shape.type : scene::ShapeType::box;
    set(k + "shape", type == scene::ShapeType::cylinder ? "cylinder"
                     : type == scene::ShapeType::sphere ? "sphere"
                                                        : "box");
    set(k + "size_x", exact_decimal(size.x));
    set(k + "size_y", exact_decimal(size.y));
    set(k + "size_z", exact_decimal(size.z));
    set(k + "com_x", exact_decimal(b.com_m.x));
    set(k + "com_y", exact_decimal(b.com_m.y));
    set(k + "com_z", exact_decimal(b.com_m.z));
  };
  set("file", file.string());
  set("found_by", found_by);
  set("period_s", exact_decimal(scene.settings.control_period_s));
  set("udp_address", scene.settings.script_udp_address);
  set("udp_port", std::to_string(scene.settings.script_udp_port));

  set("robots", std::to_string(scene.robots.size()));
  for (std::size_t r = 0; r < scene.robots.size(); ++r) {
    const scene::Robot& robot = scene.robots[r];
    const std::string rp = robot_prefix(static_cast<int>(r));
    const std::string k = "robot_" + std::to_string(r) + "_";
    set(k + "id", robot.id);
    set(k + "main",
        robot.main_body >= 0
            ? sim::solid_path(rp, scene.bodies[static_cast<std::size_t>(robot.main_body)].id)
            : std::string());
    set(k + "origin_x", exact_decimal(robot.origin_m.x));
    set(k + "origin_y", exact_decimal(robot.origin_m.y));
    set(k + "origin_z", exact_decimal(robot.origin_m.z));
    set(k + "offset_x", exact_decimal(robot.offset_m.x));
    set(k + "offset_y", exact_decimal(robot.offset_m.y));
    set(k + "offset_z", exact_decimal(robot.offset_m.z));
    set(k + "yaw", exact_decimal(robot.yaw_rad));
    set(k + "solids", std::to_string(robot.bodies.size()));
    for (std::size_t i = 0; i < robot.bodies.size(); ++i) {
      const scene::Body& b = scene.bodies[static_cast<std::size_t>(robot.bodies[i])];
      set(k + "solid_" + std::to_string(i) + "_id", b.id);
      set(k + "solid_" + std::to_string(i) + "_body", sim::solid_path(rp, b.id));
      solid_look(k + "solid_" + std::to_string(i) + "_", b);
      if (b.kind == scene::SolidKind::belt) set(k + "solid_" + std::to_string(i) + "_belt", "1");
      const std::string canvas = solid_canvas_name(robot.bodies[i]);
      if (image_index(canvas) >= 0) set(k + "solid_" + std::to_string(i) + "_canvas", canvas);
    }
    // The shells (GetShellPos, GetShellColor): their solid, pose in its frame, colour.
    set(k + "shells", std::to_string(robot.shells.size()));
    for (std::size_t i = 0; i < robot.shells.size(); ++i) {
      const auto [body, geom] = robot.shells[i];
      const scene::Body& b = scene.bodies[static_cast<std::size_t>(body)];
      const scene::Geom& g = b.geoms[static_cast<std::size_t>(geom)];
      const std::string sk = k + "shell_" + std::to_string(i) + "_";
      set(sk + "body", sim::solid_path(rp, b.id));
      set(sk + "geom", std::to_string(geom));
      set(sk + "x", exact_decimal(g.pose.position.x));
      set(sk + "y", exact_decimal(g.pose.position.y));
      set(sk + "z", exact_decimal(g.pose.position.z));
      const char* rgba[] = {"r", "g", "b", "a"};
      const double c[] = {g.visual.color.r, g.visual.color.g, g.visual.color.b, g.visual.color.a};
      for (int j = 0; j < 4; ++j)
        set(sk + rgba[j], exact_decimal(c[j]));
    }
    // SimTwo's axis list: one per joint axis in joint order, Fixed and Ball joints included,
    // a Universal joint's axis 2 before its axis 1 (quirk of §2).
    std::vector<std::pair<std::string, std::string>> axes;  // (axis path, joint id)
    for (int j : robot.joints) {
      const scene::Joint& joint = scene.joints[static_cast<std::size_t>(j)];
      std::string first, second;
      for (std::size_t a = 0; a < topology.axes.size(); ++a) {
        if (topology.axes[a].joint != j) continue;
        (topology.axes[a].which == 0 ? first : second) = axis_prefix(static_cast<int>(a));
      }
      if (joint.type == scene::JointType::universal) axes.emplace_back(second, joint.id);
      axes.emplace_back(first, joint.id);
    }
    set(k + "axes", std::to_string(axes.size()));
    for (std::size_t i = 0; i < axes.size(); ++i) {
      set(k + "axis_" + std::to_string(i), axes[i].first);
      set(k + "axis_" + std::to_string(i) + "_joint", axes[i].second);
    }
    set(k + "sensors", std::to_string(robot.sensors.size()));
    for (std::size_t i = 0; i < robot.sensors.size(); ++i) {
      const scene::Sensor& s = scene.sensors[static_cast<std::size_t>(robot.sensors[i])];
      const std::string sk = k + "sensor_" + std::to_string(i) + "_";
      set(sk + "id", s.id);
      set(sk + "kind", s.kind);
      set(sk + "prefix", sim::component_path(rp, "sensors", s.name));
    }
  }
  // A robot's <camera> shell is a camera sensor outside its robot's list (SimTwo has no such
  // sensor): in no list a script indexes.
  auto camera_shell = [&](std::size_t i) {
    const scene::Sensor& s = scene.sensors[i];
    if (s.kind != "camera" || s.robot < 0) return false;
    const std::vector<int>& listed = scene.robots[static_cast<std::size_t>(s.robot)].sensors;
    return std::find(listed.begin(), listed.end(), static_cast<int>(i)) == listed.end();
  };
  // The world's sensor list: each robot's sensors, then the scene-level ones, in load order.
  std::size_t g = 0;
  for (std::size_t i = 0; i < scene.sensors.size(); ++i) {
    if (camera_shell(i)) continue;
    const scene::Sensor& s = scene.sensors[i];
    const std::string sk = "global_sensor_" + std::to_string(g++) + "_";
    set(sk + "id", s.id);
    set(sk + "kind", s.kind);
    set(sk + "prefix", sim::component_path(s.robot >= 0 ? robot_prefix(s.robot) : std::string(),
                                           "sensors", s.name));
  }
  set("global_sensors", std::to_string(g));
  // The robots' <camera> shells (camera sensors outside their robot's list), in load order:
  // GetCameraPixel and CamBitmap read the last one's image, as SimTwo's last camera wins.
  std::size_t cameras = 0;
  for (std::size_t i = 0; i < scene.sensors.size(); ++i) {
    if (!camera_shell(i)) continue;
    const scene::Sensor& s = scene.sensors[i];
    set("camera_shell_" + std::to_string(cameras++) + "_prefix",
        sim::component_path(robot_prefix(s.robot), "sensors", s.name));
  }
  set("camera_shells", std::to_string(cameras));
  set("things", std::to_string(scene.things.size()));
  for (std::size_t t = 0; t < scene.things.size(); ++t) {
    const scene::Body& b = scene.bodies[static_cast<std::size_t>(scene.things[t])];
    const std::string tk = "thing_" + std::to_string(t) + "_";
    set(tk + "id", b.id);
    set(tk + "body", sim::thing_path(b.id));
    const scene::Color c = b.geoms.empty() ? scene::Color{} : b.geoms[0].visual.color;
    set(tk + "r", exact_decimal(c.r));
    set(tk + "g", exact_decimal(c.g));
    set(tk + "b", exact_decimal(c.b));
    set(tk + "a", exact_decimal(c.a));
    solid_look(tk, b);
  }
  set("obstacles", std::to_string(scene.obstacles.size()));
  for (std::size_t o = 0; o < scene.obstacles.size(); ++o) {
    const scene::Geom& ob = scene.obstacles[o];
    const std::string ok = "obstacle_" + std::to_string(o) + "_";
    set(ok + "id", ob.id);
    set(ok + "x", exact_decimal(ob.pose.position.x));
    set(ok + "y", exact_decimal(ob.pose.position.y));
    set(ok + "z", exact_decimal(ob.pose.position.z));
    const std::string canvas = obstacle_canvas_name(static_cast<int>(o));
    if (image_index(canvas) >= 0) set(ok + "canvas", canvas);
    const char* rgba[] = {"r", "g", "b", "a"};
    const double c[] = {ob.visual.color.r, ob.visual.color.g, ob.visual.color.b, ob.visual.color.a};
    for (int k = 0; k < 4; ++k)
      set(ok + rgba[k], exact_decimal(c[k]));
    for (int r = 0; r < 3; ++r)
      for (int col = 0; col < 3; ++col)
        set(ok + "rot_" + std::to_string(r) + std::to_string(col),
            exact_decimal(ob.pose.rotation.m[r][col]));
  }
  // The file's cells, then the caller's (later ones win in the plugin's sheet).
  std::vector<scene::SheetCell> cells = scene.sheet;
  cells.insert(cells.end(), options.sheet_cells.begin(), options.sheet_cells.end());
  set("cells", std::to_string(cells.size()));
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const std::string ck = "cell_" + std::to_string(i) + "_";
    set(ck + "r", std::to_string(cells[i].row));
    set(ck + "c", std::to_string(cells[i].col));
    set(ck + "text", cells[i].text);
  }
  const auto& constants = scene.globals.entries();
  set("constants", std::to_string(constants.size()));
  for (std::size_t i = 0; i < constants.size(); ++i) {
    set("constant_" + std::to_string(i) + "_name", constants[i].first);
    set("constant_" + std::to_string(i) + "_value", exact_decimal(constants[i].second));
  }

  scene::PluginInstance p;
  p.kind = "pascal_script";
  p.id = "script";
  p.robot = -1;
  p.where = Location{found_by, "", ""};
  p.params = scene::ParamSource{std::move(el), found_by, std::make_shared<scene::ConstantTable>()};
  return p;
}

}  // namespace s2sim
