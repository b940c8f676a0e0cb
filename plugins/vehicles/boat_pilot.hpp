#pragma once
/// \file
/// boat_pilot: holds a heading and a speed with two stern thrusters (scenes/boat): the sum of
/// their thrusts pushes, their difference turns (docs/models/fluids.md).
///
///     <plugin kind='boat_pilot' id='pilot' body='hull' left='left' right='right'
///             kt='4e-4' beam='0.4' heading_deg='0' speed='0.5'/>
///
/// `left`, `right`: the thrusters' `propeller` components (spin-rate driven, ids in this
/// robot), `beam` the distance between them (m). Inputs `heading_ref` (rad), `speed_ref`
/// (m/s, forward). Signals `surge` (N), `turn` (N·m).

#include "pilots.hpp"

#include <string>

namespace s2sim::vehicles {

class BoatPilot final : public Component {
 public:
  void configure(ConfigureContext& ctx) override {
    const Params& p = ctx.params();
    const Range pos = Range::positive();
    hull_ = ctx.body(p.text("body"));
    kt_ = p.number("kt", pos);
    beam_ = p.number("beam", pos);
    max_thrust_ = p.number("max_thrust", 20.0, pos);
    const std::string robot = "robots/" + std::string(ctx.robot()) + "/actuators/";
    left_ = ctx.input(robot + p.text("left") + "/spin");
    right_ = ctx.input(robot + p.text("right") + "/spin");
    heading_ = ctx.declare_input("heading_ref", "rad", p.number("heading_deg", 0.0) * kPi / 180);
    speed_ = ctx.declare_input("speed_ref", "m/s", p.number("speed", 0.0));
    surge_ = ctx.declare_signal("surge", "N");
    turn_ = ctx.declare_signal("turn", "N*m");
    schedule_every(ctx, p.number("period", 20.0, pos));
  }

  void update(StepContext& ctx) override {
    const Pose& pose = ctx.body_pose(hull_);
    const Twist& tw = ctx.body_twist(hull_);
    const Vec3 forward = pose.rotation.column(0);
    const double yaw = std::atan2(forward.y, forward.x);
    const double speed = dot(tw.linear_m_s, forward);
    const double surge = std::clamp(40.0 * (ctx.input(speed_) - speed), -max_thrust_, max_thrust_);
    const double turn =
        std::clamp(20.0 * wrap_angle(ctx.input(heading_) - yaw) - 15.0 * tw.angular_rad_s.z,
                   -max_thrust_ * beam_, max_thrust_ * beam_);
    // Right thruster at −beam/2 (starboard): pushing it more turns the bow left (+yaw).
    set_thrust(ctx, right_, 0.5 * surge + turn / beam_);
    set_thrust(ctx, left_, 0.5 * surge - turn / beam_);
    ctx.publish(surge_, surge);
    ctx.publish(turn_, turn);
  }

 private:
  void set_thrust(StepContext& ctx, InputHandle spin, double thrust) const {
    thrust = std::clamp(thrust, -max_thrust_, max_thrust_);
    ctx.set_input(spin, std::copysign(std::sqrt(std::abs(thrust) / kt_), thrust));
  }

  BodyHandle hull_;
  double kt_ = 0, beam_ = 0, max_thrust_ = 0;
  InputHandle left_, right_, heading_, speed_;
  SignalHandle surge_, turn_;
};

}  // namespace s2sim::vehicles
