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
  /// Shape `shape` changed its primitive (ShapeTable::reshape): its reach again.
  void reshaped(const ShapeTable& table, std::int32_t shape);

  /// `poses` per kernel body (0 = world).
  void update(const ShapeTable& table, const Pose* poses);
  /// The same, and each moving shape's speculative margin (docs/models/contact.md,
  /// "Speculative contact"): the distance its surface can travel in `step_s` at the speed its
  /// body's `twists` give it (body origin's velocity, world frame), at most `max_margin_m`,
  /// and 0 when below `min_margin_m` (slow shapes are placed exactly as by the plain update,
  /// which is this one without `twists`);
  /// its box grows by that margin, so that the pairs and planes it may reach within the step
  /// are found before they touch.
  void update(const ShapeTable& table, const Pose* poses, const Twist* twists, double step_s,
              double min_margin_m, double max_margin_m);
  /// The same for the moving shapes `shapes[0 .. count)` only (one part of the island-parallel
  /// step places its own); the others keep where they were.
  void update(const ShapeTable& table, const Pose* poses, const Twist* twists, double step_s,
              double min_margin_m, double max_margin_m, const std::int32_t* shapes,
              std::size_t count);

  const Pose* world() const { return world_.data(); }
  const Aabb* boxes() const { return box_.data(); }
  /// Per shape, its speculative margin (0 for static shapes and after the plain `update`).
  const double* margins() const { return speculative_m_.data(); }

 private:
  double margin_ = 0;
  std::vector<Pose> world_;
  std::vector<Aabb> box_;
  std::vector<double> speculative_m_;
  std::vector<double> reach2_m2_;  // per shape: (its farthest point from its body origin)²
};

}  // namespace s2sim::collision
