#pragma once
/// \file
/// blimp_pilot: flies the blimp of scenes/blimp through waypoints (docs/models/fluids.md).
/// The vertical propeller holds the altitude of the current waypoint (PID on z), the two side
/// propellers push forward (more when the waypoint is far and ahead) and steer (their
/// difference, PD on the bearing to the waypoint). A waypoint counts as reached within
/// `radius` metres; then the next one is flown to; after the last it only holds altitude.
///
///     <plugin kind='blimp_pilot' id='pilot' body='envelope' left='left' right='right'
///             vertical='lift' kt='1e-5' beam='0.6' radius='0.2'
///             waypoints='3 0 2; 3 3 2.5; 0 3 2; 0 0 1.5'/>
///
/// Signals `waypoint` (index being flown to, = count when done), `distance` (m to it).

#include "pilots.hpp"

#include <sstream>
#include <string>
#include <vector>

namespace s2sim::vehicles {

class BlimpPilot final : public Component {
 public:
  static constexpr int kMaxWaypoints = 32;

  void configure(ConfigureContext& ctx) override {
    const Params& p = ctx.params();
    const Range pos = Range::positive();
    body_ = ctx.body(p.text("body"));
    kt_ = p.number("kt", pos);
    beam_ = p.number("beam", pos);
    radius_ = p.number("radius", 0.2, pos);
    max_thrust_ = p.number("max_thrust", 1.0, pos);
    cruise_ = p.number("cruise", 0.5, pos);
    const std::string robot = "robots/" + std::string(ctx.robot()) + "/actuators/";
    left_ = ctx.input(robot + p.text("left") + "/spin");
    right_ = ctx.input(robot + p.text("right") + "/spin");
    vertical_ = ctx.input(robot + p.text("vertical") + "/spin");
    std::string list = p.text("waypoints");
    for (char& c : list)
      if (c == ';' || c == ',') c = ' ';
    std::istringstream in(list);
    double x = 0, y = 0, z = 0;
    while (in >> x >> y >> z) {
      if (count_ == kMaxWaypoints)
        throw Error(ErrorKind::scene, p.where("waypoints"),
                    "at most " + std::to_string(kMaxWaypoints) + " waypoints");
      waypoints_[count_++] = {x, y, z};
    }
    if (count_ == 0 || !in.eof())
      throw Error(ErrorKind::scene, p.where("waypoints"),
                  "expects 'x y z; x y z; ...' (metres), got '" + p.text("waypoints") + "'");
    waypoint_ = ctx.declare_signal("waypoint", "1");
    distance_ = ctx.declare_signal("distance", "m");
    state_ = ctx.declare_state("pilot", 2, 0.0);  // waypoint index, altitude integral
    schedule_every(ctx, p.number("period", 20.0, pos));
  }

  void update(StepContext& ctx) override {
    const Span<double> s = ctx.state(state_);
    const Pose& pose = ctx.body_pose(body_);
    const Twist& tw = ctx.body_twist(body_);
    int index = static_cast<int>(s[0]);
    Vec3 goal = waypoints_[std::min(index, count_ - 1)];
    Vec3 to_goal = goal - pose.position;
    if (index < count_ && norm(to_goal) < radius_) {
      s[0] = ++index;
      goal = waypoints_[std::min(index, count_ - 1)];
      to_goal = goal - pose.position;
    }
    // Altitude: PID on z through the vertical propeller.
    s[1] = std::clamp(s[1] + to_goal.z * ctx.period_s(), -2.0, 2.0);
    const double lift = 1.5 * to_goal.z - 2.0 * tw.linear_m_s.z + 0.5 * s[1];
    // Velocity pursuit in the horizontal plane: the velocity wanted points at the goal (up to
    // `cruise` m/s, slower within a few metres); the blimp heads along what its velocity lacks,
    // so it also cancels its sideways drift, and pushes by the part of it ahead.
    const Vec3 forward = pose.rotation.column(0);
    const double yaw = std::atan2(forward.y, forward.x);
    const double horizontal = std::hypot(to_goal.x, to_goal.y);
    const double done = index >= count_ ? 0.0 : 1.0;
    const double wanted = done * std::min(cruise_, 0.3 * horizontal);
    const Vec3 v = tw.linear_m_s;
    const double ex = (horizontal > 1e-9 ? wanted * to_goal.x / horizontal : 0.0) - v.x;
    const double ey = (horizontal > 1e-9 ? wanted * to_goal.y / horizontal : 0.0) - v.y;
    const double lack = std::hypot(ex, ey);
    const double bearing = lack > 0.02 ? wrap_angle(std::atan2(ey, ex) - yaw) : 0.0;
    const double ahead = std::max(0.0, std::cos(bearing));
    const double surge = 2.0 * ahead * (ex * forward.x + ey * forward.y);
    const double turn = 0.15 * bearing - 0.3 * tw.angular_rad_s.z;
    set_thrust(ctx, right_, 0.5 * surge + turn / beam_);
    set_thrust(ctx, left_, 0.5 * surge - turn / beam_);
    set_thrust(ctx, vertical_, lift);
    ctx.publish(waypoint_, index);
    ctx.publish(distance_, norm(to_goal));
  }

 private:
  void set_thrust(StepContext& ctx, InputHandle spin, double thrust) const {
    thrust = std::clamp(thrust, -max_thrust_, max_thrust_);
    ctx.set_input(spin, std::copysign(std::sqrt(std::abs(thrust) / kt_), thrust));
  }

  BodyHandle body_;
  double kt_ = 0, beam_ = 0, radius_ = 0, max_thrust_ = 0, cruise_ = 0;
  Vec3 waypoints_[kMaxWaypoints];
  int count_ = 0;
  InputHandle left_, right_, vertical_;
  SignalHandle waypoint_, distance_;
  StateHandle state_;
};

}  // namespace s2sim::vehicles
