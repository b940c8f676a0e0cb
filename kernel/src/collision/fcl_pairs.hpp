#pragma once
/// \file
/// Narrow phase by FCL for the pairs without an analytic path here: box-box (FCL's ODE-derived
/// boxBox2, up to 4 points, called directly so that no vector is allocated), and pairs with a
/// cylinder (GJK/EPA through libccd, one point). FCL and Eigen stay in fcl_pairs.cpp: Simbody's
/// headers break Eigen's templates.

#include "collision/contact_point.hpp"

#include <memory>

namespace s2sim::collision {

class FclPairs {
 public:
  FclPairs();
  ~FclPairs();
  FclPairs(const FclPairs&) = delete;
  FclPairs& operator=(const FclPairs&) = delete;

  /// Contacts of shape a at `pose_a` against shape b at `pose_b` (world poses); writes at
  /// most 4 points to `out` with the conventions of contact_primitives.hpp and returns the count.
  int collide(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b,
              ContactPoint* out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace s2sim::collision
