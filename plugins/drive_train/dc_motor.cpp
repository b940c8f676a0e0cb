/// \file
/// dc_motor: Ua = e + Ra ia + La dia/dt, Td = Ks ia, e = Ks N w (docs/models/dc-motor.md).

#include "components.hpp"
#include "defaults.hpp"
#include "drive_train_math.hpp"

#include <string>
#include <utility>

namespace s2sim::drive_train {

void DcMotor::configure(ConfigureContext& ctx) {
  namespace d = defaults;
  const Params& p = ctx.params();
  axis_ = ctx.axis(p.text("axis"));
  const bool linear = ctx.axis_is_linear(axis_);
  active_ = p.boolean("motor.active", d::kMotorActive);
  simple_ = p.boolean("motor.simple", d::kMotorSimple);
  R_ = p.number("motor.ri", d::kMotorRi, Range::non_negative());
  L_ = p.number("motor.li", d::kMotorLi, Range::non_negative());
  K_ = p.number("motor.ki", d::kMotorKi, Range::non_negative());
  vmax_ = p.number("motor.vmax", d::kMotorVmax, Range::non_negative());
  imax_ = p.number("motor.imax", d::kMotorImax, Range::non_negative());
  N_ = p.number("gear.ratio", d::kGearRatio, Range::positive());
  const std::string back_emf = keyword(p, "motor.backemf", d::kMotorBackEmf);
  if (back_emf != "physical" && back_emf != "simtwo")
    throw bad_value(p, "motor.backemf",
                    "must be 'physical' or 'simtwo', got '" + p.text("motor.backemf") + "'");
  simtwo_back_emf_ = back_emf == "simtwo";
  // SimTwo limits the current's change per physics step whatever the step (quirk 12): under
  // SimTwo semantics by default, anywhere with `<motor slew>`.
  slew_A_per_tick_ =
      p.number("motor.slew", simtwo_semantics(p) ? d::kMotorSlewSimTwo : d::kMotorSlewS2Sim,
               Range::non_negative());
  if (simple_ && active_) R_ = p.number("motor.ri", Range::positive());  // i = V/R
  bv_ = p.number("friction.bv", d::kFrictionBv, Range::non_negative());
  fc_ = p.number("friction.fc", d::kFrictionFc, Range::non_negative());
  spring_k_ = p.number("spring.k", d::kSpringK, Range::non_negative());
  // `zeropos` is in degrees on a rotational axis; a slider keeps metres (S2Sim deviation from
  // quirk 14, where SimTwo converts degrees even there).
  zero_pos_ = p.number("spring.zeropos", d::kSpringZeroPos);
  if (!linear) zero_pos_ = zero_pos_ * kPi / 180.0;
  // Parsed, so that a bad value is an error, but not modelled (as SimTwo): the gearbox's
  // losses and the rotor's own friction (docs/models/dc-motor.md).
  const std::pair<const char*, double> unmodelled[] = {
      {"gear.ke", d::kGearKe},   {"gear.be", d::kGearBe},   {"gear.ke2", d::kGearKe2},
      {"gear.kv2", d::kGearKv2}, {"rotor.bv", d::kRotorBv}, {"rotor.fc", d::kRotorFc}};
  for (const auto& [path, fallback] : unmodelled)
    (void)p.number(path, fallback);
  // The rotor's inertia reflected through the gear, N²·J, is the axis's armature: the kernel
  // adds it to the mass matrix (none on a slider: a rotary motor on a slider needs a lead, m/rad,
  // the format does not have).
  const double rotor_J = p.number("rotor.J", p.number("rotor.j", d::kRotorJ));
  if (active_ && !linear && N_ * N_ * rotor_J > 0) ctx.add_axis_inertia(axis_, N_ * N_ * rotor_J);

  const std::string at = ctx.axis_prefix(axis_) + "/";
  const char* torque_unit = linear ? "N" : "N*m";
  ref_voltage_ = ctx.declare_input_at(at + "ref_voltage", "V", 0.0);
  voltage_ = ctx.declare_signal_at(at + "voltage", "V");
  current_ = ctx.declare_signal_at(at + "current", "A");
  back_emf_ = ctx.declare_signal_at(at + "back_emf", "V");
  motor_torque_ = ctx.declare_signal_at(at + "motor_torque", torque_unit);
  power_ = ctx.declare_signal_at(at + "power", "W");
  energy_sig_ = ctx.declare_signal_at(at + "energy", "J");
  current_state_ = ctx.declare_state("current", 1, 0.0);
  energy_ = ctx.declare_state("energy", 1, 0.0);
}

void DcMotor::initialize(StepContext& ctx) {
  *ctx.state(current_state_) = 0.0;
  *ctx.state(energy_) = 0.0;
}

void DcMotor::update(StepContext& ctx) {
  const double w = ctx.axis_velocity(axis_);  // mid-step speed of the last step
  const double q = ctx.axis_position(axis_);
  const double dt = ctx.tick_s();
  double& i = *ctx.state(current_state_);
  double& energy = *ctx.state(energy_);

  double v = 0, e = 0;
  CurrentStep step;
  const double de_dw = simtwo_back_emf_ ? K_ / N_ : K_ * N_;
  if (active_) {
    v = std::clamp(ctx.input(ref_voltage_), -vmax_, vmax_);
    e = de_dw * w;
    step = advance_current(i, v, e, R_, L_, imax_, simple_, dt);
  }
  // The slew limit is a box around the last step's current: it bounds the drive as the
  // current limit does, so the implicit solve keeps it.
  double i_min = -imax_, i_max = imax_;
  if (slew_A_per_tick_ > 0) {
    i_min = std::max(i_min, i - slew_A_per_tick_);
    i_max = std::min(i_max, i + slew_A_per_tick_);
    step.end = std::clamp(step.end, i_min, i_max);
    step.mean = std::clamp(step.mean, i_min, i_max);
  }
  i = step.end;
  const double motor_torque = N_ * K_ * step.mean;
  const double power = v * step.mean;
  energy += power * dt;

  // The motor torque falls with the speed through the back-EMF, within the current limit;
  // the viscous friction too: drives, which the kernel integrates implicitly (stable and
  // without ringing on any inertia, docs/models/dc-motor.md). The spring stays an explicit
  // force: the leapfrog keeps its energy exactly, an implicit spring would bleed it.
  if (active_) {
    ctx.apply_axis_drive(axis_, N_ * K_ * step.unlimited_mean, -N_ * K_ * step.dmean_de * de_dw,
                         N_ * K_ * i_min, N_ * K_ * i_max);
  }
  if (bv_ > 0) ctx.apply_axis_drive(axis_, -bv_ * w, bv_);
  if (spring_k_ > 0) ctx.apply_axis_force(axis_, -spring_k_ * (q - zero_pos_));
  if (fc_ > 0) ctx.apply_axis_friction(axis_, fc_);

  ctx.publish(voltage_, v);
  ctx.publish(current_, i);
  ctx.publish(back_emf_, e);
  ctx.publish(motor_torque_, motor_torque);
  ctx.publish(power_, power);
  ctx.publish(energy_sig_, energy);
}

}  // namespace s2sim::drive_train
