/// \file
/// encoder: ppr ticks per joint revolution (per 2π m on a slider, as SimTwo), floor of the
/// total travel so that the quantisation carries its residue and never drifts; optional noise
/// in ticks per sample (docs/models/dc-motor.md).

#include "components.hpp"
#include "defaults.hpp"
#include "drive_train_math.hpp"

#include <cmath>
#include <string>

namespace s2sim::drive_train {

namespace {
enum : int { kLast = 0, kTravel = 1, kNoise = 2, kCount = 3, kSize = 4 };
}

void Encoder::configure(ConfigureContext& ctx) {
  ctx.declare_local();  // one axis, its inputs and signals: stepped in the axis's part
  const Params& p = ctx.params();
  axis_ = ctx.axis(p.text("axis"));
  linear_ = ctx.axis_is_linear(axis_);
  // SimTwo rounds the tick count (RobotTh_wo_comm writes ppr='700.8').
  const std::int64_t ppr = std::llround(p.number("encoder.ppr", defaults::kEncoderPpr));
  if (ppr <= 0) throw bad_value(p, "encoder.ppr", "must be > 0, got " + std::to_string(ppr));
  ppr_ = static_cast<double>(ppr);
  mean_ = p.number("encoder.mean", defaults::kEncoderMean);
  stdev_ = p.number("encoder.stdev", defaults::kEncoderStdev);
  // S2Sim's `period` (ms); by default the scene's control period, SimTwo's script tick.
  const double period_ms = p.number(
      "encoder.period", p.number("control_period", ctx.tick_s() * 1000.0, Range::positive()),
      Range::positive());
  ctx.set_schedule(Stage::sense, period_on_grid(period_ms / 1000.0, ctx.tick_s()));
  const std::string at = ctx.axis_prefix(axis_) + "/";
  count_ = ctx.declare_signal_at(at + "encoder", "1");
  odo_ = ctx.declare_signal_at(at + "encoder_delta", "1");
  state_ = ctx.declare_state("encoder", kSize, 0.0);
}

void Encoder::initialize(StepContext& ctx) {
  const Span<double> s = ctx.state(state_);
  s[kLast] = ctx.axis_position(axis_);
  s[kTravel] = s[kNoise] = s[kCount] = 0.0;
}

void Encoder::update(StepContext& ctx) {
  const Span<double> s = ctx.state(state_);
  const double q = ctx.axis_position(axis_);
  double delta = q - s[kLast];
  if (!linear_) delta = wrap_pi(delta);  // loop axes live in (−π, π]
  s[kLast] = q;
  s[kTravel] += delta;
  if (mean_ != 0.0 || stdev_ > 0.0)
    s[kNoise] += stdev_ > 0.0 ? ctx.random().normal(mean_, stdev_) : mean_;
  const double count = std::floor(ppr_ * s[kTravel] / (2 * kPi) + s[kNoise]);
  ctx.publish(odo_, count - s[kCount]);
  s[kCount] = count;
  ctx.publish(count_, count);
}

}  // namespace s2sim::drive_train
