/// \file
/// The `<wheels>` generator (simtwo-format.md §4.8): each `<wheel>` makes a cylinder tyre on
/// a circle around the robot origin and a motorised hinge to the main body.

#include "scene/loading.hpp"
#include "scene/mass.hpp"
#include "scene/rotation.hpp"

#include <cmath>

namespace s2sim::scene::detail {
namespace {

struct WheelSpec {
  std::string id = "W";  // "W" means the generated W<n>
  bool omni = false;
  double mass_kg = 0.13, radius_m = 0.09, width_m = 0.03, center_dist_m = 0.2;
  Surface surface{true, 1, 0.001, 0.001, 0, 0};
  double angle_deg = 0;
  Vec3 offset_m;
  ParamSource drive;  ///< the drive-train elements as written (the plugin has the defaults)
  Color color{128 / 255.0, 128 / 255.0, 128 / 255.0, 1};
  const Element* tyre_el = nullptr;  // for messages
};

WheelSpec wheel_defaults(const Reader& r, const Element& wheels) {
  WheelSpec w;
  w.drive = drive_train_source(r, std::make_shared<const ConstantTable>(r.constants()), wheels);
  return w;
}

void read_wheel(const Reader& r, const Element& el, WheelSpec& w) {
  for (const Element& c : el.children) {
    const std::string& n = c.name;
    if (n == "ID") {
      w.id = r.text(c, "value", w.id);
    } else if (n == "omni") {
      w.omni = true;
    } else if (n == "tyre") {
      w.mass_kg = r.number(c, "mass", w.mass_kg);
      w.radius_m = r.number(c, "radius", w.radius_m);
      w.width_m = r.number(c, "width", w.width_m);
      w.center_dist_m = r.number(c, "centerdist", w.center_dist_m);
      w.tyre_el = &c;
    } else if (n == "surface") {
      w.surface.mu = r.number(c, "mu", w.surface.mu);
      w.surface.mu2 = r.number(c, "mu2", w.surface.mu2);
      w.surface.softness = read_softness(r, c, w.surface.softness);
    } else if (n == "axis") {
      w.angle_deg = r.number(c, "angle", w.angle_deg);  // x, y are unused (quirk 28)
    } else if (n == "offset") {
      w.offset_m = r.xyz(c, w.offset_m);
    } else if (n == "color_rgb") {
      w.color = r.color_rgb(c, w.color);
    } else {
      read_drive_child(c, "", w.drive);
    }
  }
}

}  // namespace

void load_wheels(LoadContext& ctx, const Reader& r, const Element& wheels, int robot) {
  Scene& scene = ctx.scene;
  WheelSpec defaults = wheel_defaults(r, wheels);
  for (const Element& el : wheels.children) {
    if (el.name == "default") {
      read_wheel(r, el, defaults);
      continue;
    }
    if (el.name != "wheel") continue;
    Robot& rb = scene.robots[static_cast<std::size_t>(robot)];
    if (rb.main_body < 0) r.fail(el, "", "<wheels> need a solid (the main body) before them");
    WheelSpec w = defaults;
    w.tyre_el = nullptr;
    read_wheel(r, el, w);
    const Element& tyre_el = w.tyre_el ? *w.tyre_el : el;
    if (!(w.mass_kg > 0)) r.fail(tyre_el, "mass", "must be > 0, got " + format_number(w.mass_kg));
    if (!(w.radius_m > 0))
      r.fail(tyre_el, "radius", "must be > 0, got " + format_number(w.radius_m));
    if (!(w.width_m > 0)) r.fail(tyre_el, "width", "must be > 0, got " + format_number(w.width_m));

    int wheel_number = 1;
    for (const Joint& j : scene.joints)
      if (j.robot == robot && j.from_wheels) ++wheel_number;

    const Vec3 radial{cos_deg(w.angle_deg), sin_deg(w.angle_deg), 0};
    const Vec3 centre =
        Vec3{w.center_dist_m * radial.x, w.center_dist_m * radial.y, w.radius_m} + w.offset_m;

    Body tyre;
    tyre.id = "Tyre " + format_number(w.angle_deg);
    tyre.kind = SolidKind::tyre;
    tyre.robot = robot;
    // Local Z (the cylinder axis) points radially outward: Rz(a)·Ry(90°).
    tyre.pose = Pose{centre, rot_z_deg(w.angle_deg) * rot_y_deg(90)};
    tyre.mass_kg = w.mass_kg;
    tyre.drag = Drag{0, 0, 0};
    tyre.where = r.at(el);
    Geom g;
    g.id = tyre.id;
    g.shape.type = ShapeType::cylinder;
    g.shape.radius_m = w.radius_m;
    g.shape.length_m = w.width_m;
    g.surface = w.surface;
    g.surface.explicit_surface = true;
    g.friction = w.omni ? FrictionKind::omni : FrictionKind::isotropic;
    g.visual.color = w.color;  // SimTwo ignores the wheel colour; applying it is harmless
    g.where = tyre.where;
    tyre.inertia_kg_m2 = uniform_inertia(g.shape, w.mass_kg);
    tyre.geoms.push_back(std::move(g));
    scene.bodies.push_back(std::move(tyre));
    const int tyre_index = static_cast<int>(scene.bodies.size() - 1);
    rb.bodies.push_back(tyre_index);

    Joint j;
    j.id = w.id;
    if (j.id == "W") j.id += std::to_string(wheel_number);
    j.type = JointType::hinge;
    j.robot = robot;
    j.body1 = tyre_index;
    j.body2 = rb.main_body;
    j.anchor_m = centre;
    j.axis1 = -radial;
    j.from_wheels = true;
    j.where = r.at(el);
    j.drive1 = w.drive;
    j.drive1.element.path = j.where.element;
    j.drive2 = j.drive1;
    scene.joints.push_back(std::move(j));
    rb.joints.push_back(static_cast<int>(scene.joints.size() - 1));
  }
}

}  // namespace s2sim::scene::detail
