#pragma once
/// \file
/// The spray gun's deposition model (docs/models/sensors.md, "Spray painting"), free of any
/// component: the paint leaves the nozzle into a cone of half angle θmax about the beam, with
/// a Gaussian profile in the angle θ off the beam (σ = θmax / 2, SimTwo's 0.1 rad at its
/// default 0.2 rad), normalised so that the whole cone carries the gun's flow Q:
///
///   I(θ) = Q · exp(−θ² / 2σ²) / W,   W = 2π ∫₀^θmax exp(−θ² / 2σ²) sin θ dθ   (m³/s per sr)
///
/// A triangle whose centre lies inside the cone and whose front faces the nozzle receives
/// I(θc) · Ω · Δt of paint volume in a step Δt, Ω the solid angle it subtends at the nozzle
/// (which carries the 1/r² of distance and the cos of incidence), spread over its area A:
/// its thickness grows by I(θc) · Ω · Δt / A.

#include <s2sim/math.hpp>

#include <algorithm>
#include <cmath>

namespace s2sim::sensors::spray {

/// exp(−θ² / 2σ²): the profile's weight at θ off the beam.
inline double profile(double theta, double sigma) {
  const double u = theta / sigma;
  return std::exp(-0.5 * u * u);
}

/// W of the header: the profile integrated over the cone's solid angle (Simpson's rule on
/// 2 000 intervals; exact to ~1e-12 for any cone up to a hemisphere).
inline double cone_weight(double theta_max, double sigma) {
  constexpr int kIntervals = 2000;
  const double h = theta_max / kIntervals;
  double sum = 0;
  for (int i = 0; i <= kIntervals; ++i) {
    const double t = i * h;
    const double f = profile(t, sigma) * std::sin(t);
    sum += f * (i == 0 || i == kIntervals ? 1 : (i % 2 ? 4 : 2));
  }
  return 2 * kPi * sum * h / 3;
}

/// The solid angle (sr) the triangle a, b, c subtends at the origin, the vertices given from
/// it (Van Oosterom and Strackee's formula).
inline double solid_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double la = norm(a), lb = norm(b), lc = norm(c);
  const double num = std::abs(dot(a, cross(b, c)));
  const double den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
  return 2 * std::atan2(num, den);
}

/// The angle between unit `axis` and `v` (|v| = `length` > 0), in [0, π].
inline double angle_off(const Vec3& axis, const Vec3& v, double length) {
  return std::acos(std::clamp(dot(axis, v) / length, -1.0, 1.0));
}

}  // namespace s2sim::sensors::spray
