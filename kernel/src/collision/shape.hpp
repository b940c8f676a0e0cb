#pragma once
/// \file
/// The collision layer's vocabulary: the geometry of one collision shape in its own frame,
/// its surface as written in the scene, world-aligned bounding boxes and static planes. Plain
/// data with the SDK's math types; no Simbody, no Eigen (FCL lives in fcl_pairs.cpp alone).

#include <s2sim/math.hpp>

#include <algorithm>
#include <cstdint>

namespace s2sim::scene {
struct ConvexHull;
}

namespace s2sim::collision {

/// `convex`: a mesh's convex hull (scene::ConvexHull, kept alive by the ShapeTable).
enum class ShapeKind : std::uint8_t { box, cylinder, sphere, convex };

/// The geometry of one primitive in its own frame (a cylinder's axis is local Z).
/// (Members ordered so that the hull pointer keeps the struct at 64 bytes, one cache line.)
struct Shape {
  ShapeKind kind = ShapeKind::box;
  /// A cylinder that touches a plane at its mid-plane only (omni and mecanum wheels roll on
  /// their rollers' crowns), not at its tread's two edges.
  bool mid_plane = false;
  Vec3 half_extents_m;                      ///< box
  double radius_m = 0;                      ///< cylinder, sphere
  double half_length_m = 0;                 ///< cylinder, along local Z
  double bounding_radius_m = 0;             ///< about the shape origin
  const scene::ConvexHull* hull = nullptr;  ///< convex: vertices, faces, in the shape frame
};
static_assert(sizeof(Shape) == 64, "a shape fills one cache line");

/// Anisotropic friction (spec §4.3): the direction of the full coefficient `mu`; `mu2` acts
/// across it.
enum class Anisotropy : std::uint8_t { none, omni, mecanum_left, mecanum_right };

/// Contact parameters of one surface, as written in the scene.
struct Surface {
  bool has_mu = false;  ///< an explicit mu (SimTwo's "has surface")
  double mu = 0;        ///< along the first friction direction (all directions if isotropic)
  double mu2 = -1;      ///< across it, for anisotropic surfaces; -1 = same as mu
  double softness = 1e-5;
  double restitution = 0;
  double restitution_threshold_m_s = 0;
  Anisotropy anisotropy = Anisotropy::none;
  bool belt = false;  ///< a conveyor's belt: the surface moves along its local +X
};

/// A world-aligned bounding box.
struct Aabb {
  Vec3 min, max;
};

/// Whether two boxes overlap (touching counts).
inline bool overlap(const Aabb& a, const Aabb& b) {
  return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y &&
         a.min.z <= b.max.z && b.min.z <= a.max.z;
}

/// The smallest box holding both.
inline Aabb united(const Aabb& a, const Aabb& b) {
  return {{std::min(a.min.x, b.min.x), std::min(a.min.y, b.min.y), std::min(a.min.z, b.min.z)},
          {std::max(a.max.x, b.max.x), std::max(a.max.y, b.max.y), std::max(a.max.z, b.max.z)}};
}

/// A static half-space boundary: points p with dot(normal, p) < offset_m are inside matter.
struct Plane {
  Vec3 normal;  ///< unit, pointing out of the matter
  double offset_m = 0;
};

/// Half the sides of the exact world-aligned box of `shape` turned by `rotation`.
Vec3 extent(const Shape& shape, const Mat3& rotation);

/// The world-aligned box of `shape` at world pose `pose`, exact when `margin` is 0, else
/// grown by `margin` on every side.
inline Aabb bounds(const Shape& shape, const Pose& pose, double margin = 0) {
  Vec3 e = extent(shape, pose.rotation);
  if (margin != 0) e += Vec3{margin, margin, margin};
  return {pose.position - e, pose.position + e};
}

}  // namespace s2sim::collision
