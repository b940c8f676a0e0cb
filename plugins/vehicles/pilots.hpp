#pragma once
/// \file
/// The pilots of the fluid vehicles, and what they share.

#include <s2sim/sdk.hpp>

#include <algorithm>
#include <cmath>

namespace s2sim::vehicles {

/// An angle wrapped to (−π, π].
inline double wrap_angle(double a) {
  return std::remainder(a, 2 * kPi);
}

/// Runs the component every `period_ms` (rounded to whole ticks) in the control stage.
inline void schedule_every(ConfigureContext& ctx, double period_ms) {
  const double tick = ctx.tick_s();
  const double period = std::max(1.0, std::round(period_ms / 1000.0 / tick)) * tick;
  ctx.set_schedule(Stage::control, period);
}

}  // namespace s2sim::vehicles
