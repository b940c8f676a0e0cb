#pragma once
/// \file
/// Small value types shared by the kernel and plugins. SI units, world frame Z up.

#include <cmath>

namespace s2sim {

/// π, to the last bit of a double (the value of M_PI and std::numbers::pi).
inline constexpr double kPi = 3.141592653589793;

/// The simulator's gravity, m/s², along −Z: 9.81, as SimTwo's (not the 9.80665 of standard
/// gravity). The multibody model, the loose bodies and the IMU all use this value.
inline constexpr double kGravity_m_s2 = 9.81;

/// A 3-vector (metres, newtons, radians per second... as the name of the variable says).
struct Vec3 {
  double x = 0, y = 0, z = 0;

  constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
  constexpr Vec3& operator+=(const Vec3& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  constexpr Vec3& operator-=(const Vec3& o) {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  constexpr bool operator==(const Vec3& o) const { return x == o.x && y == o.y && z == o.z; }
  constexpr bool operator!=(const Vec3& o) const { return !(*this == o); }
};
constexpr Vec3 operator*(double s, const Vec3& v) {
  return v * s;
}
constexpr double dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const Vec3& v) {
  return std::sqrt(dot(v, v));
}

/// A 3x3 matrix, row-major: m[row][col].
struct Mat3 {
  double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  static constexpr Mat3 identity() { return {}; }
  constexpr Vec3 operator*(const Vec3& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  constexpr Mat3 operator*(const Mat3& o) const {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        r.m[i][j] = m[i][0] * o.m[0][j] + m[i][1] * o.m[1][j] + m[i][2] * o.m[2][j];
    return r;
  }
  constexpr Mat3 transposed() const {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        r.m[i][j] = m[j][i];
    return r;
  }
  /// Column j, e.g. the body's local axis j expressed in the parent frame.
  constexpr Vec3 column(int j) const { return {m[0][j], m[1][j], m[2][j]}; }
  constexpr bool operator==(const Mat3& o) const {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (m[i][j] != o.m[i][j]) return false;
    return true;
  }
};

/// A unit quaternion (w, x, y, z) for an orientation.
struct Quat {
  double w = 1, x = 0, y = 0, z = 0;
};

/// Inverse of a 3x3 matrix; the zero matrix when it is singular.
inline Mat3 inverse(const Mat3& a) {
  const auto& m = a.m;
  const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
  const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
  const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
  const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
  Mat3 r;
  if (!(std::abs(det) > 1e-300)) {
    r.m[0][0] = r.m[1][1] = r.m[2][2] = 0;
    return r;
  }
  r.m[0][0] = c00 / det;
  r.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
  r.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
  r.m[1][0] = c01 / det;
  r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
  r.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
  r.m[2][0] = c02 / det;
  r.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
  r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
  return r;
}

/// Rotation matrix of a unit quaternion.
constexpr Mat3 to_matrix(const Quat& q) {
  const double w = q.w, x = q.x, y = q.y, z = q.z;
  Mat3 r;
  r.m[0][0] = 1 - 2 * (y * y + z * z);
  r.m[0][1] = 2 * (x * y - w * z);
  r.m[0][2] = 2 * (x * z + w * y);
  r.m[1][0] = 2 * (x * y + w * z);
  r.m[1][1] = 1 - 2 * (x * x + z * z);
  r.m[1][2] = 2 * (y * z - w * x);
  r.m[2][0] = 2 * (x * z - w * y);
  r.m[2][1] = 2 * (y * z + w * x);
  r.m[2][2] = 1 - 2 * (x * x + y * y);
  return r;
}

/// Unit quaternion of a rotation matrix (Shepperd's method), w >= 0.
inline Quat to_quat(const Mat3& r) {
  const auto& m = r.m;
  const double trace = m[0][0] + m[1][1] + m[2][2];
  Quat q;
  if (trace > 0) {
    const double s = 2 * std::sqrt(1 + trace);
    q = {0.25 * s, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s};
  } else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
    const double s = 2 * std::sqrt(1 + m[0][0] - m[1][1] - m[2][2]);
    q = {(m[2][1] - m[1][2]) / s, 0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s};
  } else if (m[1][1] > m[2][2]) {
    const double s = 2 * std::sqrt(1 + m[1][1] - m[0][0] - m[2][2]);
    q = {(m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s};
  } else {
    const double s = 2 * std::sqrt(1 + m[2][2] - m[0][0] - m[1][1]);
    q = {(m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s};
  }
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  const double sign = q.w < 0 ? -1.0 : 1.0;
  return {sign * q.w / n, sign * q.x / n, sign * q.y / n, sign * q.z / n};
}

/// A rigid transform: a point p in the local frame is at `position + rotation * p`.
struct Pose {
  Vec3 position;
  Mat3 rotation;

  constexpr Vec3 operator*(const Vec3& p) const { return position + rotation * p; }
  constexpr Pose operator*(const Pose& o) const {
    return {position + rotation * o.position, rotation * o.rotation};
  }
  constexpr Pose inverse() const {
    const Mat3 rt = rotation.transposed();
    return {-(rt * position), rt};
  }
};

/// Heading of a frame: atan2 of its local +X axis projected on the world XY plane (radians).
inline double yaw_of(const Mat3& r) {
  return std::atan2(r.m[1][0], r.m[0][0]);
}

/// Velocity of a body: angular velocity and the linear velocity of the body origin, both in
/// the world frame.
struct Twist {
  Vec3 angular_rad_s;
  Vec3 linear_m_s;
};

/// A force and torque about the body origin, both in the world frame.
struct Wrench {
  Vec3 torque_Nm;
  Vec3 force_N;
};

}  // namespace s2sim
