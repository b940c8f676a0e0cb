#include "collision/contact_primitives.hpp"

#include <s2sim/kernel/scene.hpp>

#include <algorithm>
#include <cmath>

namespace s2sim::collision {
namespace {

/// Below this tangential share of the normal, a cylinder's cap counts as flat on a plane.
constexpr double kFlatCap = 1e-3;

int box_plane(const Vec3& half, const Pose& pose, const Plane& plane, double margin,
              ContactPoint* out) {
  int n = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 local{corner & 1 ? half.x : -half.x, corner & 2 ? half.y : -half.y,
                     corner & 4 ? half.z : -half.z};
    const Vec3 p = pose * local;
    const double depth = plane.offset_m - dot(plane.normal, p);
    if (depth > -margin) out[n++] = {p, plane.normal, depth, corner};
  }
  return n;
}

/// Per cap, the deepest rim point and the two rim points 120 degrees either side of it: one
/// point for a rolling wheel's edge, a stable tripod for a cylinder standing on a cap.
int cylinder_plane(double radius, double half_length, const Pose& pose, const Plane& plane,
                   bool mid_plane, double margin, ContactPoint* out) {
  const Vec3 axis = pose.rotation.column(2);
  const Vec3 tangential = plane.normal - dot(plane.normal, axis) * axis;
  const double t = norm(tangential);
  const Vec3 down = t > kFlatCap ? tangential * (-1.0 / t) : pose.rotation.column(0);
  const Vec3 side = cross(axis, down);
  const double c = -0.5, s = std::sqrt(3.0) / 2;
  const Vec3 rim[3] = {down, c * down + s * side, c * down - s * side};
  int n = 0;
  if (mid_plane && t > kFlatCap) {
    const Vec3 p = pose.position + down * radius;
    const double depth = plane.offset_m - dot(plane.normal, p);
    if (depth > -margin) out[n++] = {p, plane.normal, depth, 6};
    return n;
  }
  for (int cap = 0; cap < 2; ++cap) {
    const Vec3 center = pose.position + axis * (cap == 0 ? -half_length : half_length);
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = center + rim[k] * radius;
      const double depth = plane.offset_m - dot(plane.normal, p);
      if (depth > -margin) out[n++] = {p, plane.normal, depth, cap * 3 + k};
    }
  }
  return n;
}

/// The hull's vertices within the margin of the plane; beyond kMaxPointsPerPair of them (a
/// flat sole), the deepest one and the extreme ones along eight directions of the plane, so
/// that the points span the support polygon. A point's feature is its vertex index.
int convex_plane(const scene::ConvexHull& hull, const Pose& pose, const Plane& plane, double margin,
                 ContactPoint* out) {
  int n = 0;
  int deepest = -1;
  double deepest_depth = -margin;
  std::int32_t best[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
  double best_score[8];
  const Vec3 t1 = std::abs(plane.normal.z) < 0.9 ? cross(plane.normal, Vec3{0, 0, 1})
                                                 : cross(plane.normal, Vec3{1, 0, 0});
  const Vec3 u = t1 / norm(t1), w = cross(plane.normal, u);
  const Vec3 directions[7] = {u, -u, w, -w, u + w, -(u + w), u - w};
  for (double& s : best_score)
    s = -1e300;
  int touching = 0;
  for (std::size_t i = 0; i < hull.vertices.size(); ++i) {
    const Vec3 p = pose * hull.vertices[i];
    const double depth = plane.offset_m - dot(plane.normal, p);
    if (depth <= -margin) continue;
    if (touching < kMaxPointsPerPair)
      out[touching] = {p, plane.normal, depth, static_cast<std::int32_t>(i)};
    ++touching;
    if (depth > deepest_depth || deepest < 0) {
      deepest_depth = depth;
      deepest = static_cast<int>(i);
    }
    for (int k = 0; k < 7; ++k) {
      const double score = dot(directions[k], p);
      if (score > best_score[k] || best[k] < 0) {  // the first: a pose of NaNs scores nothing
        best_score[k] = score;
        best[k] = static_cast<std::int32_t>(i);
      }
    }
  }
  if (touching <= kMaxPointsPerPair) return touching;
  // Too many: the deepest, then each direction's extreme, without repeats.
  std::int32_t chosen[8];
  chosen[n++] = deepest;
  for (int k = 0; k < 7 && n < kMaxPointsPerPair; ++k) {
    bool seen = false;
    for (int c = 0; c < n; ++c)
      seen = seen || chosen[c] == best[k];
    if (!seen) chosen[n++] = best[k];
  }
  for (int c = 0; c < n; ++c) {
    const Vec3 p = pose * hull.vertices[static_cast<std::size_t>(chosen[c])];
    out[c] = {p, plane.normal, plane.offset_m - dot(plane.normal, p), chosen[c]};
  }
  return n;
}

}  // namespace

int plane_contacts(const Shape& shape, const Pose& pose, const Plane& plane, ContactPoint* out,
                   double margin_m) {
  switch (shape.kind) {
    case ShapeKind::box:
      return box_plane(shape.half_extents_m, pose, plane, margin_m, out);
    case ShapeKind::cylinder:
      // Omni and mecanum wheels touch on their rollers' crowns, in the wheel's mid-plane: one
      // point (two tread edges would scrub against each other when the robot turns).
      return cylinder_plane(shape.radius_m, shape.half_length_m, pose, plane, shape.mid_plane,
                            margin_m, out);
    case ShapeKind::sphere: {
      const double depth = shape.radius_m - (dot(plane.normal, pose.position) - plane.offset_m);
      if (depth <= -margin_m) return 0;
      out[0] = {pose.position - plane.normal * shape.radius_m, plane.normal, depth, 0};
      return 1;
    }
    case ShapeKind::convex:
      return convex_plane(*shape.hull, pose, plane, margin_m, out);
  }
  return 0;
}

int sphere_sphere(double radius_a, const Vec3& center_a, double radius_b, const Vec3& center_b,
                  ContactPoint* out, double margin_m) {
  const Vec3 d = center_a - center_b;
  const double distance = norm(d);
  const double depth = radius_a + radius_b - distance;
  if (depth <= -margin_m) return 0;
  const Vec3 n = distance > 1e-12 ? d / distance : Vec3{0, 0, 1};
  out[0] = {center_a - n * radius_a, n, depth, 0};
  return 1;
}

int sphere_box(double radius_a, const Vec3& center_a, const Vec3& half_b, const Pose& pose_b,
               ContactPoint* out, double margin_m) {
  const Vec3 c = pose_b.rotation.transposed() * (center_a - pose_b.position);
  const Vec3 q{std::clamp(c.x, -half_b.x, half_b.x), std::clamp(c.y, -half_b.y, half_b.y),
               std::clamp(c.z, -half_b.z, half_b.z)};
  const Vec3 d = c - q;
  const double distance = norm(d);
  Vec3 n_local;
  double depth;
  if (distance > 1e-12) {
    depth = radius_a - distance;
    n_local = d / distance;
  } else {
    // Centre inside the box: leave through the nearest face.
    const double gaps[3] = {half_b.x - std::abs(c.x), half_b.y - std::abs(c.y),
                            half_b.z - std::abs(c.z)};
    const int axis = static_cast<int>(std::min_element(gaps, gaps + 3) - gaps);
    const double coordinate = axis == 0 ? c.x : axis == 1 ? c.y : c.z;
    n_local = Vec3{axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0} *
              (coordinate < 0 ? -1.0 : 1.0);
    depth = radius_a + gaps[axis];
  }
  if (depth <= -margin_m) return 0;
  const Vec3 n = pose_b.rotation * n_local;
  out[0] = {center_a - n * radius_a, n, depth, 0};
  return 1;
}

void swap_roles(ContactPoint* points, int count) {
  for (int i = 0; i < count; ++i) {
    points[i].point_m += points[i].normal * points[i].depth_m;
    points[i].normal = -points[i].normal;
  }
}

}  // namespace s2sim::collision
