#pragma once
// Hand-built scene descriptions for model tests: the physics is checked without the loader.

#include <s2sim/kernel/scene.hpp>

#include <cmath>
#include <string>

namespace s2sim::test {

inline Mat3 rotation_about(const Vec3& axis, double angle) {
  const double n = norm(axis);
  const double x = axis.x / n, y = axis.y / n, z = axis.z / n;
  const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
  Mat3 r;
  r.m[0][0] = t * x * x + c;
  r.m[0][1] = t * x * y - s * z;
  r.m[0][2] = t * x * z + s * y;
  r.m[1][0] = t * x * y + s * z;
  r.m[1][1] = t * y * y + c;
  r.m[1][2] = t * y * z - s * x;
  r.m[2][0] = t * x * z - s * y;
  r.m[2][1] = t * y * z + s * x;
  r.m[2][2] = t * z * z + c;
  return r;
}

/// A uniform box body at `position`.
inline scene::Body box(const std::string& id, double mass_kg, Vec3 size_m, Vec3 position,
                       Mat3 rotation = {}) {
  scene::Body b;
  b.id = id;
  b.mass_kg = mass_kg;
  b.pose = {position, rotation};
  const double x = size_m.x, y = size_m.y, z = size_m.z;
  b.inertia_kg_m2 = {{{mass_kg * (y * y + z * z) / 12, 0, 0},
                      {0, mass_kg * (x * x + z * z) / 12, 0},
                      {0, 0, mass_kg * (x * x + y * y) / 12}}};
  scene::Geom g;
  g.id = id;
  g.shape.type = scene::ShapeType::box;
  g.shape.size_m = size_m;
  b.geoms.push_back(g);
  return b;
}

/// A uniform sphere body at `position`.
inline scene::Body sphere(const std::string& id, double mass_kg, double radius_m, Vec3 position) {
  scene::Body b;
  b.id = id;
  b.kind = scene::SolidKind::sphere;
  b.mass_kg = mass_kg;
  b.pose = {position, {}};
  const double i = 0.4 * mass_kg * radius_m * radius_m;
  b.inertia_kg_m2 = {{{i, 0, 0}, {0, i, 0}, {0, 0, i}}};
  scene::Geom g;
  g.id = id;
  g.shape.type = scene::ShapeType::sphere;
  g.shape.radius_m = radius_m;
  b.geoms.push_back(g);
  return b;
}

inline scene::Joint joint(const std::string& id, scene::JointType type, int body1, int body2,
                          Vec3 anchor, Vec3 axis1 = {0, 0, 1}) {
  scene::Joint j;
  j.id = id;
  j.type = type;
  j.body1 = body1;
  j.body2 = body2;
  j.anchor_m = anchor;
  j.axis1 = axis1 / norm(axis1);
  return j;
}

/// A robot owning every body and joint given so far (main body = first body).
inline void add_robot(scene::Scene& s, const std::string& id) {
  scene::Robot r;
  r.id = id;
  for (int b = 0; b < static_cast<int>(s.bodies.size()); ++b) {
    s.bodies[b].robot = static_cast<int>(s.robots.size());
    r.bodies.push_back(b);
  }
  for (int j = 0; j < static_cast<int>(s.joints.size()); ++j) {
    s.joints[j].robot = static_cast<int>(s.robots.size());
    r.joints.push_back(j);
  }
  r.main_body = r.bodies.empty() ? -1 : 0;
  s.robots.push_back(r);
}

/// A parallelogram four-bar: two cranks hinged to the world, joined by a coupler; the second
/// coupler hinge (D) closes the loop.
inline scene::Scene four_bar() {
  scene::Scene s;
  const Vec3 y{0, 1, 0};
  s.bodies.push_back(box("crank1", 1.0, {0.02, 0.02, 0.4}, {0, 0, 1.8}));
  s.bodies.push_back(box("crank2", 1.0, {0.02, 0.02, 0.4}, {0.5, 0, 1.8}));
  s.bodies.push_back(box("coupler", 1.0, {0.5, 0.02, 0.02}, {0.25, 0, 1.6}));
  s.joints.push_back(joint("A", scene::JointType::hinge, 0, -1, {0, 0, 2}, y));
  s.joints.push_back(joint("B", scene::JointType::hinge, 1, -1, {0.5, 0, 2}, y));
  s.joints.push_back(joint("C", scene::JointType::hinge, 2, 0, {0, 0, 1.6}, y));
  s.joints.push_back(joint("D", scene::JointType::hinge, 2, 1, {0.5, 0, 1.6}, y));
  add_robot(s, "fourbar");
  return s;
}

/// Complete elliptic integral of the first kind K(k) by the arithmetic-geometric mean.
inline double elliptic_k(double k) {
  double a = 1, b = std::sqrt(1 - k * k);
  for (int i = 0; i < 40; ++i) {
    const double an = (a + b) / 2;
    b = std::sqrt(a * b);
    a = an;
  }
  return kPi / (2 * a);
}

}  // namespace s2sim::test
