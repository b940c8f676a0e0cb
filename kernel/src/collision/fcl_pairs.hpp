#pragma once
/// \file
/// Narrow phase by FCL for the pairs with a cylinder or a convex hull (GJK/EPA through libccd,
/// one point), and
/// box-box by FCL's ODE-derived boxBox2 (up to 4 points, called directly so that no vector is
/// allocated): the contact query solves two boxes with box_box.hpp, which gives the same
/// points, and keeps this path as its reference (tests/kernel/collision/box_box_test.cpp). FCL
/// and Eigen stay in fcl_pairs.cpp: Simbody's headers break Eigen's templates.

#include "collision/contact_point.hpp"

#include <memory>
#include <vector>

namespace s2sim::collision {

class FclPairs {
 public:
  FclPairs();
  ~FclPairs();
  FclPairs(const FclPairs&) = delete;
  FclPairs& operator=(const FclPairs&) = delete;

  /// Contacts of shape a at `pose_a` against shape b at `pose_b` (world poses); writes at
  /// most 4 points to `out` with the conventions of contact_primitives.hpp and returns the count.
  /// Two boxes within `margin_m` of each other give their speculative points (negative depth,
  /// from b's box grown by the margin); other pairs report touching points only.
  int collide(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b,
              ContactPoint* out, double margin_m = 0);

  /// Builds FCL's convex object of every convex shape of `shapes` once, before any step:
  /// `collide` then finds them without allocating.
  void prepare(const std::vector<Shape>& shapes);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace s2sim::collision
