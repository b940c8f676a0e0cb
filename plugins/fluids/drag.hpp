#pragma once
/// \file
/// drag: the force and torque of a fluid on a body moving through it (docs/models/fluids.md).
///
/// Physical form (S2Sim scenes), per body axis i with v the velocity of the centre of
/// pressure relative to the medium and ω the angular velocity, both in the body frame:
///   F_i = −(b_i·v_i + ½·ρ·Cd_i·A_i·v_i·|v_i|),   T_i = −(c_i·ω_i + k_i·ω_i·|ω_i|)
///
///     <plugin kind='drag' id='air' body='hull' density='1.225' cd='0.47' area='0.0314'
///             linear='0' angular='0.01' angular_quadratic='0'>
///       <center x='0' y='0' z='0'/>   <!-- centre of pressure, body frame -->
///     </plugin>
///
/// SimTwo's form (`semantics='simtwo'`, made by the kernel for a solid's `<drag>`): its
/// per-step velocity factors `stokes` and `roll` (ODE's damping: v ← (1 − stokes)·v after
/// each step) and its quadratic `cd` on the primitive's projected areas with ρ = 1.293 and a
/// torque −½·ρ·ω_i·|ω_i|·A_i·roll clamped to ±100 N·m (simtwo-format.md §4.4).
///
/// Inputs `wind_x`, `wind_y`, `wind_z` (m/s, world): the medium's velocity (wind, current).
/// Signals `force` (N, magnitude), `force_x/_y/_z` (N, world), `torque` (N·m, magnitude).

#include "common.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::fluids {

constexpr double kSimTwoAirDensity = 1.293;       // kg/m³ (simtwo-format.md §4.4)
constexpr double kSimTwoTorqueClamp = 100;        // N·m per world component
constexpr double kSimTwoDampingThreshold = 1e-4;  // ODE damps only above |v|² = 1e-4

class Drag final : public Component {
 public:
  void configure(ConfigureContext& ctx) override {
    ctx.refuse_unread_attributes();  // a misspelt coefficient would leave its default
    const Params& p = ctx.params();
    body_ = ctx.body(p.text("body"));
    if (body_.index == 0) throw bad_value(p, "body", "the world does not move through a fluid");
    simtwo_ = simtwo_semantics(p);
    const Range nn = Range::non_negative();
    if (simtwo_) {
      stokes_ = p.number("stokes", 1e-5, {0.0, 1.0, false, true});
      roll_ = p.number("roll", 1e-3, {0.0, 1.0, false, true});
      cd_ = Vec3{1, 1, 1} * p.number("cd", 0.0, nn);
      area_ = per_axis(p, "area", 0.0, nn);
      density_ = kSimTwoAirDensity;
      loaded_mass_kg_ = ctx.body_mass_kg(body_);
      mass_ = p.number("mass", loaded_mass_kg_, Range::positive());
      center_ = Vec3{p.number("com_x", 0.0), p.number("com_y", 0.0), p.number("com_z", 0.0)};
      auto& I = inertia_.m;
      I[0][0] = p.number("ixx", 0.0, nn);
      I[1][1] = p.number("iyy", 0.0, nn);
      I[2][2] = p.number("izz", 0.0, nn);
      I[0][1] = I[1][0] = p.number("ixy", 0.0);
      I[0][2] = I[2][0] = p.number("ixz", 0.0);
      I[1][2] = I[2][1] = p.number("iyz", 0.0);
      gravity_ = p.boolean("gravity", true);
    } else {
      density_ = p.number("density", 1.225, nn);
      cd_ = per_axis(p, "cd", 1.0, nn);
      area_ = per_axis(p, "area", 0.0, nn);
      linear_ = per_axis(p, "linear", 0.0, nn);
      angular_ = per_axis(p, "angular", 0.0, nn);
      angular_quadratic_ = per_axis(p, "angular_quadratic", 0.0, nn);
      center_ = p.vec3("center");
    }
    quadratic_ = times(cd_, area_) * (0.5 * density_);
    wind_x_ = ctx.declare_input("wind_x", "m/s", p.number("wind_x", 0.0));
    wind_y_ = ctx.declare_input("wind_y", "m/s", p.number("wind_y", 0.0));
    wind_z_ = ctx.declare_input("wind_z", "m/s", p.number("wind_z", 0.0));
    force_ = ctx.declare_signal("force", "N");
    force_x_ = ctx.declare_signal("force_x", "N");
    force_y_ = ctx.declare_signal("force_y", "N");
    force_z_ = ctx.declare_signal("force_z", "N");
    torque_ = ctx.declare_signal("torque", "N*m");
    ctx.set_schedule(Stage::actuate, ctx.tick_s());
  }

  void update(StepContext& ctx) override {
    const Pose& pose = ctx.body_pose(body_);
    const Twist& twist = ctx.body_twist(body_);
    const Vec3 arm = pose.rotation * center_;
    const Vec3 point = pose.position + arm;
    const Vec3 wind{ctx.input(wind_x_), ctx.input(wind_y_), ctx.input(wind_z_)};
    const Vec3 v_point = twist.linear_m_s + cross(twist.angular_rad_s, arm);
    const Vec3 v_local = to_local(pose.rotation, v_point - wind);
    const Vec3 w_local = to_local(pose.rotation, twist.angular_rad_s);

    Vec3 force_local = -(times(linear_, v_local) + times(quadratic_, signed_square(v_local)));
    Vec3 torque_local =
        -(times(angular_, w_local) + times(angular_quadratic_, signed_square(w_local)));
    Vec3 force = pose.rotation * force_local, torque = pose.rotation * torque_local;
    if (simtwo_) simtwo_terms(ctx, pose, twist, v_point, w_local, force, torque);

    ctx.apply_force(body_, force, point);
    ctx.apply_torque(body_, torque);
    ctx.publish(force_, norm(force));
    ctx.publish(force_x_, force.x);
    ctx.publish(force_y_, force.y);
    ctx.publish(force_z_, force.z);
    ctx.publish(torque_, norm(torque));
  }

 private:
  /// SimTwo's quadratic torque and ODE's per-step damping as forces over the coming step.
  void simtwo_terms(const StepContext& ctx, const Pose& pose, const Twist& twist, const Vec3& v_com,
                    const Vec3& w_local, Vec3& force, Vec3& torque) const {
    // −½·ρ·ω_i·|ω_i|·A_i·roll, each world component clamped (only with a coefficient).
    if (cd_.x != 0) {
      const Vec3 t =
          pose.rotation * (times(area_, signed_square(w_local)) * (-0.5 * density_ * roll_));
      torque += Vec3{std::clamp(t.x, -kSimTwoTorqueClamp, kSimTwoTorqueClamp),
                     std::clamp(t.y, -kSimTwoTorqueClamp, kSimTwoTorqueClamp),
                     std::clamp(t.z, -kSimTwoTorqueClamp, kSimTwoTorqueClamp)};
    }
    // ODE scales the velocity after the step, v ← (1 − s)·(v + h·a) when |v + h·a|² > 1e-4:
    // as a force over the step, −m·s·(v/h + g) with the gravity this body feels (other loads
    // are not known here, so they are left out of both the factor and the threshold).
    // A mass set while running (SetSolidMass) scales the mass and inertia damped, as ODE's
    // velocity scaling does; exactly 1 otherwise.
    const double scale = loaded_mass_kg_ > 0 ? ctx.body_mass_kg(body_) / loaded_mass_kg_ : 1.0;
    const double h = ctx.tick_s();
    Vec3 after = v_com;
    if (gravity_) after.z -= kGravity_m_s2 * h;
    if (dot(after, after) > kSimTwoDampingThreshold) force -= after * (mass_ * scale * stokes_ / h);
    const Vec3& w = twist.angular_rad_s;
    if (dot(w, w) > kSimTwoDampingThreshold) {
      const Mat3 inertia_world = pose.rotation * inertia_ * pose.rotation.transposed();
      torque -= (inertia_world * w) * (roll_ * scale / h);
    }
  }

  BodyHandle body_;
  bool simtwo_ = false, gravity_ = true;
  double density_ = 0, stokes_ = 0, roll_ = 0, mass_ = 0, loaded_mass_kg_ = 1;
  Vec3 cd_, area_, quadratic_, linear_, angular_, angular_quadratic_, center_;
  Mat3 inertia_;
  InputHandle wind_x_, wind_y_, wind_z_;
  SignalHandle force_, force_x_, force_y_, force_z_, torque_;
};

}  // namespace s2sim::fluids
