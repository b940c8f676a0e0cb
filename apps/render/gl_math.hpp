#pragma once
/// \file
/// Single-precision vectors and 4x4 matrices for OpenGL (column-major, like GLSL). The
/// simulation works in double; the viewer converts once per drawable per frame.

#include <s2sim/math.hpp>

#include <cmath>

namespace s2sim::render {

struct Vec3f {
  float x = 0, y = 0, z = 0;
  Vec3f operator+(const Vec3f& o) const { return {x + o.x, y + o.y, z + o.z}; }
  Vec3f operator-(const Vec3f& o) const { return {x - o.x, y - o.y, z - o.z}; }
  Vec3f operator*(float s) const { return {x * s, y * s, z * s}; }
};
inline float dot(const Vec3f& a, const Vec3f& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3f cross(const Vec3f& a, const Vec3f& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Vec3f normalized(const Vec3f& v) {
  const float n = std::sqrt(dot(v, v));
  return n > 0 ? v * (1.0f / n) : v;
}
inline Vec3f to_f(const Vec3& v) {
  return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
}

struct Vec4f {
  float x = 0, y = 0, z = 0, w = 0;
};

/// Column-major: m[col * 4 + row].
struct Mat4 {
  float m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

  float& at(int row, int col) { return m[col * 4 + row]; }
  float at(int row, int col) const { return m[col * 4 + row]; }

  Mat4 operator*(const Mat4& o) const {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        float s = 0;
        for (int k = 0; k < 4; ++k)
          s += at(i, k) * o.at(k, j);
        r.at(i, j) = s;
      }
    return r;
  }
  Vec4f operator*(const Vec4f& v) const {
    return {at(0, 0) * v.x + at(0, 1) * v.y + at(0, 2) * v.z + at(0, 3) * v.w,
            at(1, 0) * v.x + at(1, 1) * v.y + at(1, 2) * v.z + at(1, 3) * v.w,
            at(2, 0) * v.x + at(2, 1) * v.y + at(2, 2) * v.z + at(2, 3) * v.w,
            at(3, 0) * v.x + at(3, 1) * v.y + at(3, 2) * v.z + at(3, 3) * v.w};
  }
  Vec3f transform_point(const Vec3f& p) const {
    const Vec4f r = *this * Vec4f{p.x, p.y, p.z, 1};
    return {r.x, r.y, r.z};
  }
};

/// The matrix of a rigid pose.
inline Mat4 to_mat4(const Pose& p) {
  Mat4 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r.at(i, j) = static_cast<float>(p.rotation.m[i][j]);
  r.at(0, 3) = static_cast<float>(p.position.x);
  r.at(1, 3) = static_cast<float>(p.position.y);
  r.at(2, 3) = static_cast<float>(p.position.z);
  return r;
}

inline Mat4 scale_matrix(const Vec3f& s) {
  Mat4 r;
  r.at(0, 0) = s.x;
  r.at(1, 1) = s.y;
  r.at(2, 2) = s.z;
  return r;
}

inline Mat4 translation(const Vec3f& t) {
  Mat4 r;
  r.at(0, 3) = t.x;
  r.at(1, 3) = t.y;
  r.at(2, 3) = t.z;
  return r;
}

inline Mat4 look_at(const Vec3f& eye, const Vec3f& target, const Vec3f& up) {
  const Vec3f f = normalized(target - eye);
  const Vec3f s = normalized(cross(f, up));
  const Vec3f u = cross(s, f);
  Mat4 r;
  r.at(0, 0) = s.x;
  r.at(0, 1) = s.y;
  r.at(0, 2) = s.z;
  r.at(1, 0) = u.x;
  r.at(1, 1) = u.y;
  r.at(1, 2) = u.z;
  r.at(2, 0) = -f.x;
  r.at(2, 1) = -f.y;
  r.at(2, 2) = -f.z;
  r.at(0, 3) = -dot(s, eye);
  r.at(1, 3) = -dot(u, eye);
  r.at(2, 3) = dot(f, eye);
  return r;
}

inline Mat4 perspective(float fovy_rad, float aspect, float near_m, float far_m) {
  Mat4 r;
  const float f = 1.0f / std::tan(fovy_rad / 2);
  r.at(0, 0) = f / aspect;
  r.at(1, 1) = f;
  r.at(2, 2) = (far_m + near_m) / (near_m - far_m);
  r.at(2, 3) = 2 * far_m * near_m / (near_m - far_m);
  r.at(3, 2) = -1;
  r.at(3, 3) = 0;
  return r;
}

inline Mat4 orthographic(float l, float r, float b, float t, float n, float f) {
  Mat4 m;
  m.at(0, 0) = 2 / (r - l);
  m.at(1, 1) = 2 / (t - b);
  m.at(2, 2) = -2 / (f - n);
  m.at(0, 3) = -(r + l) / (r - l);
  m.at(1, 3) = -(t + b) / (t - b);
  m.at(2, 3) = -(f + n) / (f - n);
  return m;
}

/// General 4x4 inverse (for unprojecting mouse rays); identity when singular.
Mat4 inverse(const Mat4& a);

}  // namespace s2sim::render
