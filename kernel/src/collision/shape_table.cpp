#include "collision/shape_table.hpp"

#include <s2sim/component.hpp>

#include <algorithm>
#include <cmath>

namespace s2sim::collision {
namespace {

Shape make_shape(const scene::Geom& g) {
  Shape s;
  switch (g.shape.type) {
    case scene::ShapeType::box:
      s.kind = ShapeKind::box;
      s.half_extents_m = g.shape.size_m * 0.5;
      s.bounding_radius_m = norm(s.half_extents_m);
      break;
    case scene::ShapeType::cylinder:
      s.kind = ShapeKind::cylinder;
      s.radius_m = g.shape.radius_m;
      s.half_length_m = 0.5 * g.shape.length_m;
      s.bounding_radius_m = std::hypot(s.radius_m, s.half_length_m);
      break;
    case scene::ShapeType::sphere:
      s.kind = ShapeKind::sphere;
      s.radius_m = g.shape.radius_m;
      s.bounding_radius_m = s.radius_m;
      break;
    case scene::ShapeType::convex:
      s.kind = ShapeKind::convex;
      s.hull = g.shape.hull.get();
      for (const Vec3& v : s.hull->vertices)
        s.bounding_radius_m = std::max(s.bounding_radius_m, norm(v));
      break;
  }
  s.mid_plane = g.friction != scene::FrictionKind::isotropic;
  return s;
}

Surface make_surface(const scene::Geom& g) {
  Surface s;
  s.has_mu = g.surface.explicit_surface && g.surface.mu >= 0;
  s.mu = g.surface.mu;
  s.mu2 = g.surface.mu2;
  s.softness = g.surface.softness;
  s.restitution = g.surface.bounce;
  s.restitution_threshold_m_s = g.surface.bounce_threshold_m_s;
  switch (g.friction) {
    case scene::FrictionKind::isotropic:
      s.anisotropy = Anisotropy::none;
      break;
    case scene::FrictionKind::omni:
      s.anisotropy = Anisotropy::omni;
      break;
    case scene::FrictionKind::mecanum_left:
      s.anisotropy = Anisotropy::mecanum_left;
      break;
    case scene::FrictionKind::mecanum_right:
      s.anisotropy = Anisotropy::mecanum_right;
      break;
  }
  return s;
}

std::uint32_t make_material(const scene::Geom& g) {
  std::uint32_t m = 0;
  if (g.material.metallic) m |= material_metallic;
  if (g.material.ferromagnetic) m |= material_ferromagnetic;
  if (g.material.rfid_tag) m |= material_rfid_tag;
  if (g.visual.canvas) m |= material_canvas;
  return m;
}

}  // namespace

Vec3 extent(const Shape& s, const Mat3& r) {
  Vec3 e;
  switch (s.kind) {
    case ShapeKind::box:
      e = {std::abs(r.m[0][0]) * s.half_extents_m.x + std::abs(r.m[0][1]) * s.half_extents_m.y +
               std::abs(r.m[0][2]) * s.half_extents_m.z,
           std::abs(r.m[1][0]) * s.half_extents_m.x + std::abs(r.m[1][1]) * s.half_extents_m.y +
               std::abs(r.m[1][2]) * s.half_extents_m.z,
           std::abs(r.m[2][0]) * s.half_extents_m.x + std::abs(r.m[2][1]) * s.half_extents_m.y +
               std::abs(r.m[2][2]) * s.half_extents_m.z};
      break;
    case ShapeKind::cylinder: {
      // Exact: the axis contributes |a_i|·half_length, the rim disc r·sqrt(1 - a_i²).
      const Vec3 a = r.column(2);
      auto extent = [&](double ai) {
        return std::abs(ai) * s.half_length_m + s.radius_m * std::sqrt(std::max(0.0, 1 - ai * ai));
      };
      e = {extent(a.x), extent(a.y), extent(a.z)};
      break;
    }
    case ShapeKind::sphere:
      e = {s.radius_m, s.radius_m, s.radius_m};
      break;
    case ShapeKind::convex:
      // The hull's turned vertices, each side's farthest from the shape origin.
      for (const Vec3& v : s.hull->vertices) {
        const Vec3 p = r * v;
        e = {std::max(e.x, std::abs(p.x)), std::max(e.y, std::abs(p.y)),
             std::max(e.z, std::abs(p.z))};
      }
      break;
  }
  return e;
}

ShapeTable::ShapeTable(const scene::Scene& scene) {
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const auto& body = scene.bodies[i];
    for (std::size_t g = 0; g < body.geoms.size(); ++g)
      add(body.geoms[g], static_cast<std::int32_t>(i + 1),
          body.kind == scene::SolidKind::belt && g == 0);
  }
  for (const auto& obstacle : scene.obstacles)
    add(obstacle, 0, false);

  planes_.push_back({{0, 0, 1}, 0});  // the ground
  walls_ = scene.settings.world_walls;
  wall_distance_m_ = scene.settings.world_wall_distance_m;
  if (walls_) {
    const double d = wall_distance_m_;
    planes_.push_back({{1, 0, 0}, -d});
    planes_.push_back({{-1, 0, 0}, -d});
    planes_.push_back({{0, 1, 0}, -d});
    planes_.push_back({{0, -1, 0}, -d});
  }
}

void ShapeTable::add(const scene::Geom& g, std::int32_t body, bool belt) {
  const auto index = static_cast<std::int32_t>(shape_.size());
  shape_.push_back(make_shape(g));
  if (g.shape.hull) hulls_.push_back(g.shape.hull);
  body_.push_back(body);
  local_.push_back(g.pose);
  local_identity_.push_back(g.pose.position == Vec3{} && g.pose.rotation == Mat3::identity());
  surface_.push_back(make_surface(g));
  surface_.back().belt = belt;
  material_.push_back(make_material(g));
  (body == 0 ? statics_ : moving_).push_back(index);
}

void ShapeTable::reshape(std::int32_t shape, const scene::Geom& geom) {
  shape_.at(static_cast<std::size_t>(shape)) = make_shape(geom);
}

std::int32_t ShapeTable::first_shape_of(std::int32_t body) const {
  for (std::size_t s = 0; s < body_.size(); ++s)
    if (body_[s] == body) return static_cast<std::int32_t>(s);
  return -1;
}

}  // namespace s2sim::collision
