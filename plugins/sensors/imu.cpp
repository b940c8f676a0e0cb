/// `imu`: a 3-axis accelerometer and gyroscope in the sensor frame (S2Sim's; SimTwo's `imu`
/// is inert). The accelerometer reads the specific force f = a − g of the sensor point, a
/// from the point's velocity differenced over the sensor period (v_point = v + ω × r); the
/// gyroscope reads ω. Each axis adds a bias drawn at reset N(bias_mean, bias), a bias random
/// walk b += N(0, bias_walk·√T) per sample and white noise N(0, noise).
#include "kinds.hpp"

namespace s2sim::sensors {

namespace {
/// v rotated by the rotation vector w·t (Rodrigues).
Vec3 rotate(const Vec3& v, const Vec3& w, double t) {
  const double wn = norm(w);
  const double angle = wn * t;
  if (!(std::abs(angle) > 1e-12)) return v;
  const Vec3 k = w / wn;
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

void read_channel(const Params& p, const char* el, double& noise, double& bias, double& walk,
                  double& mean) {
  const std::string e(el);
  noise = p.number(e + ".noise", 0.0, Range::non_negative());
  bias = p.number(e + ".bias", 0.0, Range::non_negative());
  walk = p.number(e + ".bias_walk", 0.0, Range::non_negative());
  mean = p.number(e + ".bias_mean", 0.0);
}
}  // namespace

void Imu::configure(ConfigureContext& ctx) {
  ctx.declare_local();  // its own body (and joint): stepped in that body's part
  s_.read(ctx);
  s_.schedule(ctx);
  const Params& p = ctx.params();
  read_channel(p, "accelerometer", acc_.noise, acc_.bias, acc_.bias_walk, acc_.bias_mean);
  read_channel(p, "gyroscope", gyro_.noise, gyro_.bias, gyro_.bias_walk, gyro_.bias_mean);
  const char* axes[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    acc_sig_[i] = ctx.declare_signal(std::string("acc_") + axes[i], "m/s^2");
    gyro_sig_[i] = ctx.declare_signal(std::string("gyro_") + axes[i], "rad/s");
  }
  prev_v_ = ctx.declare_state("previous_velocity", 4, 0.0);
  bias_ = ctx.declare_state("bias", 6, 0.0);
}

void Imu::initialize(StepContext& ctx) {
  RandomStream r = ctx.random();
  const Span<double> b = ctx.state(bias_);
  for (int i = 0; i < 3; ++i)
    b[i] = acc_.bias_mean + (acc_.bias > 0 ? r.normal(0, acc_.bias) : 0.0);
  for (int i = 3; i < 6; ++i)
    b[i] = gyro_.bias_mean + (gyro_.bias > 0 ? r.normal(0, gyro_.bias) : 0.0);
  ctx.state(prev_v_)[3] = 0;
}

void Imu::update(StepContext& ctx) {
  const Pose& body = ctx.body_pose(s_.body);
  const Twist& tw = ctx.body_twist(s_.body);
  const Pose w = body * s_.spec.pose;
  const Vec3 v = tw.linear_m_s + cross(tw.angular_rad_s, w.position - body.position);
  const Span<double> prev = ctx.state(prev_v_);
  const double dt = ctx.period_s();
  Vec3 a;
  if (prev[3] != 0) a = (v - Vec3{prev[0], prev[1], prev[2]}) / dt;
  prev[0] = v.x;
  prev[1] = v.y;
  prev[2] = v.z;
  prev[3] = 1;
  const Mat3 rt = w.rotation.transposed();
  const Vec3 g = rt * tw.angular_rad_s;
  // The differenced acceleration is the mean over the last period, whose direction lags by
  // half a period of rotation: turn it forward by ω·T/2 (exact for a steady rotation).
  const Vec3 f = rotate(rt * (a + Vec3{0, 0, kGravity_m_s2}), g, 0.5 * dt);
  RandomStream r = ctx.random();
  const Span<double> b = ctx.state(bias_);
  const double fs[3] = {f.x, f.y, f.z}, gs[3] = {g.x, g.y, g.z};
  const double sq = std::sqrt(dt);
  for (int i = 0; i < 3; ++i) {
    if (acc_.bias_walk > 0) b[i] += r.normal(0, acc_.bias_walk * sq);
    if (gyro_.bias_walk > 0) b[i + 3] += r.normal(0, gyro_.bias_walk * sq);
    const double an = acc_.noise > 0 ? r.normal(0, acc_.noise) : 0.0;
    const double gn = gyro_.noise > 0 ? r.normal(0, gyro_.noise) : 0.0;
    ctx.publish(acc_sig_[i], fs[i] + b[i] + an);
    ctx.publish(gyro_sig_[i], gs[i] + b[i + 3] + gn);
  }
}

}  // namespace s2sim::sensors
