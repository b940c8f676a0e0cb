#pragma once
/// \file
/// Analytic narrow phase: the exact contact points of primitives against a plane, sphere
/// against sphere and sphere against box. Every function appends at most `capacity` points
/// to `out` and returns how many it wrote; shape a is the first argument, normals point from
/// b toward a and points lie on a's surface. With a `margin_m` > 0 they also report the points
/// not yet touching but closer than the margin, with a negative depth (minus the gap): the
/// speculative points of docs/models/contact.md.

#include "collision/contact_point.hpp"

namespace s2sim::collision {

/// `pose` is the shape's world pose. A cylinder on its side touches at its tread's two edges,
/// exactly at its radius from the axle; one with `mid_plane` (omni and mecanum wheels) at its
/// mid-plane only.
int plane_contacts(const Shape& shape, const Pose& pose, const Plane& plane, ContactPoint* out,
                   double margin_m = 0);

int sphere_sphere(double radius_a, const Vec3& center_a, double radius_b, const Vec3& center_b,
                  ContactPoint* out, double margin_m = 0);

/// A sphere (a) against a box (b) of half extents `half_b` at `pose_b`.
int sphere_box(double radius_a, const Vec3& center_a, const Vec3& half_b, const Pose& pose_b,
               ContactPoint* out, double margin_m = 0);

/// Turns points computed for the pair (b, a) into points for (a, b): the normal flips and
/// each point moves from b's surface to a's, `depth` along the old normal.
void swap_roles(ContactPoint* points, int count);

}  // namespace s2sim::collision
