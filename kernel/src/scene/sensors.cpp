/// \file
/// `<sensors>` / `<tools>` of robots and scene-level sensor files (simtwo-format.md §4.11).
/// Only the common children are parsed here; a sensor's behaviour reads the rest through its
/// ParamSource.

#include "scene/loading.hpp"
#include "scene/rotation.hpp"
#include "scene/xml.hpp"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace s2sim::scene::detail {
namespace {

bool is_sensor_element(std::string_view name) {
  // SimTwo's twelve, then S2Sim's own kinds (SimTwo ignores them as unknown names).
  static constexpr std::array<std::string_view, 18> kinds = {
      "IR",    "IRSharp", "capacitive", "inductive",  "floorline", "ranger2d",
      "imu",   "RFID",    "beacon",     "pentip",     "solenoid",  "spraygun",
      "sonar", "pose",    "touch",      "jointforce", "camera",    "lidar3d"};
  for (auto k : kinds)
    if (k == name) return true;
  return false;
}

/// An index name equal to another sensor's ID would give both the same signals: refused, so
/// that neither is renamed behind the script's back.
void check_index_name(const Scene& scene, const Reader& r, const Element& el, const Sensor& s,
                      const std::vector<int>& siblings) {
  for (int i : siblings) {
    const Sensor& other = scene.sensors[static_cast<std::size_t>(i)];
    if (other.name != s.name || (!s.id.empty() && !other.id.empty())) continue;
    const std::string why =
        s.id.empty() ? "this sensor has no <ID>, so it is named by its index '" + s.name +
                           "', which the sensor at " + other.where.str() + " has as its ID"
                     : "the ID '" + s.id + "' is the index name of the ID-less sensor at " +
                           other.where.str();
    r.fail(el, "", why + "; give one of them another <ID>");
  }
}

/// Names `s` (its ID, or its index in its list) and adds it to the scene, its parameters the
/// element `el`; to its robot's list (which scripts index) when `listed`.
void add_sensor(Scene& scene, const Reader& r, const Element& el, Sensor&& s, bool listed = true) {
  s.params = ParamSource{el, r.file(), std::make_shared<ConstantTable>(r.constants())};
  // Scripts address an ID-less sensor by its index (SimTwo's ID is ""), so that index names
  // its signals; the world's index for scene-level sensors (GetGlobalSensorVal).
  const int robot = s.robot;
  std::vector<int> siblings;  // the sensors of the same list: the robot's, or scene-level
  if (robot >= 0) {
    siblings = scene.robots[static_cast<std::size_t>(robot)].sensors;
  } else {
    for (std::size_t i = 0; i < scene.sensors.size(); ++i)
      if (scene.sensors[i].robot < 0) siblings.push_back(static_cast<int>(i));
  }
  const std::size_t index = robot >= 0 ? siblings.size() : scene.sensors.size();
  s.name = s.id.empty() ? std::to_string(index) : s.id;
  check_index_name(scene, r, el, s, siblings);
  scene.sensors.push_back(std::move(s));
  if (robot >= 0 && listed)
    scene.robots[static_cast<std::size_t>(robot)].sensors.push_back(
        static_cast<int>(scene.sensors.size() - 1));
}

}  // namespace

void load_sensors(LoadContext& ctx, const Reader& r, const Element& list, int robot, bool is_tool) {
  Scene& scene = ctx.scene;
  for (const Element& el : list.children) {
    // Other names (`nranger2d`...) are disabled sensors, and `<defines>` is not processed.
    if (!is_sensor_element(el.name)) continue;
    Sensor s;
    s.kind = el.name;
    s.robot = robot;
    s.is_tool = is_tool;
    s.where = r.at(el);
    s.color = Color{128 / 255.0, 128 / 255.0, 128 / 255.0, 1};
    std::string id_value, id_name;
    bool has_name = false;
    const Element* solid_el = nullptr;
    Vec3 pos, rot_deg;

    for (const Element& c : el.children) {
      const std::string& n = c.name;
      if (n == "ID") {
        id_value = r.text(c, "value", id_value);
        if (r.has(c, "name")) {
          id_name = r.text(c, "name", "");
          has_name = true;
        }
      } else if (n == "solid") {
        solid_el = &c;
      } else if (n == "absolute_coords") {
        s.absolute_coords = true;
      } else if (n == "pos") {
        pos = r.xyz(c, pos);
      } else if (n == "rot_deg") {
        rot_deg = r.xyz(c, rot_deg);
      } else if (n == "beam") {  // several <beam> elements accumulate
        Beam& b = s.beam;
        b.length_m = r.number(c, "length", b.length_m);
        b.initial_width_m = r.number(c, "initial_width", b.initial_width_m);
        b.final_width_m = r.number(c, "final_width", b.final_width_m);
        if (auto deg = r.optional_number(c, "angle")) b.angle_rad = deg_to_rad(*deg);
        b.rays = r.integer_in(c, "rays", b.rays, 1, kMaxBeamRays);
        if (const SensorRuleBroken broken = check_beam(b))
          r.fail(c, broken.attribute, broken.message);
      } else if (n == "noise") {
        Noise& z = s.noise;
        z.present = true;
        z.stdev = r.number(c, "stdev", z.stdev);
        z.stdev_p = r.number(c, "stdev_p", z.stdev_p);
        z.offset = r.number(c, "offset", z.offset);
        z.gain = r.number(c, "gain", z.gain);
        z.var_k = r.number(c, "var_k", z.var_k);
        z.var_d = r.number(c, "var_d", z.var_d);
        if (const SensorRuleBroken broken = check_noise(z))
          r.fail(c, broken.attribute, broken.message);
      } else if (n == "tag") {
        s.tags.push_back(r.text(c, "value", ""));
      } else if (n == "period") {
        s.period_s = r.number(c, "value", s.period_s);
        if (const SensorRuleBroken broken = check_sensor_period(s.period_s))
          r.fail(c, broken.attribute, broken.message);
      } else if (n == "force") {
        s.force.fmax_N = r.number(c, "fmax", s.force.fmax_N);
        s.force.k1 = r.number(c, "k1", s.force.k1);
        s.force.k2 = r.number(c, "k2", s.force.k2);
      } else if (n == "color_rgb") {
        s.color = r.color_rgb(c, s.color);
      }
    }
    s.id = has_name ? id_name : id_value;
    s.pose = Pose{pos, sensor_rotation_from_rot_deg(rot_deg)};

    if (robot >= 0) {
      const Robot& rb = scene.robots[static_cast<std::size_t>(robot)];
      s.body = rb.main_body;
      if (solid_el) {
        const std::string sid = r.text(*solid_el, "id", "");
        s.body = find_body(scene, rb.bodies, sid, false);
        if (s.body < 0 && rb.main_body >= 0) {
          // SimTwo's fallback for an unknown mother (IndexFromID = -1): the main body.
          ctx.warn(r.at(*solid_el, "id"),
                   "no solid with ID '" + sid +
                       "' in this robot; the sensor goes on the main body '" +
                       scene.bodies[static_cast<std::size_t>(rb.main_body)].id + "'");
          s.body = rb.main_body;
        }
      }
      if (s.body < 0) r.fail(el, "", "sensor of a robot without solids");
      // absolute_coords: the pose is in the robot frame at load; keep it in the body frame.
      if (s.absolute_coords)
        s.pose = scene.bodies[static_cast<std::size_t>(s.body)].pose.inverse() * s.pose;
    } else if (solid_el) {
      ctx.warn(r.at(*solid_el), "<solid> of a scene-level sensor ignored (world-fixed)");
    }

    add_sensor(scene, r, el, std::move(s));
  }
}

void add_camera_shell(LoadContext& ctx, const Reader& r, const Element& el, int robot, int body,
                      const Pose& shell_pose, const std::string& id) {
  Sensor s;
  s.kind = "camera";
  s.id = id;
  s.robot = robot;
  s.body = body;
  s.where = r.at(el);
  // The shell's camera looks along the shell's +Z with +Y up; a sensor frame looks along its
  // +X with +Z up. Columns: the sensor's X, Y, Z in the shell frame.
  Mat3 sensor_in_shell;
  sensor_in_shell.m[0][0] = 0, sensor_in_shell.m[0][1] = 1, sensor_in_shell.m[0][2] = 0;
  sensor_in_shell.m[1][0] = 0, sensor_in_shell.m[1][1] = 0, sensor_in_shell.m[1][2] = 1;
  sensor_in_shell.m[2][0] = 1, sensor_in_shell.m[2][1] = 0, sensor_in_shell.m[2][2] = 0;
  s.pose = Pose{shell_pose.position, shell_pose.rotation * sensor_in_shell};
  // Not in the robot's sensor list: SimTwo's scripts index that list, and a shell is not in
  // it there.
  add_sensor(ctx.scene, r, el, std::move(s), false);
}

void load_sensors_file(LoadContext& ctx, const std::filesystem::path& file,
                       const ConstantTable& globals, const std::string& root_name) {
  const std::string display = ctx.display(file);
  const Element root = read_xml_file(file, display);
  if (root.name != root_name)
    throw Error(
        ErrorKind::scene, Location{display, root.path, ""},
        "expected a <" + root_name + "> file (as the scene element), found <" + root.name + ">");
  ConstantTable scope = globals;  // a copy, although sensor lists do not process <defines>
  const Reader r(display, scope);
  load_sensors(ctx, r, root, -1, root_name == "tools");
}

}  // namespace s2sim::scene::detail
