/// \file
/// dc_motor: Ua = e + Ra ia + La dia/dt, Td = Ks ia, e = Ks N w (docs/models/dc-motor.md).

#include "components.hpp"
#include "defaults.hpp"
#include "drive_train_math.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace s2sim::drive_train {

void DcMotor::configure(ConfigureContext& ctx) {
  ctx.declare_local();  // one axis, its inputs and signals: stepped in the axis's part
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
  // What SimTwo's SetMotorActive and SetMotorPars change at run time (and the viewer's
  // inputs, --set, a remote client): read every tick, validated where they are used.
  active_in_ =
      ctx.declare_input_at(at + "motor_active", "1", active_ ? 1.0 : 0.0, Range::unit_interval());
  simple_in_ =
      ctx.declare_input_at(at + "motor_simple", "1", simple_ ? 1.0 : 0.0, Range::unit_interval());
  ri_in_ = ctx.declare_input_at(at + "motor_ri", "ohm", R_);
  li_in_ = ctx.declare_input_at(at + "motor_li", "H", L_);
  ki_in_ = ctx.declare_input_at(at + "motor_ki", linear ? "N/A" : "N*m/A", K_);
  vmax_in_ = ctx.declare_input_at(at + "motor_vmax", "V", vmax_, Range::non_negative());
  imax_in_ = ctx.declare_input_at(at + "motor_imax", "A", imax_);
  gear_in_ = ctx.declare_input_at(at + "gear_ratio", "1", N_);
  // SimTwo's SetAxisSpring and SetFrictionDef: the scene's spring and friction are the initial
  // values (the zero position in rad or m, as the script gives it).
  spring_k_in_ = ctx.declare_input_at(at + "spring_k", linear ? "N/m" : "N*m/rad", spring_k_,
                                      Range::non_negative());
  spring_zero_in_ = ctx.declare_input_at(at + "spring_zeropos", linear ? "m" : "rad", zero_pos_);
  friction_bv_in_ = ctx.declare_input_at(at + "friction_bv", linear ? "N*s/m" : "N*m*s/rad", bv_,
                                         Range::non_negative());
  friction_fc_in_ =
      ctx.declare_input_at(at + "friction_fc", torque_unit, fc_, Range::non_negative());
  prefix_ = at;
  voltage_ = ctx.declare_signal_at(at + "voltage", "V");
  current_ = ctx.declare_signal_at(at + "current", "A");
  back_emf_ = ctx.declare_signal_at(at + "back_emf", "V");
  motor_torque_ = ctx.declare_signal_at(at + "motor_torque", torque_unit);
  power_ = ctx.declare_signal_at(at + "power", "W");
  energy_sig_ = ctx.declare_signal_at(at + "energy", "J");
  drawn_sig_ = ctx.declare_signal_at(at + "energy_drawn", "J");  // SimTwo's energy meter
  current_state_ = ctx.declare_state("current", 1, 0.0);
  energy_ = ctx.declare_state("energy", 2, 0.0);
}

void DcMotor::initialize(StepContext& ctx) {
  ctx.state(current_state_)[0] = 0.0;
  ctx.state(energy_)[0] = 0.0;
  ctx.state(energy_)[1] = 0.0;
}

DcMotor::Parameters DcMotor::parameters(const StepContext& ctx) const {
  Parameters m;
  m.active = ctx.input(active_in_) != 0.0;
  m.simple = ctx.input(simple_in_) != 0.0;
  auto read = [&](InputHandle h, const char* name, bool positive) {
    const double v = ctx.input(h);
    if (std::isfinite(v) && v >= 0 && (v > 0 || !positive)) return v;
    char value[32];
    std::snprintf(value, sizeof value, "%.17g", v);
    throw Error(ErrorKind::runtime, "input '" + prefix_ + name + "' = " + value +
                                        (positive ? ": must be positive" : ": must be >= 0"));
  };
  m.R = read(ri_in_, "motor_ri", m.simple && m.active);  // simple: i = V/R
  m.L = read(li_in_, "motor_li", false);
  m.K = read(ki_in_, "motor_ki", false);
  m.vmax = read(vmax_in_, "motor_vmax", false);
  m.imax = read(imax_in_, "motor_imax", false);
  m.N = read(gear_in_, "gear_ratio", true);
  return m;
}

void DcMotor::update(StepContext& ctx) {
  const double w = ctx.axis_velocity(axis_);  // mid-step speed of the last step
  const double q = ctx.axis_position(axis_);
  const double dt = ctx.tick_s();
  double& i = ctx.state(current_state_)[0];
  double& energy = ctx.state(energy_)[0];
  double& drawn = ctx.state(energy_)[1];

  double v = 0, e = 0, motor_torque = 0, power = 0;
  if (ctx.input(active_in_) != 0.0) {
    const Parameters m = parameters(ctx);
    v = std::clamp(ctx.input(ref_voltage_), -m.vmax, m.vmax);
    const double de_dw = simtwo_back_emf_ ? m.K / m.N : m.K * m.N;
    e = de_dw * w;
    CurrentStep step = advance_current(i, v, e, m.R, m.L, m.imax, m.simple, dt);
    // The slew limit is a box around the last step's current: it bounds the drive as the
    // current limit does, so the implicit solve keeps it.
    double i_min = -m.imax, i_max = m.imax;
    if (slew_A_per_tick_ > 0) {
      i_min = std::max(i_min, i - slew_A_per_tick_);
      i_max = std::min(i_max, i + slew_A_per_tick_);
      step.end = std::clamp(step.end, i_min, i_max);
      step.mean = std::clamp(step.mean, i_min, i_max);
    }
    i = step.end;
    motor_torque = m.N * m.K * step.mean;
    power = v * step.mean;
    energy += power * dt;
    if (power > 0) drawn += power * dt;  // what the supply gives; regeneration is not credited
    // The motor torque falls with the speed through the back-EMF, within the current limit:
    // a drive, which the kernel integrates implicitly (stable and without ringing on any
    // inertia, docs/models/dc-motor.md).
    ctx.apply_axis_drive(axis_, m.N * m.K * step.unlimited_mean, -m.N * m.K * step.dmean_de * de_dw,
                         m.N * m.K * i_min, m.N * m.K * i_max);
  } else {
    // Switched off (SimTwo's SetMotorActive false): no current, no torque. Its parameters are
    // not used, so not read: they are validated when it is switched on again.
    i = 0;
  }
  // The viscous friction is a drive too; the spring stays an explicit force: the leapfrog
  // keeps its energy exactly, an implicit spring would bleed it.
  const double bv = friction(ctx, friction_bv_in_, "friction_bv");
  const double fc = friction(ctx, friction_fc_in_, "friction_fc");
  const double k = ctx.input(spring_k_in_), zero = ctx.input(spring_zero_in_);
  if (!std::isfinite(k) || !std::isfinite(zero))
    throw Error(ErrorKind::runtime, "input '" + prefix_ +
                                        (std::isfinite(k) ? "spring_zeropos" : "spring_k") +
                                        "' is not finite");
  if (bv > 0) ctx.apply_axis_drive(axis_, -bv * w, bv);
  if (k != 0) ctx.apply_axis_force(axis_, -k * (q - zero));
  if (fc > 0) ctx.apply_axis_friction(axis_, fc);

  ctx.publish(voltage_, v);
  ctx.publish(current_, i);
  ctx.publish(back_emf_, e);
  ctx.publish(motor_torque_, motor_torque);
  ctx.publish(power_, power);
  ctx.publish(energy_sig_, energy);
  ctx.publish(drawn_sig_, drawn);
}

double DcMotor::friction(const StepContext& ctx, InputHandle h, const char* name) const {
  const double v = ctx.input(h);
  if (std::isfinite(v) && v >= 0) return v;
  char value[32];
  std::snprintf(value, sizeof value, "%.17g", v);
  throw Error(ErrorKind::runtime, "input '" + prefix_ + name + "' = " + value + ": must be >= 0");
}

}  // namespace s2sim::drive_train
