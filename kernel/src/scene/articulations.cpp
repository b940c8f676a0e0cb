/// \file
/// `<articulations>` (simtwo-format.md §4.9): `<default>` then `<joint>`s between robot solids
/// or to the world. Angles in the XML are degrees; here radians.

#include "scene/loading.hpp"
#include "scene/rotation.hpp"

#include <cmath>
#include <limits>

namespace s2sim::scene::detail {
namespace {

/// What `<default>` captures for the following joints (axis 1 drive train and the marker).
struct JointDefaults {
  ParamSource drive;  ///< the drive-train elements as written (the plugin has the defaults)
  JointDraw draw;
};

JointDefaults articulation_defaults(const Reader& r, const Element& list) {
  JointDefaults d;
  d.drive = drive_train_source(r, std::make_shared<const ConstantTable>(r.constants()), list);
  d.draw.color = color_from_tcolor(0x800000);
  return d;
}

void read_draw(const Reader& r, const Element& c, JointDraw& draw) {
  draw.radius_m = r.number(c, "radius", draw.radius_m);
  draw.height_m = r.number(c, "height", draw.height_m);
  draw.color = r.rgb24(c, "rgb24", draw.color);
}

/// Converts `<limits Min Max>` for one axis. Rotational stops engage only inside
/// (-180°, 180°), as ODE's hinge angle lives in (-pi, pi]; a side that never engages
/// becomes ±infinity. Slider stops (metres) engage whenever `<limits>` is given.
Limits make_limits(double min, double max, bool given, bool rotational) {
  Limits l;
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (!rotational) {
    l.min = min;
    l.max = max;
    l.active = given;
    return l;
  }
  const double lo = deg_to_rad(min), hi = deg_to_rad(max);
  const bool lo_engages = lo > -kPi && lo < kPi;
  const bool hi_engages = hi > -kPi && hi < kPi;
  l.active = lo_engages || hi_engages;
  l.min = l.active && !lo_engages ? -inf : lo;
  l.max = l.active && !hi_engages ? inf : hi;
  return l;
}

/// A range whose minimum exceeds its maximum holds no position: refused, not reinterpreted.
void check_limits(const Reader& r, const Element& el, double min, double max) {
  if (min > max)
    r.fail(el, "Min",
           "Min (" + format_number(min) + ") is greater than Max (" + format_number(max) +
               "): the joint would have no allowed position");
}

}  // namespace

void load_articulations(LoadContext& ctx, const Reader& r, const Element& list, int robot) {
  Scene& scene = ctx.scene;
  JointDefaults defaults = articulation_defaults(r, list);
  for (const Element& el : list.children) {
    if (el.name != "joint" && el.name != "default") continue;
    const bool is_default = el.name == "default";

    Joint j;
    j.robot = robot;
    j.where = r.at(el);
    j.drive1 = defaults.drive;
    j.drive2 = defaults.drive;  // `*2` children start from axis 1's current defaults
    j.drive1.element.path = j.drive2.element.path = j.where.element;
    j.draw = defaults.draw;
    std::optional<std::string> id;
    Vec3 pos, axis{0, 0, 1}, axis2{0, 0, 1};
    const Element* axis_el = nullptr;
    const Element* axis2_el = nullptr;
    double lim_min = -360, lim_max = 360, lim2_min = -360, lim2_max = 360;
    bool lim_given = false, lim2_given = false;
    const Element* connect_el = nullptr;
    const Element* type_el = nullptr;
    const Element* solid_el = nullptr;

    for (const Element& c : el.children) {
      const std::string& n = c.name;
      if (n == "ID") {
        if (r.has(c, "value")) id = r.text(c, "value", "");
      } else if (n == "type") {
        type_el = &c;
      } else if (n == "connect") {
        connect_el = &c;
      } else if (n == "pos") {
        pos = r.xyz(c, pos);
      } else if (n == "axis") {
        axis = r.xyz(c, axis);
        j.wrap1 = r.boolean(c, "wrap", j.wrap1);
        axis_el = &c;
      } else if (n == "axis2") {
        axis2 = r.xyz(c, axis2);
        j.wrap2 = r.boolean(c, "wrap", j.wrap2);
        axis2_el = &c;
      } else if (n == "limits") {
        lim_min = r.number(c, "Min", lim_min);
        lim_max = r.number(c, "Max", lim_max);
        check_limits(r, c, lim_min, lim_max);
        lim_given = true;
      } else if (n == "limits2") {
        lim2_min = r.number(c, "Min", lim2_min);
        lim2_max = r.number(c, "Max", lim2_max);
        check_limits(r, c, lim2_min, lim2_max);
        lim2_given = true;
      } else if (n == "solid") {
        solid_el = &c;
      } else if (n == "draw") {
        read_draw(r, c, j.draw);
      } else if (n == "desc") {
        j.description = r.text(c, "Eng", j.description);
      } else if (!read_drive_child(c, "", j.drive1)) {
        read_drive_child(c, "2", j.drive2);
      }
    }

    if (is_default) {
      // `*2` children and geometry of a <default> are not captured (as in SimTwo).
      defaults.drive = j.drive1;
      defaults.draw = j.draw;
      continue;
    }

    Robot& rb = scene.robots[static_cast<std::size_t>(robot)];
    if (!type_el || !r.has(*type_el, "value"))
      r.fail(type_el ? *type_el : el, type_el ? "value" : "", "missing joint <type value>");
    const std::string type = r.text(*type_el, "value", "");
    if (type == "Hinge") {
      j.type = JointType::hinge;
    } else if (type == "Slider") {
      j.type = JointType::slider;
    } else if (type == "Universal") {
      j.type = JointType::universal;
    } else if (type == "Fixed") {
      j.type = JointType::fixed;
    } else if (type == "Ball") {
      j.type = JointType::ball;
    } else {
      r.fail(*type_el, "value",
             "unknown joint type '" + type +
                 "' (expected Hinge, Slider, Universal, Fixed or Ball; case-sensitive)");
    }

    j.id = id ? *id : "joint" + std::to_string(rb.joints.size() + 1);

    // Bodies: B1/B2 (or S1/S2); 0 or world is the world; the last solid with the ID wins.
    if (!connect_el) r.fail(el, "", "missing <connect B1 B2>");
    auto resolve = [&](const char* attr, const char* alt) {
      const char* used = r.has(*connect_el, attr) ? attr : alt;
      if (!r.has(*connect_el, used)) r.fail(*connect_el, attr, "missing body ID");
      const std::string name = r.text(*connect_el, used, "");
      if (name == "0" || name == "world") return -1;
      const int b = find_body(scene, rb.bodies, name, true);
      // SimTwo silently skips such a joint; S2Sim refuses it.
      if (b < 0) r.fail(*connect_el, used, "no solid with ID '" + name + "' in this robot");
      return b;
    };
    j.body1 = resolve("B1", "S1");
    j.body2 = resolve("B2", "S2");
    if (j.body1 < 0 && j.body2 < 0) r.fail(*connect_el, "", "both bodies are the world");
    if (j.body1 == j.body2)  // a loop on one body: Simbody asserts on it (found by fuzzing)
      r.fail(*connect_el, r.has(*connect_el, "B2") ? "B2" : "S2",
             "joins solid '" + r.text(*connect_el, r.has(*connect_el, "B2") ? "B2" : "S2", "") +
                 "' to itself");
    if (j.body1 < 0) std::swap(j.body1, j.body2);  // the solid is body 1, as in SimTwo

    const bool rotational = j.type != JointType::slider;

    if (j.type == JointType::hinge || j.type == JointType::slider ||
        j.type == JointType::universal) {
      j.limits1 = make_limits(lim_min, lim_max, lim_given, rotational);
    }
    if (j.type == JointType::universal)
      j.limits2 = make_limits(lim2_min, lim2_max, lim2_given, true);

    auto unit = [&](Vec3 v, const Element* where, const char* name) {
      const double len = norm(v);
      if (!(len > 1e-12))
        r.fail(where ? *where : el, "", std::string(name) + " is the zero vector");
      return v / len;
    };
    Pose frame;  // robot frame, or the frame of <solid id>
    if (solid_el) {
      const std::string sid = r.text(*solid_el, "id", "");
      const int b = find_body(scene, rb.bodies, sid, false);
      if (b < 0) r.fail(*solid_el, "id", "no solid with ID '" + sid + "' in this robot");
      frame = scene.bodies[static_cast<std::size_t>(b)].pose;
    }
    j.anchor_m = frame * pos;
    j.axis1 = frame.rotation * unit(axis, axis_el, "axis");
    j.axis2 = frame.rotation * unit(axis2, axis2_el, "axis2");

    scene.joints.push_back(std::move(j));
    rb.joints.push_back(static_cast<int>(scene.joints.size() - 1));
  }
}

}  // namespace s2sim::scene::detail
