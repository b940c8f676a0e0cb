#pragma once
/// \file
/// Box against box without FCL: the separating-axis test over the 15 axes (3 face normals of
/// each box, 9 edge-edge cross products), then one point for an edge-edge contact or the
/// reference face clipped against the incident face for up to 4 points. This is the algorithm
/// of ODE's dBoxBox as FCL's boxBox2 carries it, re-written on the kernel's Vec3/Mat3 with the
/// same arithmetic, so that it gives boxBox2's points, normals, depths and point order to the
/// last bit (tests/kernel/collision/box_box_test.cpp compares the two).

#include "collision/contact_point.hpp"

namespace s2sim::collision {

/// Most points box_box writes.
constexpr int kMaxBoxBoxPoints = 4;

/// Contacts of box a (half sides `half_a_m`, world pose `pose_a`) against box b (`half_b_m`,
/// `pose_b`) with the conventions of contact_primitives.hpp: normals from b toward a, points on
/// a's surface, `feature` the point's index. Writes at most kMaxBoxBoxPoints points to `out`
/// and returns the count. With `margin_m` > 0, b's box is grown by the margin on every side and
/// the depths reduced by it: points closer than the margin come out with a negative depth (the
/// speculative points). Allocates nothing.
int box_box(const Vec3& half_a_m, const Pose& pose_a, const Vec3& half_b_m, const Pose& pose_b,
            ContactPoint* out, double margin_m = 0);

}  // namespace s2sim::collision
