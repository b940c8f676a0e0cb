#pragma once
/// \file
/// SimTwo's rotation conventions (simtwo-format.md §9.2) and small geometry helpers.

#include <s2sim/math.hpp>

namespace s2sim::scene {

constexpr double deg_to_rad(double deg) {
  return deg * kPi / 180.0;
}

/// cos and sin of an angle in degrees, exact at multiples of 90° (so that `rot_deg z='90'`
/// gives a clean matrix instead of 6e-17 residues).
double cos_deg(double deg);
double sin_deg(double deg);

/// Right-handed rotations about the fixed axes, angles in radians.
Mat3 rot_x(double rad);
Mat3 rot_y(double rad);
Mat3 rot_z(double rad);

/// The same with the angle in degrees (exact at multiples of 90°).
Mat3 rot_x_deg(double deg);
Mat3 rot_y_deg(double deg);
Mat3 rot_z_deg(double deg);

/// Solids, shells, obstacles and obstacle offsets: R = Rz(z)·Ry(y)·Rx(x), angles in degrees.
Mat3 rotation_from_rot_deg(const Vec3& deg);

/// Sensor frames: R = Rx(x)·Ry(y)·Rz(z), angles in degrees; the beam is the frame's +X.
/// (SimTwo's ray matrix Rx·Ry·Rz·Ry(90°) maps the ray's +Z onto exactly this +X.)
Mat3 sensor_rotation_from_rot_deg(const Vec3& deg);

}  // namespace s2sim::scene
