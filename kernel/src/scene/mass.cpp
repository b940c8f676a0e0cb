/// \file
/// Uniform primitive inertias and parallel-axis combination.

#include "scene/mass.hpp"

namespace s2sim::scene {
namespace {

Mat3 diagonal(double a, double b, double c) {
  return Mat3{{{a, 0, 0}, {0, b, 0}, {0, 0, c}}};
}

Mat3 add(const Mat3& a, const Mat3& b) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r.m[i][j] = a.m[i][j] + b.m[i][j];
  return r;
}

// Inertia of a point mass at offset d: m (|d|² E − d dᵀ).
Mat3 point_inertia(double m, const Vec3& d) {
  const double v[3] = {d.x, d.y, d.z};
  const double dd = dot(d, d);
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r.m[i][j] = m * ((i == j ? dd : 0.0) - v[i] * v[j]);
  return r;
}

}  // namespace

Mat3 uniform_inertia(const Shape& shape, double m) {
  switch (shape.type) {
    case ShapeType::box:
    case ShapeType::convex: {  // a hull: its bounding box (imported links give their inertia)
      const Vec3& s = shape.size_m;
      return diagonal(m * (s.y * s.y + s.z * s.z) / 12, m * (s.x * s.x + s.z * s.z) / 12,
                      m * (s.x * s.x + s.y * s.y) / 12);
    }
    case ShapeType::cylinder: {
      const double r = shape.radius_m, l = shape.length_m;
      const double side = m * (3 * r * r + l * l) / 12;
      return diagonal(side, side, m * r * r / 2);
    }
    case ShapeType::sphere: {
      const double i = 0.4 * m * shape.radius_m * shape.radius_m;
      return diagonal(i, i, i);
    }
  }
  return diagonal(0, 0, 0);
}

void add_rigid_part(Body& body, double mp, const Vec3& cp, const Mat3& ip) {
  const double mb = body.mass_kg;
  const double m = mb + mp;
  const Vec3 c = (body.com_m * mb + cp * mp) / m;
  body.inertia_kg_m2 = add(add(body.inertia_kg_m2, point_inertia(mb, body.com_m - c)),
                           add(ip, point_inertia(mp, cp - c)));
  body.mass_kg = m;
  body.com_m = c;
}

}  // namespace s2sim::scene
