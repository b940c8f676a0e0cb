#include "common.hpp"

#include <algorithm>
#include <cstdio>

namespace s2sim::sensors {

Mat3 sensor_rotation_deg(const Vec3& deg) {
  const double x = deg.x * kPi / 180, y = deg.y * kPi / 180, z = deg.z * kPi / 180;
  Mat3 rx, ry;
  rx.m[1][1] = std::cos(x);
  rx.m[1][2] = -std::sin(x);
  rx.m[2][1] = std::sin(x);
  rx.m[2][2] = std::cos(x);
  ry.m[0][0] = std::cos(y);
  ry.m[0][2] = std::sin(y);
  ry.m[2][0] = -std::sin(y);
  ry.m[2][2] = std::cos(y);
  return rx * ry * rot_z(z);
}

Mat3 rot_z(double a) {
  Mat3 r;
  r.m[0][0] = std::cos(a);
  r.m[0][1] = -std::sin(a);
  r.m[1][0] = std::sin(a);
  r.m[1][1] = std::cos(a);
  return r;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

void fail(const Params& p, const std::string& child, const std::string& attribute,
          const std::string& message) {
  fail_at(p, child.empty() ? attribute : child + "." + attribute, message);
}

void fail_at(const Params& p, std::string_view path, const std::string& message) {
  throw Error(ErrorKind::scene, p.where(path), message);
}

const ZigguratTables& ziggurat_tables() {
  static const ZigguratTables tables = [] {
    ZigguratTables t{};
    const double m1 = 2147483648.0;  // 2^31
    double dn = 3.442619855899, tn = dn;
    const double vn = 9.91256303526217e-3;
    const double q = vn / std::exp(-0.5 * dn * dn);
    t.kn[0] = (dn / q) * m1;
    t.kn[1] = 0;
    t.wn[0] = q / m1;
    t.wn[127] = dn / m1;
    t.fn[0] = 1.0;
    t.fn[127] = std::exp(-0.5 * dn * dn);
    for (int i = 126; i >= 1; --i) {
      dn = std::sqrt(-2 * std::log(vn / dn + std::exp(-0.5 * dn * dn)));
      t.kn[i + 1] = (dn / tn) * m1;
      tn = dn;
      t.fn[i] = std::exp(-0.5 * dn * dn);
      t.wn[i] = dn / m1;
    }
    return t;
  }();
  return tables;
}

double ziggurat_normal(RandomStream& r, const ZigguratTables& t) {
  constexpr double kR = 3.442619855899;  // start of the tail
  for (;;) {
    const std::uint64_t u = r.next_u64();
    const auto iz = static_cast<int>(u & 127);  // layer from the low bits
    const auto hz = static_cast<std::int32_t>(static_cast<std::uint32_t>(u >> 32));  // value
    const double x = hz * t.wn[iz];
    if (std::abs(static_cast<double>(hz)) < t.kn[iz]) return x;  // inside the layer: ~99 %
    if (iz == 0) {                                               // the tail beyond kR
      double xt, y;
      do {
        xt = -std::log(1.0 - r.uniform()) / kR;
        y = -std::log(1.0 - r.uniform());
      } while (y + y < xt * xt);
      return hz > 0 ? kR + xt : -kR - xt;
    }
    if (t.fn[iz] + r.uniform() * (t.fn[iz - 1] - t.fn[iz]) < std::exp(-0.5 * x * x)) return x;
  }
}

void SensorSetup::read(ConfigureContext& ctx) {
  const Params& p = ctx.params();
  if (const SensorSpec* s = ctx.sensor_spec()) {
    spec = *s;  // the loader checked it by the rules of s2sim/sensor.hpp, at each element
  } else {
    // A `<plugin kind='IRSharp' ...>` placement: the same children, read and checked here.
    spec = SensorSpec{};
    if (p.has("solid.id"))
      spec.body = ctx.body(p.text("solid.id"));
    else if (!ctx.robot().empty())
      fail(p, "solid", "id",
           "a robot sensor placed with <plugin> names its solid: <solid id='...'/>");
    else
      spec.body = BodyHandle{0};
    spec.pose.position = p.vec3("pos");
    spec.pose.rotation = sensor_rotation_deg(p.vec3("rot_deg"));
    SensorBeam& b = spec.beam;
    b.length_m = p.number("beam.length", b.length_m);
    b.initial_width_m = p.number("beam.initial_width", b.initial_width_m);
    b.final_width_m = p.number("beam.final_width", b.final_width_m);
    if (p.has("beam.angle")) b.angle_rad = p.number("beam.angle") * kPi / 180;
    b.rays = p.integer_in("beam.rays", b.rays, 1, kMaxBeamRays);
    if (const SensorRuleBroken broken = check_beam(b))
      fail(p, "beam", broken.attribute, broken.message);
    SensorNoise& z = spec.noise;
    z.present = p.has_element("noise");
    z.stdev = p.number("noise.stdev", z.stdev);
    z.stdev_p = p.number("noise.stdev_p", z.stdev_p);
    z.offset = p.number("noise.offset", z.offset);
    z.gain = p.number("noise.gain", z.gain);
    z.var_k = p.number("noise.var_k", z.var_k);
    z.var_d = p.number("noise.var_d", z.var_d);
    if (const SensorRuleBroken broken = check_noise(z))
      fail(p, "noise", broken.attribute, broken.message);
    if (p.has("tag.value")) spec.simtwo.tags.push_back(p.text("tag.value"));
    spec.period_s = p.number("period.value", spec.period_s);
    if (const SensorRuleBroken broken = check_sensor_period(spec.period_s))
      fail(p, "period", broken.attribute, broken.message);
  }
  body = spec.body;
  ignore = body.index > 0 ? body : BodyHandle{};
  noise.on = spec.noise.present;
  noise.stdev = spec.noise.stdev;
  noise.stdev_p = spec.noise.stdev_p;
  noise.offset = spec.noise.offset;
  noise.gain = spec.noise.gain;
  period_ticks = std::max<std::int64_t>(1, std::llround(spec.period_s / ctx.tick_s()));
}

void SensorSetup::default_period(ConfigureContext& ctx, double period_s) {
  if (ctx.params().has_element("period")) return;
  spec.period_s = period_s;
  period_ticks = std::max<std::int64_t>(1, std::llround(period_s / ctx.tick_s()));
}

void SensorSetup::schedule(ConfigureContext& ctx, Stage stage) {
  ctx.set_schedule(stage, static_cast<double>(period_ticks) * ctx.tick_s());
}

}  // namespace s2sim::sensors
