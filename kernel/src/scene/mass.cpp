/// \file
/// Uniform primitive inertias, parallel-axis combination and the rule for physical inertias.

#include "scene/mass.hpp"

#include "scene/attributes.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace s2sim::scene {

// Eigenvalues of a symmetric 3×3 matrix, ascending (the trigonometric closed form).
std::array<double, 3> symmetric_eigenvalues(const Mat3& a) {
  const double p1 = a.m[0][1] * a.m[0][1] + a.m[0][2] * a.m[0][2] + a.m[1][2] * a.m[1][2];
  const double q = (a.m[0][0] + a.m[1][1] + a.m[2][2]) / 3;
  std::array<double, 3> e{};
  if (p1 == 0) {
    e = {a.m[0][0], a.m[1][1], a.m[2][2]};
    std::sort(e.begin(), e.end());
    return e;
  }
  const double p2 = (a.m[0][0] - q) * (a.m[0][0] - q) + (a.m[1][1] - q) * (a.m[1][1] - q) +
                    (a.m[2][2] - q) * (a.m[2][2] - q) + 2 * p1;
  const double p = std::sqrt(p2 / 6);
  Mat3 b;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      b.m[i][j] = (a.m[i][j] - (i == j ? q : 0)) / p;
  const double det = b.m[0][0] * (b.m[1][1] * b.m[2][2] - b.m[1][2] * b.m[2][1]) -
                     b.m[0][1] * (b.m[1][0] * b.m[2][2] - b.m[1][2] * b.m[2][0]) +
                     b.m[0][2] * (b.m[1][0] * b.m[2][1] - b.m[1][1] * b.m[2][0]);
  const double r = std::clamp(det / 2, -1.0, 1.0);
  const double phi = std::acos(r) / 3;
  const double e1 = q + 2 * p * std::cos(phi);
  const double e3 = q + 2 * p * std::cos(phi + 2 * kPi / 3);
  e = {e3, 3 * q - e1 - e3, e1};
  return e;
}

std::string inertia_text(const Mat3& i) {
  return "ixx " + format_number(i.m[0][0]) + ", iyy " + format_number(i.m[1][1]) + ", izz " +
         format_number(i.m[2][2]) + ", ixy " + format_number(i.m[0][1]) + ", ixz " +
         format_number(i.m[0][2]) + ", iyz " + format_number(i.m[1][2]);
}

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

std::string inertia_problem(double mass_kg, const Mat3& inertia) {
  if (!std::isfinite(mass_kg) || mass_kg < 0)
    return "mass must be >= 0, got " + format_number(mass_kg);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!std::isfinite(inertia.m[i][j]))
        return "inertia values must be finite (" + inertia_text(inertia) + ")";
  const auto e = symmetric_eigenvalues(inertia);
  const double scale = std::max({std::abs(e[0]), std::abs(e[1]), std::abs(e[2]), 1e-300});
  const double tol = 1e-9 * scale;
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      if (std::abs(inertia.m[i][j] - inertia.m[j][i]) > tol)
        return "the inertia is not symmetric (" + inertia_text(inertia) + ", but entry " +
               std::to_string(j) + "," + std::to_string(i) + " is " +
               format_number(inertia.m[j][i]) + ")";
  if (e[0] < -tol)
    return "a principal moment is negative (" + format_number(e[0]) + " kg·m²; " +
           inertia_text(inertia) + ")";
  if (e[0] + e[1] < e[2] - tol)
    return "the principal moments " + format_number(e[0]) + ", " + format_number(e[1]) + ", " +
           format_number(e[2]) + " kg·m² violate A + B >= C (" + inertia_text(inertia) + ")";
  return {};
}

}  // namespace s2sim::scene
