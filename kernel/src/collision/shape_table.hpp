#pragma once
/// \file
/// The one table of the scene's collision geometry, shared by contact and ray casting: every
/// collision shape (robot solids, shells, tyres, things, static obstacles) as a structure of
/// arrays, and the static planes (the ground, SimTwo's walls). Built once at load; afterwards
/// only a run-time thing's primitive changes (`reshape`). Where the shapes are at a given set
/// of body poses is a `Placement`.
///
/// Shape order: every body's geoms in body order, then the obstacles (body 0). Contact keys
/// its memory by these indices, so the order is part of the physics' behaviour.

#include "collision/shape.hpp"

#include <s2sim/kernel/scene.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace s2sim::collision {

class ShapeTable {
 public:
  explicit ShapeTable(const scene::Scene& scene);

  std::int32_t size() const { return static_cast<std::int32_t>(shape_.size()); }

  /// Gives shape `shape` (on a moving body) the primitive of `geom`, its frame and surface
  /// kept: what a thing added while running takes (sim/runtime_things.cpp). Whoever caches a
  /// shape's reach (Placement) must be told.
  void reshape(std::int32_t shape, const scene::Geom& geom);
  /// Gives shape `shape` a surface (a script's SetSolidSurfaceFriction); contact must be told.
  void set_surface(std::int32_t shape, const Surface& surface) {
    surface_.at(static_cast<std::size_t>(shape)) = surface;
  }
  /// The first shape on kernel body `body` (its own primitive), -1 if it has none.
  std::int32_t first_shape_of(std::int32_t body) const;
  /// Per shape: geometry, kernel body index (0 = static, in the world frame), shape frame in
  /// the body frame, whether that frame is the body's own, surface, and the material bits
  /// ray hits report (s2sim::material_*).
  const std::vector<Shape>& shapes() const { return shape_; }
  const std::vector<std::int32_t>& bodies() const { return body_; }
  const std::vector<Pose>& local_poses() const { return local_; }
  const std::vector<char>& local_identity() const { return local_identity_; }
  const std::vector<Surface>& surfaces() const { return surface_; }
  const std::vector<std::uint32_t>& materials() const { return material_; }

  /// Indices of the shapes on moving bodies, then of the static ones, each in table order.
  const std::vector<std::int32_t>& moving() const { return moving_; }
  const std::vector<std::int32_t>& statics() const { return statics_; }

  /// The ground (first) and, when the scene has them, the four walls.
  const std::vector<Plane>& planes() const { return planes_; }
  bool walls() const { return walls_; }
  double wall_distance_m() const { return wall_distance_m_; }

 private:
  void add(const scene::Geom& g, std::int32_t body, bool belt);

  std::vector<Shape> shape_;
  std::vector<std::int32_t> body_;
  std::vector<Pose> local_;
  std::vector<char> local_identity_;
  std::vector<Surface> surface_;
  std::vector<std::uint32_t> material_;
  std::vector<std::int32_t> moving_, statics_;
  std::vector<Plane> planes_;
  std::vector<std::shared_ptr<const scene::ConvexHull>> hulls_;  ///< what convex shapes point at
  bool walls_ = false;
  double wall_distance_m_ = 0;
};

}  // namespace s2sim::collision
