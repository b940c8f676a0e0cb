#pragma once
/// \file
/// The immersed part of a hull below a horizontal water surface: its volume and centroid, for
/// a box (exact: the box cut into six tetrahedra, each clipped by the plane), a cylinder (the
/// disks across its axis cut by the waterline, integrated along it: to round-off at any tilt)
/// and a sphere (exact: a spherical cap). Header-only and free of allocation: the buoyancy
/// component calls it every tick, the tests call it directly (docs/models/fluids.md).

#include <s2sim/math.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace s2sim::fluids {

/// The immersed part of a hull, world frame.
struct Immersion {
  double volume_m3 = 0;
  Vec3 centroid_m;  ///< meaningful when volume_m3 > 0
};

namespace detail {

inline double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return std::abs(dot(b - a, cross(c - a, d - a))) / 6.0;
}

/// Accumulates the volume and first moment of a tetrahedron.
struct Moments {
  double volume = 0;
  Vec3 moment;  ///< Σ volume · centroid
  void add_tet(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double sign = 1) {
    const double v = sign * tet_volume(a, b, c, d);
    volume += v;
    moment += (a + b + c + d) * (v / 4.0);
  }
};

inline Vec3 cut(const Vec3& below, double d_below, const Vec3& above, double d_above) {
  const double t = d_below / (d_below - d_above);
  return below + (above - below) * t;
}

/// Adds the part of tetrahedron p with signed heights d (< 0 below the surface) under it.
inline void add_clipped_tet(const Vec3 (&p)[4], const double (&d)[4], Moments& m) {
  int below[4], above[4], nb = 0, na = 0;
  for (int i = 0; i < 4; ++i)
    (d[i] < 0 ? below[nb++] : above[na++]) = i;
  if (nb == 0) return;
  if (nb == 4) {
    m.add_tet(p[0], p[1], p[2], p[3]);
    return;
  }
  if (nb == 1) {  // a small tetrahedron at the one vertex below
    const int a = below[0];
    m.add_tet(p[a], cut(p[a], d[a], p[above[0]], d[above[0]]),
              cut(p[a], d[a], p[above[1]], d[above[1]]), cut(p[a], d[a], p[above[2]], d[above[2]]));
    return;
  }
  if (nb == 3) {  // the whole less the small tetrahedron at the one vertex above
    const int b = above[0];
    m.add_tet(p[0], p[1], p[2], p[3]);
    m.add_tet(p[b], cut(p[below[0]], d[below[0]], p[b], d[b]),
              cut(p[below[1]], d[below[1]], p[b], d[b]), cut(p[below[2]], d[below[2]], p[b], d[b]),
              -1);
    return;
  }
  // Two below: a wedge (prism) a0 q00 q01 / a1 q10 q11, cut into three tetrahedra.
  const int a0 = below[0], a1 = below[1], b0 = above[0], b1 = above[1];
  const Vec3 A0 = p[a0], A1 = cut(p[a0], d[a0], p[b0], d[b0]), A2 = cut(p[a0], d[a0], p[b1], d[b1]);
  const Vec3 B0 = p[a1], B1 = cut(p[a1], d[a1], p[b0], d[b0]), B2 = cut(p[a1], d[a1], p[b1], d[b1]);
  m.add_tet(A0, A1, A2, B2);
  m.add_tet(A0, A1, B1, B2);
  m.add_tet(A0, B0, B1, B2);
}

inline Immersion finish(const Moments& m) {
  Immersion r;
  r.volume_m3 = std::max(0.0, m.volume);
  if (m.volume > 0) r.centroid_m = m.moment / m.volume;
  return r;
}

}  // namespace detail

/// A box of full edge lengths `size_m` (body axes) centred at `hull` (world pose), below the
/// plane z = surface_z_m.
inline Immersion immersed_box(const Pose& hull, const Vec3& size_m, double surface_z_m) {
  Vec3 corner[8];
  double depth[8];
  for (int i = 0; i < 8; ++i) {
    const Vec3 local{(i & 1 ? 0.5 : -0.5) * size_m.x, (i & 2 ? 0.5 : -0.5) * size_m.y,
                     (i & 4 ? 0.5 : -0.5) * size_m.z};
    corner[i] = hull * local;
    depth[i] = corner[i].z - surface_z_m;
  }
  // Kuhn's six tetrahedra along the diagonal 0-7: 0, e_a, e_a + e_b, 7 for each order a, b.
  static constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                                      {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  detail::Moments m;
  for (const auto& t : kTets) {
    const Vec3 p[4] = {corner[t[0]], corner[t[1]], corner[t[2]], corner[t[3]]};
    const double d[4] = {depth[t[0]], depth[t[1]], depth[t[2]], depth[t[3]]};
    detail::add_clipped_tet(p, d, m);
  }
  return detail::finish(m);
}

namespace detail {

/// N-point Gauss–Legendre nodes and weights on [−1, 1] (Newton's method on P_N), computed
/// once on first use (no allocation).
template <int N>
struct GaussLegendre {
  double node[N], weight[N];
};

template <int N>
const GaussLegendre<N>& gauss_legendre() {
  static const GaussLegendre<N> rule = [] {
    GaussLegendre<N> g{};
    for (int i = 0; i < N; ++i) {
      double x = std::cos(kPi * (i + 0.75) / (N + 0.5)), slope = 1;
      for (int iteration = 0; iteration < 100; ++iteration) {
        double p_prev = 1, p = x;  // P_0, P_1, then up to P_N
        for (int k = 2; k <= N; ++k) {
          const double p_next = ((2 * k - 1) * x * p - (k - 1) * p_prev) / k;
          p_prev = p;
          p = p_next;
        }
        slope = N * (x * p - p_prev) / (x * x - 1);
        const double step = p / slope;
        x -= step;
        if (std::abs(step) < 1e-16) break;
      }
      g.node[i] = x;
      g.weight[i] = 2 / ((1 - x * x) * slope * slope);
    }
    return g;
  }();
  return rule;
}

/// The part x < h of a disk of radius r (x across the disk): its area and its first moment
/// about the centre along x.
inline void disk_below(double r, double h, double& area, double& moment_x) {
  const double c = std::clamp(h, -r, r), w2 = r * r - c * c, w = std::sqrt(w2);
  area = r * r * std::acos(-c / r) + c * w;
  moment_x = -2.0 / 3.0 * w2 * w;
}

}  // namespace detail

/// A cylinder of `radius_m` and `length_m` along the hull's local Z, centred at `hull`.
///
/// With s along the axis a and x across it along e (the part of "up" within the disks), a
/// point's height is c.z + a_z·s + sin θ·x, so the cross-section at s is the part x < h(s) of
/// the disk, h linear in s. The volume ∫ A(h(s)) ds and its moments are integrated exactly
/// where the disks are whole or dry, and by 16-point Gauss–Legendre where the waterline
/// crosses them, after s = s1 + (s2 − s1)(1 − cos φ)/2, which makes the integrand analytic
/// at the ends where the waterline touches the rim (A ~ (r − h)^{3/2} there): accurate to
/// round-off at every tilt, level and upright included (immersion_test.cpp).
inline Immersion immersed_cylinder(const Pose& hull, double radius_m, double length_m,
                                   double surface_z_m) {
  const Vec3 axis = hull.rotation.column(2);
  const Vec3 tilt = Vec3{0, 0, 1} - axis * axis.z;  // up within the disks' plane
  const double sin_t = norm(tilt), r = radius_m, half = 0.5 * length_m, disk = kPi * r * r;
  const double rise = surface_z_m - hull.position.z;  // the surface above the centre
  Immersion out;
  out.centroid_m = hull.position;
  if (sin_t < 1e-12) {  // upright: whole disks up to the surface
    const double s_surface = rise / axis.z;
    const double s1 = axis.z > 0 ? -half : std::max(-half, s_surface);
    const double s2 = axis.z > 0 ? std::min(half, s_surface) : half;
    if (s2 <= s1) return out;
    out.volume_m3 = disk * (s2 - s1);
    out.centroid_m = hull.position + axis * (0.5 * (s1 + s2));
    return out;
  }
  const Vec3 across = tilt / sin_t;
  auto waterline = [&](double s) { return (rise - axis.z * s) / sin_t; };  // h(s)
  // Cut [−L/2, L/2] where the waterline meets the rim (h = ±r).
  double cuts[4] = {-half, half, 0, 0};
  int n = 2;
  if (axis.z != 0)
    for (double rim : {r, -r}) {
      const double s = (rise - rim * sin_t) / axis.z;
      if (s > -half && s < half) cuts[n++] = s;
    }
  for (int i = 1; i < n; ++i)  // insertion sort of at most four
    for (int j = i; j > 0 && cuts[j] < cuts[j - 1]; --j)
      std::swap(cuts[j], cuts[j - 1]);
  const auto& rule = detail::gauss_legendre<16>();
  double volume = 0, moment_s = 0, moment_x = 0;
  for (int k = 0; k + 1 < n; ++k) {
    const double s1 = cuts[k], s2 = cuts[k + 1], mid_h = waterline(0.5 * (s1 + s2));
    if (s2 <= s1 || mid_h <= -r) continue;  // dry
    if (mid_h >= r) {                       // whole disks
      volume += disk * (s2 - s1);
      moment_s += disk * (s2 - s1) * 0.5 * (s1 + s2);
      continue;
    }
    for (int i = 0; i < 16; ++i) {
      const double phi = 0.5 * kPi * (1 + rule.node[i]);
      const double s = s1 + (s2 - s1) * 0.5 * (1 - std::cos(phi));
      const double weight = rule.weight[i] * 0.5 * kPi * (s2 - s1) * 0.5 * std::sin(phi);
      double area = 0, first_x = 0;
      detail::disk_below(r, waterline(s), area, first_x);
      volume += weight * area;
      moment_s += weight * area * s;
      moment_x += weight * first_x;
    }
  }
  if (volume <= 0) return out;
  out.volume_m3 = volume;
  out.centroid_m = hull.position + axis * (moment_s / volume) + across * (moment_x / volume);
  return out;
}

/// A sphere of `radius_m` centred at `centre_m`.
inline Immersion immersed_sphere(const Vec3& centre_m, double radius_m, double surface_z_m) {
  const double r = radius_m;
  const double h = std::clamp(surface_z_m - (centre_m.z - r), 0.0, 2 * r);  // cap height
  Immersion out;
  out.volume_m3 = kPi * h * h * (3 * r - h) / 3;
  out.centroid_m = centre_m;
  if (h > 0) out.centroid_m.z -= 3 * (2 * r - h) * (2 * r - h) / (4 * (3 * r - h));
  return out;
}

}  // namespace s2sim::fluids
