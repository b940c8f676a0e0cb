/// \file
/// `<shells>` (simtwo-format.md §4.6): extra primitives rigidly attached to a robot body.
/// Massive shells are merged physically (S2Sim deviation from quirk 19): the body frame
/// stays, mass adds, the centre of mass moves and inertias combine by the parallel-axis
/// theorem with the shell's rotation (shell cylinders along their own Z).

#include "scene/limits.hpp"
#include "scene/loading.hpp"
#include "scene/mass.hpp"
#include "scene/primitive.hpp"
#include "scene/rotation.hpp"

namespace s2sim::scene::detail {

void load_shells(LoadContext& ctx, const Reader& r, const Element& shells, int robot) {
  Scene& scene = ctx.scene;
  for (const Element& el : shells.children) {
    const std::string& kind = el.name;
    if (kind != "cuboid" && kind != "cylinder" && kind != "sphere" && kind != "camera") continue;
    const Robot& rb = scene.robots[static_cast<std::size_t>(robot)];

    Geom g;
    g.is_shell = true;
    g.id = "Shell";
    g.where = r.at(el);
    g.visual.color = Color{128 / 255.0, 128 / 255.0, 128 / 255.0, 1};
    g.shape.type = kind == "cylinder" ? ShapeType::cylinder
                   : kind == "sphere" ? ShapeType::sphere
                                      : ShapeType::box;
    int body = rb.main_body;
    double mass = 0;
    const Element* mass_el = nullptr;
    PrimitiveFields prim;
    Camera camera;

    for (const Element& c : el.children) {
      const std::string& n = c.name;
      if (n == "ID") {
        g.id = r.text(c, "value", g.id);
      } else if (n == "solid") {
        const std::string id = r.text(c, "id", "");
        body = find_body(scene, rb.bodies, id, false);
        if (body < 0 && rb.main_body >= 0) {
          // SimTwo's fallback for an unknown mother (IndexFromID = -1): the main body.
          ctx.warn(r.at(c, "id"), "no solid with ID '" + id +
                                      "' in this robot; the shell goes on the main body '" +
                                      scene.bodies[static_cast<std::size_t>(rb.main_body)].id +
                                      "'");
          body = rb.main_body;
        }
      } else if (n == "mass") {
        mass = r.number(c, "value", mass);
        mass_el = &c;
      } else if (prim.read(r, c)) {
      } else if (n == "surface") {
        read_surface(r, c, g.surface);
      } else if (n == "focal" && kind == "camera") {
        camera.focal_length = r.number(c, "length", camera.focal_length);
      } else if (n == "frame" && kind == "camera") {
        camera.decimation = r.integer_in(c, "decimation", camera.decimation, 1, kMaxImageSide_px);
        camera.width_px = r.integer_in(c, "width", camera.width_px, 1, kMaxImageSide_px);
        camera.height_px = r.integer_in(c, "height", camera.height_px, 1, kMaxImageSide_px);
      } else {
        read_visual_child(ctx, r, c, g.shape.type, g.visual, g.material);
      }
    }
    if (body < 0) r.fail(el, "", "shell of a robot without solids");

    if (mass < 0)
      r.fail(mass_el ? *mass_el : el, "value", "mass must be >= 0, got " + format_number(mass));
    if (g.shape.type == ShapeType::box) {
      g.shape.size_m = prim.box_size(r, el);
    } else if (g.shape.type == ShapeType::cylinder) {
      // Shell cylinders: radius = size x, length = size z (quirk 6).
      PrimitiveFields::require_positive(r, el, prim.size_el, "x", prim.size.x);
      PrimitiveFields::require_positive(r, el, prim.size_el, "z", prim.size.z);
      g.shape.radius_m = prim.size.x;
      g.shape.length_m = prim.size.z;
    } else {
      PrimitiveFields::require_positive(r, el, prim.radius_el, prim.radius_attr, prim.radius);
      g.shape.radius_m = prim.radius;
    }
    if (kind == "camera") g.camera = camera;
    g.pose = Pose{prim.pos, rotation_from_rot_deg(prim.rot_deg)};
    // A camera shell is also a camera sensor, named by its ID ("Shell" when it has none).
    if (kind == "camera") add_camera_shell(ctx, r, el, robot, body, g.pose, g.id);

    Body& b = scene.bodies[static_cast<std::size_t>(body)];
    if (mass > 0) {
      const Mat3& R = g.pose.rotation;
      add_rigid_part(b, mass, prim.pos, R * uniform_inertia(g.shape, mass) * R.transposed());
    }
    scene.robots[static_cast<std::size_t>(robot)].shells.emplace_back(
        body, static_cast<int>(b.geoms.size()));
    b.geoms.push_back(std::move(g));
  }
}

}  // namespace s2sim::scene::detail
