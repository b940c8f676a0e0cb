#pragma once
/// \file
/// The three components of an axis's drive train (docs/models/dc-motor.md). The kernel creates
/// one of each on every hinge, slider and universal axis, with the joint's drive-train elements
/// as written (kernel/src/sim/drive_train_components.hpp); the defaults are the plugin's
/// (defaults.hpp).

#include <s2sim/sdk.hpp>

#include <cctype>
#include <string>
#include <string_view>

namespace s2sim::drive_train {

/// A keyword attribute (`mode`, `law`, `backemf`), lower-cased as SimTwo compares them.
inline std::string keyword(const Params& p, std::string_view path, std::string_view fallback) {
  std::string s = p.text(path, fallback);
  for (char& c : s)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// Whether the kernel says the scene follows SimTwo's control semantics (the `semantics`
/// attribute it sets on every drive-train element, docs/format.md §6): SimTwo's PID law and
/// current slew limit become the defaults.
inline bool simtwo_semantics(const Params& p) {
  const std::string s = keyword(p, "semantics", "s2sim");
  if (s != "simtwo" && s != "s2sim")
    throw Error(ErrorKind::scene, p.where("semantics"),
                "must be 'simtwo' or 's2sim', got '" + s + "'");
  return s == "simtwo";
}

/// A scene error located at the attribute `path` of the component's element.
inline Error bad_value(const Params& p, std::string_view path, const std::string& message) {
  return Error(ErrorKind::scene, p.where(path), message);
}

/// DC motor, gearbox, joint friction and spring; applies the axis torque every tick.
class DcMotor final : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void initialize(StepContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  AxisHandle axis_;
  bool active_ = true, simple_ = false, simtwo_back_emf_ = false;
  double R_ = 1, L_ = 0, K_ = 0, vmax_ = 24, imax_ = 4, N_ = 1;
  double bv_ = 0, fc_ = 0, spring_k_ = 0, zero_pos_ = 0;
  double slew_A_per_tick_ = 0;  ///< |Δi| per physics step; 0 = none
  /// The parameters as their inputs hold them this tick (the scene's values unless changed
  /// at run time: SimTwo's SetMotorActive and SetMotorPars, --set, the viewer).
  struct Parameters {
    bool active, simple;
    double R, L, K, vmax, imax, N;
  };
  Parameters parameters(const StepContext& ctx) const;
  /// A friction input, refused (a run-time error naming it) when negative or not finite.
  double friction(const StepContext& ctx, InputHandle h, const char* name) const;
  InputHandle ref_voltage_;
  InputHandle active_in_, simple_in_, ri_in_, li_in_, ki_in_, vmax_in_, imax_in_, gear_in_;
  /// The axis's spring and friction as inputs (SimTwo's SetAxisSpring, SetFrictionDef).
  InputHandle spring_k_in_, spring_zero_in_, friction_bv_in_, friction_fc_in_;
  std::string prefix_;
  SignalHandle voltage_, current_, back_emf_, motor_torque_, power_, energy_sig_, drawn_sig_;
  StateHandle current_state_, energy_;  // energy: [0] signed V·I, [1] drawn (V·I > 0 only)
};

/// Encoder: counts `ppr` ticks per joint revolution with carried residue, optional noise.
class Encoder final : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void initialize(StepContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  AxisHandle axis_;
  bool linear_ = false;
  double ppr_ = 1000, mean_ = 0, stdev_ = -1;
  SignalHandle count_, odo_;
  StateHandle state_;  // last position, unwrapped travel, accumulated noise, count
};

/// Motor controller: pidspeed, pidposition or state feedback at its own period; writes the
/// axis's `ref_voltage` input while active.
class MotorController final : public Component {
 public:
  enum class Mode { pid_speed, pid_position, state };
  void configure(ConfigureContext& ctx) override;
  void initialize(StepContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  AxisHandle axis_;
  Mode mode_ = Mode::pid_speed;
  bool simtwo_law_ = false, wrap_ = false;
  double kp_ = 1, ki_ = 0, kd_ = 0, kf_ = 0, vmax_ = 24;
  InputHandle ref_voltage_, ref_speed_, ref_pos_, active_, motor_active_;
  /// SimTwo's SetMotorControllerPars and SetMotorControllerMode: the gains and the mode (0
  /// pidspeed, 1 pidposition, 2 state) as inputs, the scene's as their initial values.
  InputHandle kp_in_, ki_in_, kd_in_, kf_in_, mode_in_;
  std::string prefix_;
  SignalHandle error_;
  // integral, previous error, primed, was active, then the gains and mode last used (a change
  // restarts the integral)
  StateHandle state_;
};

}  // namespace s2sim::drive_train
