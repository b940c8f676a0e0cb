#pragma once
/// \file
/// What the contact query finds: points of contact between two shapes, or a shape and a
/// plane, before any force.

#include "collision/shape.hpp"

#include <cstdint>

namespace s2sim::collision {

/// Most points one primitive pair can produce (a box on a plane: its 8 corners).
constexpr int kMaxPointsPerPair = 8;

/// One point of contact found by the narrow phase.
struct ContactPoint {
  Vec3 point_m;  ///< on shape a's surface, world frame
  Vec3 normal;   ///< unit, from b toward a (pushes a out of b)
  double depth_m = 0;
  std::int32_t feature = 0;  ///< stable id of the point within its pair (corner, rim point...)
};

}  // namespace s2sim::collision
