#pragma once
/// \file
/// The drive train's numerics as pure functions (docs/models/dc-motor.md), shared by the
/// components and tested directly.

#include <s2sim/math.hpp>

#include <algorithm>
#include <cmath>

namespace s2sim::drive_train {

using s2sim::kPi;  // the SDK's one value

/// The armature current over one physics step: its value at the end of the step and its mean
/// over the step (what makes the torque impulse and the energy V·∫i dt exact).
struct CurrentStep {
  double end = 0;
  double mean = 0;
  /// The mean before the current limit, and d(mean)/d(e): how it falls as the back-EMF rises
  /// (A/V, <= 0; zero for the `simple` law and without R and L). The mean over the step is
  /// clamp(unlimited_mean + dmean_de·Δe, ±imax) for a back-EMF e + Δe: a drive law.
  double unlimited_mean = 0;
  double dmean_de = 0;
};

/// Advances the armature current `i0` by `dt` with the terminal voltage `v` and the back-EMF
/// `e` held over the step (zero-order hold), then limits it to ±`imax`:
/// - L > 0, R > 0: the exact solution of L di/dt = v − e − R i (stable at any step);
/// - L > 0, R = 0: i grows linearly, (v − e)/L;
/// - L = 0, R > 0: algebraic, i = (v − e)/R;
/// - L = 0, R = 0: the current limit with the sign of v;
/// - `simple`: i = v/R, no back-EMF, no inductance (SimTwo's `simple='1'`).
inline CurrentStep advance_current(double i0, double v, double e, double R, double L, double imax,
                                   bool simple, double dt) {
  CurrentStep s;
  if (simple) {
    s.end = s.mean = v / R;
  } else if (L > 0 && R > 0) {
    const double target = (v - e) / R;
    const double x = R * dt / L;
    const double a = std::exp(-x);
    const double one_minus_a = -std::expm1(-x);
    s.end = target + (i0 - target) * a;
    s.mean = target + (i0 - target) * (one_minus_a / x);
    s.dmean_de = -(1 - one_minus_a / x) / R;
  } else if (L > 0) {
    s.end = i0 + dt * (v - e) / L;
    s.mean = i0 + 0.5 * dt * (v - e) / L;
    s.dmean_de = -0.5 * dt / L;
  } else if (R > 0) {
    s.end = s.mean = (v - e) / R;
    s.dmean_de = -1 / R;
  } else {
    s.end = s.mean = v > 0 ? imax : (v < 0 ? -imax : 0.0);
  }
  s.unlimited_mean = s.mean;
  s.end = std::clamp(s.end, -imax, imax);
  s.mean = std::clamp(s.mean, -imax, imax);
  return s;
}

/// A period on the tick grid: the nearest whole number of ticks, at least one (SimTwo's
/// accumulators fire on the first physics step at or past the period).
inline double period_on_grid(double period_s, double tick_s) {
  return std::max(1.0, std::round(period_s / tick_s)) * tick_s;
}

/// An angle difference into (−π, π].
inline double wrap_pi(double a) {
  a = std::remainder(a, 2 * kPi);  // [−π, π]
  return a <= -kPi ? a + 2 * kPi : a;
}

/// State of a discrete PID between two controller ticks.
struct PidState {
  double integral = 0;  ///< textbook: the integral term (Ki·∫e dt); SimTwo law: ∫e dt (or Σe)
  double previous_error = 0;
  bool primed = false;  ///< a previous error exists (textbook law: no derivative kick at start)
};

/// Gains and limits of a motor controller.
struct PidGains {
  double kp = 1, ki = 0, kd = 0, kf = 0;
  double saturation = 24;  ///< |u| <= saturation (the motor's vmax)
};

/// Textbook discrete PID sampled at `T`: u = Kp e + Ki Σ e T + Kd (e − e_prev)/T + Kf ref,
/// with conditional integration (the integral does not grow while the output saturates in
/// the error's direction) and saturation at ±`saturation`. `d_input` replaces the derivative
/// term's input when finite (state feedback: the speed error).
inline double pid_textbook(PidState& s, const PidGains& g, double e, double ref, double T,
                           double speed_error = NAN) {
  const double d = std::isfinite(speed_error)
                       ? g.kd * speed_error
                       : (s.primed ? g.kd * (e - s.previous_error) / T : 0.0);
  const double integral = s.integral + g.ki * e * T;
  double u = g.kp * e + integral + d + g.kf * ref;
  if (std::abs(u) > g.saturation && u * e > 0) {
    u = g.kp * e + s.integral + d + g.kf * ref;  // hold the integral: no wind-up
  } else {
    s.integral = integral;
  }
  s.previous_error = e;
  s.primed = true;
  return std::clamp(u, -g.saturation, g.saturation);
}

/// SimTwo's PID (simtwo-format.md §11.2): integral and derivative with the physics step `dt`
/// although it runs every controller period; the integral is undone when |u| >= saturation.
inline double pid_simtwo(PidState& s, const PidGains& g, double e, double ref, double dt) {
  s.integral += e * dt;
  const double d = (e - s.previous_error) / dt;
  double u = g.kp * e + g.ki * s.integral + g.kd * d + g.kf * ref;
  if (std::abs(u) >= g.saturation) {
    s.integral -= e * dt;
    u = std::clamp(u, -g.saturation, g.saturation);
  }
  s.previous_error = e;
  s.primed = true;
  return u;
}

/// SimTwo's state feedback: S ← S + e (no dt), u = Kp e + Ki S + Kd (ω_ref − ω) + Kf θ_ref,
/// no anti-windup, saturated.
inline double state_simtwo(PidState& s, const PidGains& g, double e, double speed_error,
                           double ref) {
  s.integral += e;
  s.previous_error = e;
  s.primed = true;
  return std::clamp(g.kp * e + g.ki * s.integral + g.kd * speed_error + g.kf * ref, -g.saturation,
                    g.saturation);
}

}  // namespace s2sim::drive_train
