/// \file
/// Robot `<solids>` and things (simtwo-format.md §4.2, §6): one body with one primitive each,
/// plus the visual/surface children shared with shells and obstacles.

#include "scene/limits.hpp"
#include "scene/loading.hpp"
#include "scene/mass.hpp"
#include "scene/primitive.hpp"
#include "scene/rotation.hpp"

#include <array>
#include <cctype>
#include <cmath>

namespace s2sim::scene::detail {
namespace {

/// Largest magnitude of SimTwo's drag coefficient, buoyant mass (kg) and thrust coefficient:
/// far beyond any sample, small enough that the forces stay finite.
constexpr double kMaxFluidCoefficient = 1e6;

std::string lower(std::string s) {
  for (char& c : s)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// A file referenced for visuals only: resolved against the scene folder; a missing file is
/// a warning and leaves `out` empty.
void visual_file(LoadContext& ctx, const Reader& r, const Element& el, std::string_view attr,
                 std::string_view what, std::filesystem::path& out) {
  const std::string name = r.text(el, attr, "");
  if (name.empty()) return;
  const std::filesystem::path p = ctx.resolve(name);
  std::error_code ec;  // an unreadable or over-long name is "not found" here: visual only
  if (std::filesystem::exists(p, ec)) {
    out = p;
  } else {
    ctx.warn(r.at(el, attr), std::string(what) + " '" + name + "' not found (visual only)");
  }
}

}  // namespace

bool is_solid_element(std::string_view name) {
  return name == "cuboid" || name == "cylinder" || name == "sphere" || name == "belt" ||
         name == "propeller";
}

int find_body(const Scene& scene, const std::vector<int>& list, std::string_view id, bool last) {
  int found = -1;
  for (int index : list) {
    if (scene.bodies[static_cast<std::size_t>(index)].id == id) {
      found = index;
      if (!last) break;
    }
  }
  return found;
}

double read_softness(const Reader& r, const Element& el, double fallback) {
  const double softness = r.number(el, "softness", fallback);
  // ODE's CFM read at the reference step: the contact stiffness is erp/(softness·h). Zero or
  // less is no stiffness at all; a hard contact is a small positive value (the stiffness is
  // capped at what the step can carry anyway, docs/models/contact.md).
  if (!(softness > 0))
    r.fail(el, "softness",
           "must be > 0, got " + format_number(softness) +
               " (for a hard contact give a small value such as 1e-6)");
  return softness;
}

void read_surface(const Reader& r, const Element& el, Surface& s) {
  s.mu = r.number(el, "mu", s.mu);
  s.mu2 = r.number(el, "mu2", s.mu2);
  s.softness = read_softness(r, el, s.softness);
  s.bounce = r.number(el, "bounce", s.bounce);
  // A restitution is a fraction of the approach speed: above 1 a bounce makes energy (and the
  // contact law cannot realise it), below 0 it has no meaning.
  if (!(s.bounce >= 0 && s.bounce <= 1))
    r.fail(el, "bounce", "must be in [0, 1], got " + format_number(s.bounce));
  s.bounce_threshold_m_s = r.number(el, "bounce_tresh", s.bounce_threshold_m_s);  // sic
  s.explicit_surface = s.mu >= 0;
}

bool read_visual_child(LoadContext& ctx, const Reader& r, const Element& c, ShapeType shape,
                       Visual& v, Material& m) {
  const std::string& n = c.name;
  if (n == "color_rgb") {
    v.color = r.color_rgb(c, v.color);
  } else if (n == "transparency") {
    v.color.a = r.number(c, "alpha", v.color.a);
  } else if (n == "texture") {
    visual_file(ctx, r, c, "name", "texture", v.texture);
    v.texture_scale = r.number(c, "scale", v.texture_scale);
  } else if (n == "mesh") {
    visual_file(ctx, r, c, "file", "mesh", v.mesh.file);
    visual_file(ctx, r, c, "shadowfile", "shadow mesh", v.mesh.shadow_file);
    v.mesh.scale = r.number(c, "scale", v.mesh.scale);
    v.mesh.offset_m = {r.number(c, "dx", v.mesh.offset_m.x), r.number(c, "dy", v.mesh.offset_m.y),
                       r.number(c, "dz", v.mesh.offset_m.z)};
    v.mesh.shadow = r.boolean(c, "shadow", v.mesh.shadow);
  } else if (n == "canvas" || n == "liquid") {
    if (shape != ShapeType::box) {
      ctx.warn(r.at(c), "<" + n + "> applies to cuboids only; ignored");
    } else if (n == "canvas") {
      v.canvas = true;
      v.canvas_width_px = r.integer_in(c, "width", v.canvas_width_px, 1, kMaxImageSide_px);
      v.canvas_height_px =  // SimTwo's spelling
          r.integer_in(c, "heigth", v.canvas_height_px, 1, kMaxImageSide_px);
    } else {
      v.liquid = true;
    }
  } else if (n == "painting_target") {
    v.painting_target = true;
  } else if (n == "metallic") {
    m.metallic = true;
  } else if (n == "ferromagnetic") {
    m.ferromagnetic = true;
  } else if (n == "rfidtag") {
    m.rfid_tag = true;
  } else {
    return false;
  }
  return true;
}

std::optional<int> load_solid(LoadContext& ctx, const Reader& r, const Element& el, int robot,
                              const std::vector<int>& list) {
  Scene& scene = ctx.scene;
  Body body;
  body.robot = robot;
  body.where = r.at(el);
  if (el.name == "cuboid") body.kind = SolidKind::cuboid;
  if (el.name == "cylinder") body.kind = SolidKind::cylinder;
  if (el.name == "sphere") body.kind = SolidKind::sphere;
  if (el.name == "belt") body.kind = SolidKind::belt;
  if (el.name == "propeller") {
    body.kind = SolidKind::propeller;
    body.thrust_coefficient = 0.1;
  }
  const ShapeType shape_type = body.kind == SolidKind::sphere     ? ShapeType::sphere
                               : body.kind == SolidKind::cylinder ? ShapeType::cylinder
                                                                  : ShapeType::box;

  std::optional<std::string> id;
  std::string id_kind;
  const Element* id_el = nullptr;
  double mass = 1;
  const Element* mass_el = nullptr;
  std::array<double, 6> inertia = {-1, -1, -1, 0, 0, 0};  // I11 I22 I33 I12 I13 I23
  PrimitiveFields prim;
  const Element* mother_el = nullptr;
  Surface surface;
  bool mu_given = false, mu2_given = false;
  Geom geom;
  geom.visual.color = Color{128 / 255.0, 128 / 255.0, 128 / 255.0, 1};

  for (const Element& c : el.children) {
    const std::string& n = c.name;
    if (n == "ID") {
      if (c.attribute("value")) id = r.text(c, "value", "");
      id_kind = r.text(c, "kind", id_kind);
      id_el = &c;
    } else if (n == "mass") {
      mass = r.number(c, "value", mass);
      mass_el = &c;
      static constexpr std::array<const char*, 6> names = {"I11", "I22", "I33",
                                                           "I12", "I13", "I23"};
      for (std::size_t i = 0; i < names.size(); ++i)
        inertia[i] = r.number(c, names[i], inertia[i]);
    } else if (prim.read(r, c)) {
    } else if (n == "solid") {
      mother_el = &c;
    } else if (n == "surface") {
      read_surface(r, c, surface);
      mu_given = mu_given || (r.has(c, "mu") && surface.mu >= 0);
      mu2_given = mu2_given || (r.has(c, "mu2") && surface.mu2 >= 0);
    } else if (n == "drag") {
      // SimTwo's per-step factors and quadratic coefficient (§4.4), applied by the `drag`
      // plugin (docs/models/fluids.md): bounded here so that a bad value is refused, located.
      body.drag.present = true;
      body.drag.coefficient = r.number(c, "coefficient", body.drag.coefficient);
      body.drag.stokes = r.number(c, "stokes", body.drag.stokes);
      body.drag.roll = r.number(c, "roll", body.drag.roll);
      if (!(body.drag.coefficient >= 0 && body.drag.coefficient <= kMaxFluidCoefficient))
        r.fail(c, "coefficient",
               "drag coefficient must be from 0 to " + format_number(kMaxFluidCoefficient) +
                   ", got " + format_number(body.drag.coefficient));
      if (!(body.drag.stokes >= 0 && body.drag.stokes < 1))
        r.fail(c, "stokes",
               "stokes is a per-step velocity factor from 0 to below 1, got " +
                   format_number(body.drag.stokes));
      if (!(body.drag.roll >= 0 && body.drag.roll < 1))
        r.fail(c, "roll",
               "roll is a per-step velocity factor from 0 to below 1, got " +
                   format_number(body.drag.roll));
    } else if (n == "buoyant" || n == "buoyance") {
      body.buoyancy.mass_kg = r.number(c, "mass", body.buoyancy.mass_kg);
      body.buoyancy.point_m = r.xyz(c, body.buoyancy.point_m);
      if (!(std::abs(body.buoyancy.mass_kg) <= kMaxFluidCoefficient))
        r.fail(c, "mass",
               "buoyant mass must be from -" + format_number(kMaxFluidCoefficient) + " to " +
                   format_number(kMaxFluidCoefficient) + " kg, got " +
                   format_number(body.buoyancy.mass_kg));
    } else if (n == "thrust") {
      body.thrust_coefficient = r.number(c, "coefficient", 0.1);
      if (!(std::abs(body.thrust_coefficient) <= kMaxFluidCoefficient))
        r.fail(c, "coefficient",
               "thrust coefficient must be from -" + format_number(kMaxFluidCoefficient) + " to " +
                   format_number(kMaxFluidCoefficient) + " N*s/rad, got " +
                   format_number(body.thrust_coefficient));
    } else if (n == "nogravity") {
      body.gravity = false;
    } else {
      read_visual_child(ctx, r, c, shape_type, geom.visual, geom.material);
    }
  }

  // Quirk 1, kept: without <ID value> SimTwo creates nothing (its sentinel ID is "-1").
  if (!id || *id == "-1") {
    ctx.warn(r.at(id_el ? *id_el : el, id_el ? "value" : ""),
             "<" + el.name + "> without <ID value> is not created (as in SimTwo)");
    return std::nullopt;
  }
  body.id = *id;

  if (!(mass > 0))
    r.fail(mass_el ? *mass_el : el, "value", "mass must be > 0, got " + format_number(mass));

  Shape& shape = geom.shape;
  shape.type = shape_type;
  auto positive = [&](const Element* where, const char* attr, double v) {
    PrimitiveFields::require_positive(r, el, where, attr, v);
  };
  if (shape_type == ShapeType::box) {
    shape.size_m = prim.box_size(r, el);
  } else if (shape_type == ShapeType::cylinder) {
    // Quirk 6, kept: the radius is `radius` when it differs from 1, else size x.
    if (prim.radius != 1) {
      positive(prim.radius_el, prim.radius_attr, prim.radius);
      shape.radius_m = prim.radius;
    } else {
      positive(prim.size_el, "x", prim.size.x);
      shape.radius_m = prim.size.x;
    }
    positive(prim.size_el, "z", prim.size.z);
    shape.length_m = prim.size.z;
  } else {
    positive(prim.radius_el, prim.radius_attr, prim.radius);
    shape.radius_m = prim.radius;
  }

  body.mass_kg = mass;
  if (inertia[0] > 0 && inertia[1] > 0 && inertia[2] > 0) {
    body.inertia_kg_m2 = Mat3{{{inertia[0], inertia[3], inertia[4]},
                               {inertia[3], inertia[1], inertia[5]},
                               {inertia[4], inertia[5], inertia[2]}}};
  } else {
    body.inertia_kg_m2 = uniform_inertia(shape, mass);
  }

  Pose local{prim.pos, rotation_from_rot_deg(prim.rot_deg)};
  if (mother_el) {
    const std::string mother = r.text(*mother_el, "id", "");
    const int m = find_body(scene, list, mother, false);
    if (m < 0)
      r.fail(*mother_el, "id", "no earlier solid with ID '" + mother + "' in the same list");
    local = scene.bodies[static_cast<std::size_t>(m)].pose * local;
  }
  body.pose = local;

  // Omni/mecanum wheels: anisotropic friction with SimTwo's mu = 1, mu2 = 0.001, but an
  // explicit <surface> mu/mu2 wins (S2Sim deviation from quirk 2).
  const std::string k = lower(id_kind);
  if (k == "omni" || k == "mecanumleft" || k == "mecanumright") {
    geom.friction = k == "omni"          ? FrictionKind::omni
                    : k == "mecanumleft" ? FrictionKind::mecanum_left
                                         : FrictionKind::mecanum_right;
    if (!mu_given) surface.mu = 1;
    if (!mu2_given) surface.mu2 = 0.001;
    surface.explicit_surface = true;
  }

  geom.id = body.id;
  geom.surface = surface;
  geom.where = body.where;
  body.geoms.push_back(std::move(geom));
  scene.bodies.push_back(std::move(body));
  return static_cast<int>(scene.bodies.size() - 1);
}

}  // namespace s2sim::scene::detail
