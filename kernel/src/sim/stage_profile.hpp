#pragma once
/// \file
/// Time spent per stage of the tick pipeline (sim/step.cpp), for `s2sim-bench --profile`.
/// Off unless asked for: a null profile costs one pointer test per stage.

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>

namespace s2sim::sim {

/// The stages of a tick, in the order they run (docs/architecture.md).
enum class PipelineStage : std::uint8_t {
  sense,          ///< sensor components
  control,        ///< controllers
  motor_control,  ///< motor controllers
  actuate,        ///< motors, servos and other actuators write their loads
  collide,        ///< contact: narrow phase and contact forces (per substep)
  prepare_axes,   ///< axis drives' rows and sliding axes' friction for the substep
  accelerations,  ///< M·u' = f under every load, the chosen dynamics (per substep)
  kick,           ///< u += h·u' (per substep)
  axes,           ///< axis drives (implicit) and Coulomb friction (per substep)
  drift,          ///< q += h·N(q)·u (per substep)
  project,        ///< loop constraints (per substep)
  finish,         ///< the multibody's end of tick: drives' means, bodies read, finite check
  read_out,       ///< the kernel's poses, twists and axes, the components' view refreshed
  count
};

/// Display name of a stage.
const char* stage_name(PipelineStage stage);

/// Accumulated wall time and calls per stage.
struct StageProfile {
  static constexpr std::size_t kStages = static_cast<std::size_t>(PipelineStage::count);
  std::array<double, kStages> seconds{};
  std::array<std::int64_t, kStages> calls{};
};

/// Adds the time from construction to destruction to one stage of `profile` (if not null).
class StageTimer {
 public:
  StageTimer(StageProfile* profile, PipelineStage stage) : profile_(profile), stage_(stage) {
    if (profile_) start_ = std::chrono::steady_clock::now();
  }
  ~StageTimer() {
    if (!profile_) return;
    const auto i = static_cast<std::size_t>(stage_);
    profile_->seconds[i] +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    ++profile_->calls[i];
  }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  StageProfile* profile_;
  PipelineStage stage_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace s2sim::sim
