#include "collision/ray_primitives.hpp"

#include <s2sim/kernel/scene.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace s2sim::collision {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

double comp(const Vec3& v, int i) {
  return i == 0 ? v.x : (i == 1 ? v.y : v.z);
}
Vec3 axis(int i, double sign) {
  Vec3 v;
  (i == 0 ? v.x : (i == 1 ? v.y : v.z)) = sign;
  return v;
}
}  // namespace

bool ray_box(const Vec3& o, const Vec3& d, const Vec3& half, double t_max, double& t, Vec3& n) {
  double t_near = -kInf, t_far = kInf;
  int near_axis = -1;
  double near_sign = 0;
  for (int i = 0; i < 3; ++i) {
    const double oi = comp(o, i), di = comp(d, i), hi = comp(half, i);
    if (di == 0.0) {
      if (oi < -hi || oi > hi) return false;  // parallel to this slab and outside it
      continue;
    }
    double t0 = (-hi - oi) / di, t1 = (hi - oi) / di;
    double sign = -1;  // entering through the -hi face when t0 < t1
    if (t0 > t1) {
      std::swap(t0, t1);
      sign = 1;
    }
    if (t0 > t_near) {
      t_near = t0;
      near_axis = i;
      near_sign = sign;
    }
    t_far = std::min(t_far, t1);
    if (t_near > t_far) return false;
  }
  if (near_axis < 0 || t_near < 0 || t_near > t_max) return false;  // inside, behind or far
  t = t_near;
  n = axis(near_axis, near_sign);
  return true;
}

bool ray_sphere(const Vec3& o, const Vec3& d, double r, double t_max, double& t, Vec3& n) {
  const double c = dot(o, o) - r * r;
  if (c <= 0) return false;  // starts inside (or on) the sphere
  const double b = dot(o, d);
  if (b >= 0) return false;  // moving away
  const double disc = b * b - c;
  if (disc < 0) return false;
  const double s = -b - std::sqrt(disc);
  if (s < 0 || s > t_max) return false;
  t = s;
  n = (o + d * s) / r;
  return true;
}

bool ray_convex(const Vec3& o, const Vec3& d, const scene::ConvexHull& hull, double t_max,
                double& t, Vec3& n) {
  // Cyrus–Beck: the ray's interval inside every face's half-space; it enters through the face
  // it crosses last.
  double enter = -kInf, leave = t_max;
  Vec3 enter_normal;
  for (const auto& f : hull.faces) {
    const double distance = dot(f.normal, o) - f.offset_m;  // > 0: outside this face
    const double approach = dot(f.normal, d);
    if (approach == 0) {
      if (distance > 0) return false;  // parallel and outside
      continue;
    }
    const double s = -distance / approach;
    if (approach < 0) {
      if (s > enter) {
        enter = s;
        enter_normal = f.normal;
      }
    } else {
      leave = std::min(leave, s);
    }
  }
  // Starting inside (or on) the hull, every entry lies behind the origin: not seen.
  if (!(enter > 0) || enter > leave) return false;
  t = enter;
  n = enter_normal;
  return true;
}

bool ray_cylinder(const Vec3& o, const Vec3& d, double r, double half_length, double t_max,
                  double& t, Vec3& n) {
  const double r2 = r * r;
  const bool inside_side = o.x * o.x + o.y * o.y <= r2;
  const bool inside_caps = o.z >= -half_length && o.z <= half_length;
  if (inside_side && inside_caps) return false;
  double best = kInf;
  Vec3 best_n;
  // Lateral surface: |(o + s d)_xy|^2 = r^2, entering from outside.
  const double a = d.x * d.x + d.y * d.y;
  if (a > 0 && !inside_side) {
    const double b = o.x * d.x + o.y * d.y;
    const double c = o.x * o.x + o.y * o.y - r2;
    const double disc = b * b - a * c;
    if (disc >= 0 && b < 0) {
      const double s = (-b - std::sqrt(disc)) / a;
      const double z = o.z + s * d.z;
      if (s >= 0 && z >= -half_length && z <= half_length && s < best) {
        best = s;
        best_n = Vec3{o.x + s * d.x, o.y + s * d.y, 0} / r;
      }
    }
  }
  // Caps: entering through z = ±half_length from outside.
  if (d.z != 0) {
    const double cap = d.z < 0 ? half_length : -half_length;
    if ((d.z < 0 && o.z >= cap) || (d.z > 0 && o.z <= cap)) {
      const double s = (cap - o.z) / d.z;
      const double x = o.x + s * d.x, y = o.y + s * d.y;
      if (s >= 0 && x * x + y * y <= r2 && s < best) {
        best = s;
        best_n = Vec3{0, 0, d.z < 0 ? 1.0 : -1.0};
      }
    }
  }
  if (best > t_max) return false;
  t = best;
  n = best_n;
  return true;
}

bool ray_plane(const Vec3& o, const Vec3& d, const Vec3& point, const Vec3& normal, double t_max,
               double& t) {
  const double dn = dot(d, normal);
  if (dn >= 0) return false;  // parallel or from behind
  const double h = dot(o - point, normal);
  if (h < 0) return false;  // origin behind the plane
  const double s = h / -dn;
  if (s > t_max) return false;
  t = s;
  return true;
}

}  // namespace s2sim::collision
