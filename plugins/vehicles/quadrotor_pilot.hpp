#pragma once
/// \file
/// quadrotor_pilot: the cascaded controller of scenes/quadrotor (docs/models/fluids.md).
///
/// Position (PD) → the wanted acceleration → the wanted thrust vector m·(a + g·ẑ); attitude
/// (PD on the tilt between the frame's Z and that vector, and on the heading) → body torques;
/// a mixer turns thrust and torques into the four propellers' spin rates (thrust k_T·ω², drag
/// torque k_Q·ω², which is the yaw control: props 1 and 3 spin positive, 2 and 4 negative);
/// each motor gets the voltage for its spin rate, K·ω + R·k_Q·ω²/K, plus speed feedback.
///
///     <plugin kind='quadrotor_pilot' id='pilot' body='frame' mass='1.1' arm='0.2'
///             kt='1.6e-5' kq='2.5e-7' motor_k='0.02' motor_r='0.2' vmax='12'
///             axes='m1 m2 m3 m4' mission='square' hover_s='5' leg_s='5' side='2'/>
///
/// Props: m1 at +X, m2 at +Y, m3 at −X, m4 at −Y of the frame, spinning about its +Z.
/// Inputs `x_ref`, `y_ref`, `z_ref` (m), `yaw_ref` (rad); with `mission='square'` the pilot
/// holds (x_ref, y_ref) for `hover_s`, then flies the corners (side, 0), (side, side),
/// (0, side), (0, 0) relative to it, `leg_s` each. Signals `thrust` (N), `target_x`,
/// `target_y` (m).

#include "pilots.hpp"

#include <array>
#include <sstream>
#include <string>

namespace s2sim::vehicles {

class QuadrotorPilot final : public Component {
 public:
  void configure(ConfigureContext& ctx) override {
    const Params& p = ctx.params();
    const Range pos = Range::positive();
    frame_ = ctx.body(p.text("body"));
    mass_ = p.number("mass", pos);
    arm_ = p.number("arm", pos);
    kt_ = p.number("kt", pos);
    kq_ = p.number("kq", pos);
    motor_k_ = p.number("motor_k", pos);
    motor_r_ = p.number("motor_r", Range::non_negative());
    vmax_ = p.number("vmax", pos);
    square_ = p.choice("mission", {"hover", "square"}, "hover") == "square";
    hover_s_ = p.number("hover_s", 5.0, Range::non_negative());
    leg_s_ = p.number("leg_s", 5.0, pos);
    side_ = p.number("side", 2.0);
    std::istringstream names(p.text("axes"));
    std::string name;
    int n = 0;
    while (names >> name) {
      if (n == 4) throw Error(ErrorKind::scene, p.where("axes"), "needs exactly four axes");
      axes_[n] = ctx.axis(name);
      voltage_[n] = ctx.input(ctx.axis_prefix(axes_[n]) + "/ref_voltage");
      ++n;
    }
    if (n != 4) throw Error(ErrorKind::scene, p.where("axes"), "needs exactly four axes");
    x_ref_ = ctx.declare_input("x_ref", "m", p.number("x_ref", 0.0));
    y_ref_ = ctx.declare_input("y_ref", "m", p.number("y_ref", 0.0));
    z_ref_ = ctx.declare_input("z_ref", "m", p.number("z_ref", 1.0));
    yaw_ref_ = ctx.declare_input("yaw_ref", "rad", p.number("yaw_ref", 0.0));
    thrust_ = ctx.declare_signal("thrust", "N");
    target_x_ = ctx.declare_signal("target_x", "m");
    target_y_ = ctx.declare_signal("target_y", "m");
    integral_ = ctx.declare_state("altitude_integral", 1, 0.0);
    schedule_every(ctx, p.number("period", 2.0, pos));
  }

  void update(StepContext& ctx) override {
    const Pose& pose = ctx.body_pose(frame_);
    const Twist& tw = ctx.body_twist(frame_);
    const double h = ctx.period_s();

    // Where to be.
    double tx = ctx.input(x_ref_), ty = ctx.input(y_ref_);
    if (square_ && ctx.time_s() >= hover_s_) {
      static constexpr double kCorners[4][2] = {{1, 0}, {1, 1}, {0, 1}, {0, 0}};
      const int leg = std::min(3, static_cast<int>((ctx.time_s() - hover_s_) / leg_s_));
      tx += side_ * kCorners[leg][0];
      ty += side_ * kCorners[leg][1];
    }
    // Position: PD to an acceleration, bounded (a tilt of at most ~17°).
    const Vec3& p = pose.position;
    const Vec3& v = tw.linear_m_s;
    const Span<double> integral = ctx.state(integral_);
    const double ez = ctx.input(z_ref_) - p.z;
    // The integral trims the motors' model errors; frozen while far off (no take-off windup).
    if (std::abs(ez) < 0.1) integral[0] = std::clamp(integral[0] + ez * h, -0.5, 0.5);
    const Vec3 a{std::clamp(2.0 * (tx - p.x) - 2.4 * v.x, -3.0, 3.0),
                 std::clamp(2.0 * (ty - p.y) - 2.4 * v.y, -3.0, 3.0),
                 std::clamp(9.0 * ez - 5.0 * v.z + 3.0 * integral[0], -5.0, 5.0)};
    const Vec3 force = (a + Vec3{0, 0, kGravity_m_s2}) * mass_;
    const Vec3 z_body = pose.rotation.column(2);
    const double thrust = std::max(0.0, dot(force, z_body));

    // Attitude: tilt the frame's Z toward the force, turn its X toward the heading.
    const Vec3 tilt_world = cross(z_body, force / norm(force));
    const double yaw = std::atan2(pose.rotation.m[1][0], pose.rotation.m[0][0]);
    const double yaw_error = wrap_angle(ctx.input(yaw_ref_) - yaw);
    const Mat3 rt = pose.rotation.transposed();
    const Vec3 tilt = rt * tilt_world, w = rt * tw.angular_rad_s;
    const Vec3 torque{0.9 * tilt.x - 0.16 * w.x, 0.9 * tilt.y - 0.16 * w.y,
                      0.1 * yaw_error - 0.05 * w.z};

    // Mixer: thrusts f1..f4 of m1 (+X), m2 (+Y), m3 (−X), m4 (−Y); the frame's yaw torque is
    // c·(−f1 + f2 − f3 + f4) with c = k_Q / k_T (props 1, 3 spin positive).
    const double c = kq_ / kt_, L = arm_;
    const double f[4] = {thrust / 4 - torque.y / (2 * L) - torque.z / (4 * c),
                         thrust / 4 + torque.x / (2 * L) + torque.z / (4 * c),
                         thrust / 4 + torque.y / (2 * L) - torque.z / (4 * c),
                         thrust / 4 - torque.x / (2 * L) + torque.z / (4 * c)};
    for (int i = 0; i < 4; ++i) {
      const double sign = i % 2 == 0 ? 1.0 : -1.0;
      const double spin = sign * std::sqrt(std::max(0.0, f[i]) / kt_);
      const double load = kq_ * spin * std::abs(spin);
      const double volts = motor_k_ * spin + motor_r_ * load / motor_k_ +
                           0.02 * (spin - ctx.axis_velocity(axes_[i]));
      ctx.set_input(voltage_[i], std::clamp(volts, -vmax_, vmax_));
    }
    ctx.publish(thrust_, thrust);
    ctx.publish(target_x_, tx);
    ctx.publish(target_y_, ty);
  }

 private:
  BodyHandle frame_;
  std::array<AxisHandle, 4> axes_;
  std::array<InputHandle, 4> voltage_;
  double mass_ = 0, arm_ = 0, kt_ = 0, kq_ = 0, motor_k_ = 0, motor_r_ = 0, vmax_ = 0;
  bool square_ = false;
  double hover_s_ = 0, leg_s_ = 0, side_ = 0;
  InputHandle x_ref_, y_ref_, z_ref_, yaw_ref_;
  SignalHandle thrust_, target_x_, target_y_;
  StateHandle integral_;
};

}  // namespace s2sim::vehicles
