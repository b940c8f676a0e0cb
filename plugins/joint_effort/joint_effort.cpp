/// \file
/// joint_effort: the torque (or force) input of an actuated joint of a URDF, SDF or MJCF robot,
/// bounded by the joint's effort limit as the formats define it (URDF `<limit effort>`, SDF
/// `<effort>`, MJCF `forcerange`, or `ctrlrange` times `gear`) (docs/models/import.md).
///
///     <plugin kind='joint_effort' axis='shoulder' limit='150'/>   <!-- no limit: unbounded -->
///
/// Input `<axis>/effort` (N·m, N on a slider), held until set again; signal
/// `<axis>/effort_applied`, what the axis received: the input clamped to ±limit.

#include <s2sim/plugin.hpp>
#include <s2sim/sdk.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace {

class JointEffort final : public s2sim::Component {
 public:
  void configure(s2sim::ConfigureContext& ctx) override {
    ctx.declare_local();  // one axis, its input and signal
    const s2sim::Params& p = ctx.params();
    axis_ = ctx.axis(p.text("axis"));
    limit_ =
        p.number("limit", std::numeric_limits<double>::infinity(), s2sim::Range::non_negative());
    const bool linear = ctx.axis_is_linear(axis_);
    const std::string at = ctx.axis_prefix(axis_) + "/";
    effort_ = ctx.declare_input_at(at + "effort", linear ? "N" : "N*m", 0.0);
    applied_ = ctx.declare_signal_at(at + "effort_applied", linear ? "N" : "N*m");
  }

  void update(s2sim::StepContext& ctx) override {
    const double asked = ctx.input(effort_);
    // A NaN request is refused by the clamp's comparison: nothing is applied.
    const double applied = std::isnan(asked) ? 0.0 : std::clamp(asked, -limit_, limit_);
    if (applied != 0.0) ctx.apply_axis_force(axis_, applied);
    ctx.publish(applied_, applied);
  }

 private:
  s2sim::AxisHandle axis_;
  double limit_ = 0;
  s2sim::InputHandle effort_;
  s2sim::SignalHandle applied_;
};

}  // namespace

S2SIM_PLUGIN("joint_effort", S2SIM_KIND("joint_effort", s2sim::Category::actuator, JointEffort));
