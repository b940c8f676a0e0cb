#pragma once
/// \file
/// A scene sensor's beam, noise and period: their defaults, their limits and the rules a valid
/// one keeps, defined once for the scene loader and the sensor plugins. Each check runs where
/// the value is read, so that its error points at the element written: the loader checks
/// every `<beam>`, `<noise>` and `<period>` of a scene sensor element, and a sensor plugin
/// checks only what it reads itself from `<plugin>` parameters (a `SensorSpec` from
/// `ConfigureContext::sensor_spec()` keeps these rules already).

#include <s2sim/math.hpp>

#include <cstdio>
#include <string>
#include <vector>

namespace s2sim {

/// Rays of one sensor beam, at most (a 360-ray lidar at 0.1° would be 3 600).
inline constexpr int kMaxBeamRays = 100000;
/// A sensor's measurement period when the scene gives none, seconds.
inline constexpr double kDefaultSensorPeriod_s = 0.01;

/// A sensor's beam as the scene gives it (SimTwo's `<beam>`, several merged).
struct SensorBeam {
  double length_m = 0.8;
  double initial_width_m = 0.01;
  double final_width_m = 0.015;
  double angle_rad = 30 * kPi / 180;
  int rays = 9;
};

/// A sensor's `<noise>` (simtwo-format.md §12.3); `present` is whether the element is there.
struct SensorNoise {
  bool present = false;
  double stdev = 0, stdev_p = 0, offset = 0, gain = 1, var_k = 0, var_d = 0;
};

/// A solenoid's `<force>`: f = ½·Vin·fmax/(1 + k2·d)² (SimTwo's `solenoid`).
struct SolenoidForce {
  double fmax_N = 1, k1 = 0, k2 = 1;
};

/// The first rule a sensor setting breaks: the attribute of its element and why, with the
/// value. Empty (`attribute` null, false) when every rule holds.
struct SensorRuleBroken {
  const char* attribute = nullptr;
  std::string message;
  explicit operator bool() const { return attribute != nullptr; }
};

namespace detail {
inline std::string sensor_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}
}  // namespace detail

/// The rules of a beam: length > 0, widths >= 0, angle in 0..360 degrees, 1..kMaxBeamRays rays.
inline SensorRuleBroken check_beam(const SensorBeam& b) {
  using detail::sensor_number;
  if (!(b.length_m > 0)) return {"length", "must be > 0 m, got " + sensor_number(b.length_m)};
  if (!(b.initial_width_m >= 0))
    return {"initial_width", "must be >= 0 m, got " + sensor_number(b.initial_width_m)};
  if (!(b.final_width_m >= 0))
    return {"final_width", "must be >= 0 m, got " + sensor_number(b.final_width_m)};
  if (!(b.angle_rad >= 0) || !(b.angle_rad <= 2 * kPi + 1e-12))
    return {"angle", "must be in 0..360 degrees, got " + sensor_number(b.angle_rad * 180 / kPi)};
  if (b.rays < 1 || b.rays > kMaxBeamRays)
    return {"rays", "must be an integer from 1 to " + std::to_string(kMaxBeamRays) + ", got " +
                        std::to_string(b.rays)};
  return {};
}

/// The rules of a noise: standard deviations >= 0 (only when the element is there).
inline SensorRuleBroken check_noise(const SensorNoise& n) {
  using detail::sensor_number;
  if (!n.present) return {};
  if (!(n.stdev >= 0)) return {"stdev", "must be >= 0, got " + sensor_number(n.stdev)};
  if (!(n.stdev_p >= 0)) return {"stdev_p", "must be >= 0, got " + sensor_number(n.stdev_p)};
  return {};
}

/// The rule of a measurement period (`<period value>`): > 0 s.
inline SensorRuleBroken check_sensor_period(double period_s) {
  if (!(period_s > 0)) return {"value", "must be > 0 s, got " + detail::sensor_number(period_s)};
  return {};
}

/// What only SimTwo's scene sensor elements give a sensor.
struct SimTwoSensorFields {
  /// `<absolute_coords/>`: the pose was written in the robot frame (`SensorSpec::pose` is
  /// already in the body frame).
  bool absolute_coords = false;
  bool is_tool = false;           ///< listed under `<tools>` rather than `<sensors>`
  std::vector<std::string> tags;  ///< `<tag value>`s in order (what a `floorline` detects)
  SolenoidForce solenoid_force;   ///< `<force>` of a `solenoid`
};

}  // namespace s2sim
