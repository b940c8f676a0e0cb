#pragma once
/// \file
/// The contact layer's view of the scene: collision shapes on bodies, static planes, and the
/// contact points the narrow phase finds. Plain data with the SDK's math types; no Simbody,
/// no Eigen (FCL lives in fcl_pairs.cpp alone).

#include <s2sim/math.hpp>

#include <cstdint>

namespace s2sim::contact {

enum class ShapeKind : std::uint8_t { box, cylinder, sphere };

/// Anisotropic friction (spec §4.3): the direction of the full coefficient `mu`; `mu2` acts
/// across it.
enum class Anisotropy : std::uint8_t { none, omni, mecanum_left, mecanum_right };

/// Contact parameters of one surface, as written in the scene.
struct SurfaceParams {
  bool has_mu = false;  ///< an explicit mu (SimTwo's "has surface")
  double mu = 0;        ///< along the first friction direction (all directions if isotropic)
  double mu2 = -1;      ///< across it, for anisotropic surfaces; -1 = same as mu
  double softness = 1e-5;
  double restitution = 0;
  double restitution_threshold_m_s = 0;
  /// Hunt–Crossley's alpha·v_in that rebounds at `restitution` (contact_force.hpp), at load.
  double restitution_beta = 0;
};

/// One collision primitive attached to a body (index 0 = the world: obstacles).
struct Shape {
  ShapeKind kind = ShapeKind::box;
  Vec3 half_extents_m;       ///< box
  double radius_m = 0;       ///< cylinder, sphere
  double half_length_m = 0;  ///< cylinder, along local Z
  std::int32_t body = 0;     ///< kernel body index; 0 = static
  Pose local;                ///< shape frame in the body frame (world frame when static)
  SurfaceParams surface;
  Anisotropy anisotropy = Anisotropy::none;
  bool belt = false;                   ///< surface moves along its local +X at the belt speed
  std::int32_t belt_speed_input = -1;  ///< kernel input holding that speed (m/s)
  double bounding_radius_m = 0;        ///< about the shape origin
};

/// A static half-space boundary: points p with dot(normal, p) < offset_m are inside matter.
struct Plane {
  Vec3 normal;  ///< unit, pointing out of the matter
  double offset_m = 0;
};

/// One point of contact found by the narrow phase, before forces.
struct ContactPoint {
  Vec3 point_m;  ///< on shape a's surface, world frame
  Vec3 normal;   ///< unit, from b toward a (pushes a out of b)
  double depth_m = 0;
  std::int32_t feature = 0;  ///< stable id of the point within its pair (corner, rim point...)
};

}  // namespace s2sim::contact
