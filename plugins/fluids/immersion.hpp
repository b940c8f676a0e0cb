#pragma once
/// \file
/// The immersed part of a hull below a horizontal water surface: its volume and centroid, for
/// a box (exact: the box cut into six tetrahedra, each clipped by the plane), a cylinder
/// (slabs across its axis, each a disk cut by the waterline: exact when the axis is level) and
/// a sphere (exact: a spherical cap). Header-only and free of allocation: the buoyancy
/// component calls it every tick, the tests call it directly (docs/models/fluids.md).

#include <s2sim/math.hpp>

#include <algorithm>
#include <cmath>

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

/// Slabs a cylinder is cut into across its axis.
inline constexpr int kCylinderSlabs = 64;

/// A cylinder of `radius_m` and `length_m` along the hull's local Z, centred at `hull`.
inline Immersion immersed_cylinder(const Pose& hull, double radius_m, double length_m,
                                   double surface_z_m) {
  const Vec3 axis = hull.rotation.column(2);
  const Vec3 up{0, 0, 1};
  const Vec3 tilt = up - axis * axis.z;  // up within the disks' plane
  const double sin_t = norm(tilt);
  const double r = radius_m, ds = length_m / kCylinderSlabs, disk = kPi * r * r;
  detail::Moments m;
  for (int k = 0; k < kCylinderSlabs; ++k) {
    const Vec3 c = hull.position + axis * ((k + 0.5) * ds - 0.5 * length_m);
    double area = 0;
    Vec3 centroid = c;
    if (sin_t < 1e-12) {
      area = c.z < surface_z_m ? disk : 0;
    } else {
      const Vec3 e = tilt / sin_t;
      const double h = (surface_z_m - c.z) / sin_t;  // the waterline across the disk, along e
      if (h >= r) {
        area = disk;
      } else if (h > -r) {
        const double w = std::sqrt(r * r - h * h);
        const double above = r * r * std::acos(h / r) - h * w;  // the segment beyond h
        area = disk - above;
        const double x_above = 2 * w * w * w / (3 * above);
        centroid = c + e * (-above * x_above / area);
      }
    }
    if (area > 0) {
      m.volume += area * ds;
      m.moment += centroid * (area * ds);
    }
  }
  return detail::finish(m);
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
