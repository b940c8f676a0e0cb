#pragma once
/// \file
/// Analytic ray tests against S2Sim's collision primitives, each in its own local frame.
///
/// Every test takes a ray origin `o` and a unit direction `d` in the primitive's frame and a
/// maximum distance `t_max`; it returns whether the ray *enters* the primitive at a distance
/// t in [0, t_max] and, if so, writes t and the outward unit normal at the entry point (local
/// frame). A ray that starts inside a primitive does not see it (only entry surfaces count:
/// a sensor mounted inside a shell of its robot is not blinded by it).

#include <s2sim/math.hpp>

#include <cmath>
#include <utility>

namespace s2sim::scene {
struct ConvexHull;
}

namespace s2sim::collision {

/// Axis-aligned box centred at the origin with half extents `half` (slab test).
bool ray_box(const Vec3& o, const Vec3& d, const Vec3& half, double t_max, double& t, Vec3& n);

/// Sphere of radius `r` centred at the origin.
bool ray_sphere(const Vec3& o, const Vec3& d, double r, double t_max, double& t, Vec3& n);

/// Capped cylinder along local Z, radius `r`, from z = -half_length to +half_length.
/// A convex hull (scene::ConvexHull) in its own frame, hit from outside.
bool ray_convex(const Vec3& o, const Vec3& d, const scene::ConvexHull& hull, double t_max,
                double& t, Vec3& n);

bool ray_cylinder(const Vec3& o, const Vec3& d, double r, double half_length, double t_max,
                  double& t, Vec3& n);

/// Plane through `point` with unit normal `normal`; only its front side (where the normal
/// points) is seen: a ray from behind passes through.
bool ray_plane(const Vec3& o, const Vec3& d, const Vec3& point, const Vec3& normal, double t_max,
               double& t);

/// Whether the segment o + s d, s in [0, t_max], meets the box [lo, hi] (world AABB test);
/// `inv_d` is 1/d per component (±inf for 0). On success [t0, t1] is the overlap. Inline: it
/// is the broad phase's innermost test.
inline bool ray_aabb(const Vec3& o, const Vec3& inv_d, const Vec3& lo, const Vec3& hi, double t_max,
                     double& t0, double& t1) {
  double a = 0, b = t_max;
  auto slab = [&](double oi, double inv, double l, double h) {
    if (std::isinf(inv)) return oi >= l && oi <= h;
    double s0 = (l - oi) * inv, s1 = (h - oi) * inv;
    if (s0 > s1) std::swap(s0, s1);
    a = s0 > a ? s0 : a;
    b = s1 < b ? s1 : b;
    return a <= b;
  };
  if (!slab(o.x, inv_d.x, lo.x, hi.x) || !slab(o.y, inv_d.y, lo.y, hi.y) ||
      !slab(o.z, inv_d.z, lo.z, hi.z))
    return false;
  t0 = a;
  t1 = b;
  return true;
}

}  // namespace s2sim::collision
