/// \file
/// Rotation matrices of SimTwo's XML angles (§9.2).

#include "scene/rotation.hpp"

#include <cmath>

namespace s2sim::scene {

namespace {

// Exact values at multiples of 90°: k = deg / 90 when integral, else -1.
long quarter_turns(double deg) {
  const double q = deg / 90.0;
  if (q != std::floor(q) || std::abs(q) > 1e9) return -1;
  return ((static_cast<long>(q) % 4) + 4) % 4;
}

Mat3 about_x(double c, double s) {
  return Mat3{{{1, 0, 0}, {0, c, -s}, {0, s, c}}};
}
Mat3 about_y(double c, double s) {
  return Mat3{{{c, 0, s}, {0, 1, 0}, {-s, 0, c}}};
}
Mat3 about_z(double c, double s) {
  return Mat3{{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
}

}  // namespace

double cos_deg(double deg) {
  static constexpr double table[4] = {1, 0, -1, 0};
  const long k = quarter_turns(deg);
  return k >= 0 ? table[k] : std::cos(deg_to_rad(deg));
}

double sin_deg(double deg) {
  static constexpr double table[4] = {0, 1, 0, -1};
  const long k = quarter_turns(deg);
  return k >= 0 ? table[k] : std::sin(deg_to_rad(deg));
}

Mat3 rot_x_deg(double deg) {
  return about_x(cos_deg(deg), sin_deg(deg));
}
Mat3 rot_y_deg(double deg) {
  return about_y(cos_deg(deg), sin_deg(deg));
}
Mat3 rot_z_deg(double deg) {
  return about_z(cos_deg(deg), sin_deg(deg));
}

Mat3 rot_x(double a) {
  const double c = std::cos(a), s = std::sin(a);
  return Mat3{{{1, 0, 0}, {0, c, -s}, {0, s, c}}};
}

Mat3 rot_y(double a) {
  const double c = std::cos(a), s = std::sin(a);
  return Mat3{{{c, 0, s}, {0, 1, 0}, {-s, 0, c}}};
}

Mat3 rot_z(double a) {
  const double c = std::cos(a), s = std::sin(a);
  return Mat3{{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
}

Mat3 rotation_from_rot_deg(const Vec3& deg) {
  return rot_z_deg(deg.z) * rot_y_deg(deg.y) * rot_x_deg(deg.x);
}

Mat3 sensor_rotation_from_rot_deg(const Vec3& deg) {
  return rot_x_deg(deg.x) * rot_y_deg(deg.y) * rot_z_deg(deg.z);
}

}  // namespace s2sim::scene
