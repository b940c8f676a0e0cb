#pragma once
/// \file
/// propeller: the thrust of a spinning propeller and its drag torque (docs/models/fluids.md).
///
/// Physical form (S2Sim scenes), ω the spin rate (rad/s) about the unit `direction` (body
/// frame, default +Z):
///   thrust = handed·k_T·ω·|ω| along `direction` at `position`,   torque = k_Q·ω·|ω|.
/// The spin rate is either an axis's velocity (`axis`: a hinge carrying the propeller solid
/// `body`, driven by its DC motor; the drag torque −k_Q·ω·|ω|·direction brakes that solid, so
/// the motor's voltage, current and limits decide the spin, and the motor's reaction turns the
/// frame) or the input `spin` (no axis: `body` is the vehicle, and the reaction torque
/// −k_Q·ω·|ω|·direction is put on it directly).
///
///     <plugin kind='propeller' id='front' body='frame' kt='1.2e-5' kq='2e-7' handed='1'
///             axis='m1'>    <!-- or no axis, and the input `spin` -->
///       <direction x='0' y='0' z='1'/>
///       <position x='0.2' y='0' z='0.05'/>
///     </plugin>
///
/// `handed='-1'` is a propeller pitched the other way: it pushes along `direction` when it
/// spins negatively. SimTwo's form (`semantics='simtwo'`, made by the kernel for a
/// `<propeller>` solid): thrust = `coefficient` × the body's angular velocity (world), at its
/// centre of mass (simtwo-format.md §4.4).
///
/// Input `spin` (rad/s, without an axis). Signals `thrust` (N, along `direction`), `torque`
/// (N·m, the drag torque k_Q·ω·|ω|), `spin_rate` (rad/s).

#include "common.hpp"

namespace s2sim::fluids {

class Propeller final : public Component {
 public:
  void configure(ConfigureContext& ctx) override {
    ctx.refuse_unread_attributes();  // a misspelt coefficient would leave its default
    const Params& p = ctx.params();
    body_ = ctx.body(p.text("body"));
    if (body_.index == 0) throw bad_value(p, "body", "a propeller needs a moving body");
    simtwo_ = simtwo_semantics(p);
    if (simtwo_) {
      coefficient_ = p.number("coefficient", 0.1);
      position_ = Vec3{p.number("com_x", 0.0), p.number("com_y", 0.0), p.number("com_z", 0.0)};
    } else {
      kt_ = p.number("kt", Range::non_negative());
      kq_ = p.number("kq", 0.0, Range::non_negative());
      const double handed = p.number("handed", 1.0);
      if (handed != 1.0 && handed != -1.0)
        throw bad_value(p, "handed", "must be 1 or -1, got " + p.text("handed"));
      handed_ = handed;
      direction_ = p.vec3("direction", {0, 0, 1});
      const double n = norm(direction_);
      if (!(n > 1e-9))
        throw Error(ErrorKind::scene, p.where("direction.x"), "the direction must not be zero");
      direction_ = direction_ / n;
      position_ = p.vec3("position");
      if (p.has("axis")) {
        axis_ = ctx.axis(p.text("axis"));
        if (ctx.axis_is_linear(axis_))
          throw bad_value(
              p, "axis",
              "a propeller spins on a rotational axis, '" + p.text("axis") + "' is a slider");
      } else {
        spin_input_ = ctx.declare_input("spin", "rad/s", 0.0);
      }
    }
    thrust_ = ctx.declare_signal("thrust", "N");
    torque_ = ctx.declare_signal("torque", "N*m");
    spin_ = ctx.declare_signal("spin_rate", "rad/s");
    ctx.set_schedule(Stage::actuate, ctx.tick_s());
  }

  void update(StepContext& ctx) override {
    const Pose& pose = ctx.body_pose(body_);
    if (simtwo_) {
      const Vec3& w = ctx.body_twist(body_).angular_rad_s;
      const Vec3 force = w * coefficient_;
      ctx.apply_force(body_, force, pose * position_);
      ctx.publish(thrust_, norm(force));
      ctx.publish(spin_, norm(w));
      return;
    }
    const double w = axis_.valid() ? ctx.axis_velocity(axis_) : ctx.input(spin_input_);
    const double w2 = w * std::abs(w);
    const double thrust = handed_ * kt_ * w2, torque = kq_ * w2;
    const Vec3 dir = pose.rotation * direction_;
    ctx.apply_force(body_, dir * thrust, pose * position_);
    // The air's drag torque acts on the propeller itself (with an axis: the spinning solid,
    // so the motor carries it and its reaction turns the frame; not through the joint, whose
    // own reaction would cancel the motor's). Explicit: stable while h·2·k_Q·|ω| < 2·J_prop.
    ctx.apply_torque(body_, dir * -torque);
    ctx.publish(thrust_, thrust);
    ctx.publish(torque_, torque);
    ctx.publish(spin_, w);
  }

 private:
  BodyHandle body_;
  AxisHandle axis_;
  bool simtwo_ = false;
  double coefficient_ = 0, kt_ = 0, kq_ = 0, handed_ = 1;
  Vec3 direction_{0, 0, 1}, position_;
  InputHandle spin_input_;
  SignalHandle thrust_, torque_, spin_;
};

}  // namespace s2sim::fluids
