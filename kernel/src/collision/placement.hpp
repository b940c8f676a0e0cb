#pragma once
/// \file
/// Where the shapes of a ShapeTable are for one set of body poses: each shape's world pose and
/// exact world box. Static shapes are placed once; `update` places the moving ones, once per
/// pose set (contact: every substep; ray casting: lazily, once per tick). Each query owns the
/// placement of the poses it answers for.

#include "collision/shape_table.hpp"

#include <vector>

namespace s2sim::collision {

class Placement {
 public:
  Placement() = default;
  /// Places the static shapes; the moving ones wait for `update`. The boxes are exact, or
  /// grown by `margin` on every side (a query's guard against round-off).
  explicit Placement(const ShapeTable& table, double margin = 0);

  /// `poses` per kernel body (0 = world).
  void update(const ShapeTable& table, const Pose* poses);

  const Pose* world() const { return world_.data(); }
  const Aabb* boxes() const { return box_.data(); }

 private:
  double margin_ = 0;
  std::vector<Pose> world_;
  std::vector<Aabb> box_;
};

}  // namespace s2sim::collision
