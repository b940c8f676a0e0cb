#pragma once
/// \file
/// What every sensor kind of the `sensors` plugin shares: where the sensor sits, its beam,
/// its period and SimTwo's noise models (simtwo-format.md §12.3). SDK only.

#include <s2sim/sdk.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace s2sim::sensors {

/// Rotation of `rot_deg` for a sensor: R = Rx(x)·Ry(y)·Rz(z), the beam along +X.
Mat3 sensor_rotation_deg(const Vec3& deg);
/// Rotation about Z.
Mat3 rot_z(double rad);

/// Throws s2sim::Error (scene) "<file: element>/<child>@<attribute>: <message>".
[[noreturn]] void fail(const Params& p, const std::string& child, const std::string& attribute,
                       const std::string& message);
/// The same at a dotted `path` ("channels.lowest": the attribute `lowest` of `<channels>`).
[[noreturn]] void fail_at(const Params& p, std::string_view path, const std::string& message);
std::string num(double v);

/// SimTwo's generic noise, per value v: gain·v + offset + N(0, stdev) + N(0, stdev_p·|v|).
/// Off (identity, no draw) unless the sensor has a `<noise>` element.
struct GenericNoise {
  bool on = false;
  double stdev = 0, stdev_p = 0, offset = 0, gain = 1;
  double apply(RandomStream& r, double v) const {
    if (!on) return v;
    double out = gain * v + offset;
    if (stdev > 0) out += r.normal(0, stdev);
    if (stdev_p > 0) out += r.normal(0, stdev_p * std::abs(v));
    return out;
  }
};

/// Standard normal deviates by Marsaglia and Tsang's ziggurat (128 layers), about five times
/// cheaper than the SDK's Box-Muller: for sensors that draw one per ray. Each draw consumes a
/// variable number of 64-bit words from the sensor's own stream (deterministic for a seed).
/// The tables are built once, by `ziggurat_tables()` (call it in configure()).
struct ZigguratTables {
  double kn[128], wn[128], fn[128];
};
const ZigguratTables& ziggurat_tables();
double ziggurat_normal(RandomStream& r, const ZigguratTables& t);

/// The common part of every scene sensor: mount, beam, noise, tags, period.
struct SensorSetup {
  SensorSpec spec;    ///< as resolved by the loader (or read from `<plugin>` parameters)
  BodyHandle body;    ///< index 0 for a world-fixed sensor
  BodyHandle ignore;  ///< what its rays skip: its own body, none when world-fixed
  GenericNoise noise;
  std::int64_t period_ticks = 10;

  /// Reads the setup; for a `<plugin kind=...>` placement (no scene sensor element) the same
  /// children are read from the parameters: `solid id`, `pos`, `rot_deg`, `beam`, `noise`,
  /// `tag`, `period value`, checked by the rules of s2sim/sensor.hpp. Does not schedule.
  void read(ConfigureContext& ctx);
  /// A kind's own default period (seconds) where the scene gives no `<period>`.
  void default_period(ConfigureContext& ctx, double period_s);
  /// Schedules `update()` at the sensor's period in `stage` (the period rounded to a whole
  /// number of ticks, at least one).
  void schedule(ConfigureContext& ctx, Stage stage = Stage::sense);
  /// World pose of the sensor frame now.
  Pose world_pose(const StepContext& ctx) const { return ctx.body_pose(body) * spec.pose; }
  /// Whether this tick is a measurement tick of a component scheduled every tick.
  bool measures_now(const StepContext& ctx) const { return ctx.tick() % period_ticks == 0; }
};

/// σ_d of the IRSharp model (§12.3): u = 1/(gain·d + offset), σ_u² = var_d·d + var_k,
/// σ_d = σ_u / |gain·u²|.
inline double ir_sigma(const SensorNoise& n, double d) {
  const double u = 1.0 / (n.gain * d + n.offset);
  const double var_u = n.var_d * d + n.var_k;
  if (!(var_u > 0)) return 0;
  return std::sqrt(var_u) / std::abs(n.gain * u * u);
}

}  // namespace s2sim::sensors
