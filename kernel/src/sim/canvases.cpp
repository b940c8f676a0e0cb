/// \file
/// SimTwo's canvases (simtwo-format.md, `<canvas width heigth>`): a paintable bitmap on the
/// local +Z face of a solid's or obstacle's box. The kernel owns each one as an rgb8 image,
/// white until a component writes it (the script's TCanvas, docs/scripting.md) and again
/// after a reset; the renderer draws it on the face (docs/rendering.md).

#include "sim/names.hpp"
#include "sim/simulation_impl.hpp"

namespace s2sim {

std::string Simulation::Impl::solid_canvas_name(int body) const {
  const scene::Body& b = scene.bodies[static_cast<std::size_t>(body)];
  const std::string path =
      b.robot >= 0 ? sim::solid_path(robot_prefix(b.robot), b.id) : sim::thing_path(b.id);
  return sim::field_path(path, "canvas");
}

std::string Simulation::Impl::obstacle_canvas_name(int obstacle) {
  return "obstacles/" + std::to_string(obstacle) + "/canvas";
}

void Simulation::Impl::declare_canvases() {
  auto declare = [&](const scene::Geom& g, const std::string& name) {
    if (!g.visual.canvas) return;
    if (g.shape.type != scene::ShapeType::box) {
      warnings.push_back(g.where.str() + ": '" + g.id +
                         "' is not a box: SimTwo draws a canvas on boxes only, so it has none");
      return;
    }
    const std::int32_t i =
        add_image(name, g.visual.canvas_width_px, g.visual.canvas_height_px, PixelFormat::rgb8, -1);
    image_slots[static_cast<std::size_t>(i)].blank = 0xFF;
  };
  const int spare = scene.runtime_things.empty() ? -1 : scene.runtime_things.front();
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    if (spare >= 0 && static_cast<int>(b) >= spare) break;  // a thing added while running
    const scene::Body& body = scene.bodies[b];
    if (!body.geoms.empty()) declare(body.geoms[0], solid_canvas_name(static_cast<int>(b)));
  }
  for (std::size_t o = 0; o < scene.obstacles.size(); ++o)
    declare(scene.obstacles[o], obstacle_canvas_name(static_cast<int>(o)));
}

}  // namespace s2sim
