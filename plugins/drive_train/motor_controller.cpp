/// \file
/// motor_controller: pidspeed, pidposition (shortest way when wrap), state feedback, at the
/// controller's own period; textbook discrete law by default, SimTwo's as an option
/// (docs/models/dc-motor.md).

#include "components.hpp"
#include "defaults.hpp"
#include "drive_train_math.hpp"

#include <cmath>
#include <string>

namespace s2sim::drive_train {

namespace {
enum : int {
  kIntegral = 0,
  kPrevious = 1,
  kPrimed = 2,
  kWasActive = 3,
  kGains = 4,  // kp, ki, kd, kf, mode as last used
  kSize = 9
};
}

void MotorController::configure(ConfigureContext& ctx) {
  ctx.declare_local();  // one axis, its inputs and signals: stepped in the axis's part
  const Params& p = ctx.params();
  axis_ = ctx.axis(p.text("axis"));
  const bool linear = ctx.axis_is_linear(axis_);
  const std::string mode = keyword(p, "controller.mode", defaults::kControllerMode);
  if (mode == "pidspeed") {
    mode_ = Mode::pid_speed;
  } else if (mode == "pidposition") {
    mode_ = Mode::pid_position;
  } else if (mode == "state" || mode == "statefeedback") {
    mode_ = Mode::state;
  } else {
    // SimTwo silently keeps the previous mode for an unknown string; a typo would leave the
    // axis under another law, so S2Sim refuses it.
    throw bad_value(p, "controller.mode",
                    "unknown controller mode '" + p.text("controller.mode") +
                        "' (expected pidspeed, pidposition or state)");
  }
  const std::string law =
      keyword(p, "controller.law",
              simtwo_semantics(p) ? defaults::kControllerLawSimTwo : defaults::kControllerLaw);
  if (law != "textbook" && law != "simtwo")
    throw bad_value(p, "controller.law",
                    "must be 'textbook' or 'simtwo', got '" + p.text("controller.law") + "'");
  simtwo_law_ = law == "simtwo";
  const bool wheel = p.boolean("wheel", false);  // `<wheels>` have their own gains
  kp_ = p.number("controller.kp", wheel ? defaults::kWheelControllerKp : defaults::kControllerKp);
  ki_ = p.number("controller.ki", defaults::kControllerKi);
  kd_ = p.number("controller.kd", defaults::kControllerKd);
  kf_ = p.number("controller.kf", wheel ? defaults::kWheelControllerKf : defaults::kControllerKf);
  const double period_ms =
      p.number("controller.period", defaults::kControllerPeriodMs, Range::positive());
  const bool active = p.boolean("controller.active", defaults::kControllerActive);
  const bool motor_active = p.boolean("motor.active", defaults::kMotorActive);
  vmax_ = p.number("motor.vmax", defaults::kMotorVmax, Range::non_negative());
  wrap_ = p.boolean("wrap", !linear) && !linear;
  ctx.set_schedule(Stage::motor_control, period_on_grid(period_ms / 1000.0, ctx.tick_s()));

  const std::string at = ctx.axis_prefix(axis_) + "/";
  ref_voltage_ = ctx.declare_input_at(at + "ref_voltage", "V", 0.0);
  ref_speed_ = ctx.declare_input_at(at + "ref_speed", linear ? "m/s" : "rad/s", 0.0);
  ref_pos_ = ctx.declare_input_at(at + "ref_pos", linear ? "m" : "rad", 0.0);
  active_ = ctx.declare_input_at(at + "controller_active", "1", active ? 1.0 : 0.0,
                                 Range::unit_interval());
  motor_active_ = ctx.declare_input_at(at + "motor_active", "1", motor_active ? 1.0 : 0.0,
                                       Range::unit_interval());
  const char* error_unit =
      mode_ == Mode::pid_speed ? (linear ? "m/s" : "rad/s") : (linear ? "m" : "rad");
  kp_in_ = ctx.declare_input_at(at + "controller_kp", "1", kp_);
  ki_in_ = ctx.declare_input_at(at + "controller_ki", "1", ki_);
  kd_in_ = ctx.declare_input_at(at + "controller_kd", "1", kd_);
  kf_in_ = ctx.declare_input_at(at + "controller_kf", "1", kf_);
  mode_in_ = ctx.declare_input_at(at + "controller_mode", "1", static_cast<double>(mode_),
                                  {0.0, static_cast<double>(Mode::state)});
  prefix_ = at;
  error_ = ctx.declare_signal_at(at + "control_error", error_unit);
  state_ = ctx.declare_state("pid", kSize, 0.0);
}

void MotorController::initialize(StepContext& ctx) {
  const Span<double> s = ctx.state(state_);
  for (int k = 0; k < kSize; ++k)
    s[k] = 0.0;
  const double gains[] = {kp_, ki_, kd_, kf_, static_cast<double>(mode_)};
  for (int k = 0; k < 5; ++k)
    s[kGains + k] = gains[k];
}

void MotorController::update(StepContext& ctx) {
  const Span<double> s = ctx.state(state_);
  // A switched-off motor (SimTwo's SetMotorActive false) stops the controller where it is:
  // its integral and previous error wait for the motor to come back.
  if (ctx.input(motor_active_) == 0.0) return;
  if (ctx.input(active_) == 0.0) {
    if (s[kWasActive] != 0.0) ctx.set_input(ref_voltage_, 0.0);  // release the motor once
    s[kWasActive] = 0.0;
    return;
  }
  if (s[kWasActive] == 0.0) {  // (re)activated: start from a clean integral
    s[kIntegral] = s[kPrevious] = s[kPrimed] = 0.0;
    s[kWasActive] = 1.0;
  }
  // The gains and the mode as the inputs hold them; a change restarts the integral (SimTwo's
  // SetMotorControllerPars and SetMotorControllerMode clear its error sum).
  const double now[] = {ctx.input(kp_in_), ctx.input(ki_in_), ctx.input(kd_in_), ctx.input(kf_in_),
                        ctx.input(mode_in_)};
  for (int k = 0; k < 4; ++k)
    if (!std::isfinite(now[k]))
      throw Error(ErrorKind::runtime,
                  "input '" + prefix_ + "controller_k" + "pidf"[k] + "' is not finite");
  if (now[4] != 0 && now[4] != 1 && now[4] != 2)
    throw Error(ErrorKind::runtime, "input '" + prefix_ +
                                        "controller_mode' must be 0 (pidspeed), 1 (pidposition) "
                                        "or 2 (state)");
  bool changed = false;
  for (int k = 0; k < 5; ++k)
    if (now[k] != s[kGains + k]) {
      changed = true;
      s[kGains + k] = now[k];
    }
  if (changed) s[kIntegral] = 0.0;
  const Mode mode = static_cast<Mode>(static_cast<int>(now[4]));
  PidState pid{s[kIntegral], s[kPrevious], s[kPrimed] != 0.0};
  const PidGains gains{now[0], now[1], now[2], now[3], vmax_};
  const double q = ctx.axis_position(axis_), w = ctx.axis_velocity(axis_);
  double u = 0, e = 0;
  if (mode == Mode::pid_speed) {
    const double ref = ctx.input(ref_speed_);
    e = ref - w;
    u = simtwo_law_ ? pid_simtwo(pid, gains, e, ref, ctx.tick_s())
                    : pid_textbook(pid, gains, e, ref, ctx.period_s());
  } else {
    const double ref = ctx.input(ref_pos_);
    e = ref - q;
    if (wrap_) e = wrap_pi(e);  // the shortest way round
    if (mode == Mode::pid_position) {
      u = simtwo_law_ ? pid_simtwo(pid, gains, e, ref, ctx.tick_s())
                      : pid_textbook(pid, gains, e, ref, ctx.period_s());
    } else {
      const double speed_error = ctx.input(ref_speed_) - w;
      u = simtwo_law_ ? state_simtwo(pid, gains, e, speed_error, ref)
                      : pid_textbook(pid, gains, e, ref, ctx.period_s(), speed_error);
    }
  }
  s[kIntegral] = pid.integral;
  s[kPrevious] = pid.previous_error;
  s[kPrimed] = pid.primed ? 1.0 : 0.0;
  ctx.publish(error_, e);
  ctx.set_input(ref_voltage_, u);
}

}  // namespace s2sim::drive_train
