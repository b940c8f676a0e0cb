/// \file
/// Obstacle files (simtwo-format.md §5): static geoms placed with the scene element's offset.
/// Their `<defines>` write into the global table G (quirk 16, kept).

#include "scene/loading.hpp"
#include "scene/primitive.hpp"
#include "scene/rotation.hpp"
#include "scene/xml.hpp"

#include <algorithm>

namespace s2sim::scene::detail {

void load_obstacles_file(LoadContext& ctx, const std::filesystem::path& file,
                         ConstantTable& globals, const std::string& id_prefix, const Pose& offset) {
  const std::string display = ctx.display(file);
  const Element root = read_xml_file(file, display);
  if (root.name != "obstacles")
    throw Error(ErrorKind::scene, Location{display, root.path, ""},
                "expected an <obstacles> file, found <" + root.name + ">");
  const Reader r(display, globals);
  for (const Element& el : root.children) {
    if (el.name == "defines") {
      apply_defines(el, r, globals);
      continue;
    }
    if (el.name != "cuboid" && el.name != "cylinder" && el.name != "sphere") continue;

    Geom g;
    g.where = r.at(el);
    g.visual.color = Color{128 / 255.0, 128 / 255.0, 128 / 255.0, 1};
    g.shape.type = el.name == "cylinder" ? ShapeType::cylinder
                   : el.name == "sphere" ? ShapeType::sphere
                                         : ShapeType::box;
    std::string id;
    PrimitiveFields prim;
    prim.radius = 0;  // obstacle spheres need an explicit <radius value> (§5)
    for (const Element& c : el.children) {
      const std::string& n = c.name;
      if (n == "ID") {
        id = r.text(c, "name", r.text(c, "value", id));
      } else if (prim.read(r, c, /*size_radius_sets_x=*/true)) {
      } else if (n == "surface") {
        read_surface(r, c, g.surface);
      } else {
        read_visual_child(ctx, r, c, g.shape.type, g.visual, g.material);  // `imovable` ignored
      }
    }
    auto positive = [&](const Element* where, const char* attr, double v) {
      PrimitiveFields::require_positive(r, el, where, attr, v);
    };
    const Vec3& size = prim.size;
    const double radius = prim.radius;
    const Element* size_el = prim.size_el;
    const Element* radius_el = prim.radius_el;
    if (g.shape.type == ShapeType::box) {
      g.shape.size_m = prim.box_size(r, el);
    } else if (g.shape.type == ShapeType::cylinder) {
      g.shape.radius_m = std::max(radius, size.x);  // quirk 6, kept
      positive(radius > size.x ? radius_el : size_el, radius > size.x ? "value" : "x",
               g.shape.radius_m);
      positive(size_el, "z", size.z);
      g.shape.length_m = size.z;
    } else {
      if (!radius_el) r.fail(el, "", "a sphere obstacle needs <radius value>");
      positive(radius_el, "value", radius);
      g.shape.radius_m = radius;
    }
    if (id.empty())
      id = "Obstacle at (" + format_number(prim.pos.x) + ", " + format_number(prim.pos.y) + ", " +
           format_number(prim.pos.z) + ")";
    g.id = id_prefix + id;
    // Offset applied as R_off·R_local (S2Sim fixes quirk 17's R_local·R_off).
    g.pose = offset * Pose{prim.pos, rotation_from_rot_deg(prim.rot_deg)};
    ctx.scene.obstacles.push_back(std::move(g));
  }
}

}  // namespace s2sim::scene::detail
