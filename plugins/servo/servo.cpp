/// \file
/// servo: a position servo of the hobby / Dynamixel AX-12 kind, as a whole (motor, gearbox
/// and the servo's own controller in one): state-space position and speed feedback toward a
/// setpoint that moves to the goal at no more than the speed limit, the torque bounded by the
/// torque-speed line of the servo's motor at full voltage (stall torque `torque_max` at rest,
/// zero at the no-load speed `speed_max`) (docs/models/dc-motor.md, "Servo").
///
///     <plugin kind='servo' id='hip' axis='hip' kp='8' kd='0.08' torque_max='1.5'
///             speed_max='11.9' period='1' min_deg='-150' max_deg='150' armature='0'/>
///
/// Inputs (shared with the drive train's): `<axis>/ref_pos` (rad), the goal; `<axis>/ref_speed`
/// (rad/s), the moving speed (0 or absent = speed_max). Signals: `<axis>/servo_torque`,
/// `<axis>/servo_setpoint`. Put `<motor active='0'/>` on the joint: the servo is the motor.

#include <s2sim/plugin.hpp>
#include <s2sim/sdk.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace {

using s2sim::kPi;

class Servo final : public s2sim::Component {
 public:
  void configure(s2sim::ConfigureContext& ctx) override {
    const s2sim::Params& p = ctx.params();
    axis_ = ctx.axis(p.text("axis"));
    if (ctx.axis_is_linear(axis_))
      throw s2sim::Error(s2sim::ErrorKind::scene, p.where("axis"),
                         "a servo needs a rotational axis, '" + p.text("axis") + "' is a slider");
    // Defaults: a Dynamixel AX-12 at 12 V (1.5 N·m stall torque, 114 rpm no-load speed,
    // 300° range).
    kp_ = p.number("kp", 8.0, s2sim::Range::non_negative());
    kd_ = p.number("kd", 0.08, s2sim::Range::non_negative());
    torque_max_ = p.number("torque_max", 1.5, s2sim::Range::positive());
    speed_max_ = p.number("speed_max", 114.0 * 2 * kPi / 60, s2sim::Range::positive());
    min_ = p.number("min_deg", -150.0) * kPi / 180;
    max_ = p.number("max_deg", 150.0) * kPi / 180;
    if (!(min_ <= max_))
      throw s2sim::Error(s2sim::ErrorKind::scene, p.where("max_deg"),
                         "must be >= min_deg, got " + std::to_string(max_ * 180 / kPi) + " < " +
                             std::to_string(min_ * 180 / kPi));
    // The motor's rotor inertia reflected through the gear, N²·J (kg·m² at the joint).
    const double armature = p.number("armature", 0.0, s2sim::Range::non_negative());
    if (armature > 0) ctx.add_axis_inertia(axis_, armature);
    const double period_ms = p.number("period", ctx.tick_s() * 1000.0, s2sim::Range::positive());
    period_ticks_ = std::max<long long>(1, std::llround(period_ms / 1000.0 / ctx.tick_s()));
    const std::string at = ctx.axis_prefix(axis_) + "/";
    ref_pos_ = ctx.declare_input_at(at + "ref_pos", "rad", 0.0);
    ref_speed_ = ctx.declare_input_at(at + "ref_speed", "rad/s", 0.0);
    torque_ = ctx.declare_signal_at(at + "servo_torque", "N*m");
    setpoint_ = ctx.declare_signal_at(at + "servo_setpoint", "rad");
    state_ = ctx.declare_state("servo", 3, 0.0);  // setpoint, setpoint speed, torque
  }

  void initialize(s2sim::StepContext& ctx) override {
    const s2sim::Span<double> s = ctx.state(state_);
    s[0] = ctx.axis_position(axis_);
    s[1] = s[2] = 0.0;
  }

  void update(s2sim::StepContext& ctx) override {
    const s2sim::Span<double> s = ctx.state(state_);
    if (ctx.tick() % period_ticks_ == 0) {
      const double T = static_cast<double>(period_ticks_) * ctx.tick_s();
      const double goal = std::clamp(ctx.input(ref_pos_), min_, max_);
      const double asked = std::abs(ctx.input(ref_speed_));
      const double speed = asked > 0 ? std::min(asked, speed_max_) : speed_max_;
      const double move = std::clamp(goal - s[0], -speed * T, speed * T);
      s[0] += move;
      s[1] = move / T;
      const double q = ctx.axis_position(axis_), w = ctx.axis_velocity(axis_);
      // The servo's DC motor at full voltage bounds the torque by its torque-speed line:
      // τ ∈ τ_max·[−1 − w/w0, 1 − w/w0], w0 = speed_max (the no-load speed). Back-driven, the
      // line would ask more than the stall torque, i.e. more than the stall current, which the
      // servo's driver does not give: |τ| ≤ τ_max.
      const double u = kp_ * (s[0] - q) + kd_ * (s[1] - w);
      const double line_low = -torque_max_ * (1 + w / speed_max_);
      const double line_high = torque_max_ * (1 - w / speed_max_);
      const double low = std::clamp(line_low, -torque_max_, torque_max_);
      const double high = std::clamp(line_high, -torque_max_, torque_max_);
      s[2] = std::clamp(u, low, high);
      // The torque's slope against the speed, Kd in the linear range and τ_max/w0 along the
      // line, goes to the kernel with it as an implicit drive, linearised at the speed read:
      // applied explicitly, a slope c rings once c·dt exceeds the axis's inertia and diverges
      // past twice it (a forearm, 5e-5 kg·m², along the AX-12's line, 0.24 N·m·s/rad, at 1 ms).
      const double line_slope = torque_max_ / speed_max_;
      if (u > high)
        drive_ = {high, line_high < torque_max_ ? line_slope : 0.0, -torque_max_, high};
      else if (u < low)
        drive_ = {low, line_low > -torque_max_ ? line_slope : 0.0, low, torque_max_};
      else
        drive_ = {u, kd_, low, high};
    }
    // Updated every tick, the servo's torque is solved with the step; a slower servo holds
    // its torque over its period, explicitly, as the real one does.
    if (period_ticks_ == 1)
      ctx.apply_axis_drive(axis_, drive_.force, drive_.damping, drive_.min, drive_.max);
    else
      ctx.apply_axis_force(axis_, s[2]);
    ctx.publish(torque_, s[2]);
    ctx.publish(setpoint_, s[0]);
  }

 private:
  s2sim::AxisHandle axis_;
  double kp_ = 0, kd_ = 0, torque_max_ = 0, speed_max_ = 0, min_ = 0, max_ = 0;
  long long period_ticks_ = 1;
  // This tick's torque as a drive: its value at the speed read, its slope, its bounds.
  struct Drive {
    double force = 0, damping = 0, min = 0, max = 0;
  } drive_;
  s2sim::InputHandle ref_pos_, ref_speed_;
  s2sim::SignalHandle torque_, setpoint_;
  s2sim::StateHandle state_;
};

}  // namespace

S2SIM_PLUGIN("servo", S2SIM_KIND("servo", s2sim::Category::actuator, Servo));
