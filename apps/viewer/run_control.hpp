#pragma once
/// \file
/// Play, pause, single step, reset and speed: how many ticks each frame advances, with
/// real-time pacing and the measured real-time factor.

#include "chart_data.hpp"

#include <s2sim/kernel/simulation.hpp>

#include <array>
#include <cstdint>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace s2sim::viewer {

/// The real-time factor over the last `window_s` of wall time: simulated seconds done divided
/// by wall seconds elapsed between the oldest kept sample and the newest. It has a value from
/// the second sample on (no blank first half second), and a fixed ring of samples, so no
/// allocation per frame.
class RtfMeter {
 public:
  static constexpr double window_s = 0.5;
  /// One frame's reading: a monotonic wall clock and the simulated time, both in seconds.
  void sample(double wall_clock_s, double sim_time_s);
  /// Forget the samples (pause, reset: the simulated time jumps or stands still).
  void clear() { count_ = 0; }
  /// Simulated seconds per wall second; 0 until two samples with distinct wall times exist.
  double rtf() const;

 private:
  struct Sample {
    double wall_s, sim_s;
  };
  std::array<Sample, 256> ring_{};
  std::size_t newest_ = 0, count_ = 0;
};

/// How advance() shares the window's state when it runs on the stepping thread (stepper.hpp):
/// the caller holds `mutex` for the whole call, and advance() lets go of it only while the
/// simulation steps or resets. So the window can give up a run whose component never returns:
/// it sets `abandoned` under the mutex, and advance() touches nothing more once the step it is
/// in returns.
struct StepGate {
  std::mutex mutex;
  bool abandoned = false;
};

class RunControl {
 public:
  bool playing = true;
  /// Times real time (0.1 ... 1000); `as_fast_as_possible` overrides it.
  double speed = 1.0;
  bool as_fast_as_possible = false;
  /// Pause when the simulated time reaches this (scripts, "run until"); negative = never.
  double pause_at_s = -1;
  /// Wall time a frame may spend stepping, so the window stays responsive.
  double frame_budget_s = 0.025;

  /// Inputs held for the whole run (`--set`): set again after every reset, so that Reset
  /// replays the run as it started.
  std::vector<std::pair<std::string, double>> held_inputs;

  void request_step(std::int64_t ticks = 1) { pending_steps_ += ticks; }
  void request_reset() { pending_reset_ = true; }

  /// Advances the simulation for a frame that lasted `wall_dt_s`, recording the chart after
  /// every tick. `ignore_budget` (scripted runs) steps all the ticks the frame asks for, so
  /// results do not depend on the machine's speed. Returns the number of ticks done. With a
  /// `gate` (its mutex held by the caller), it returns as soon as the gate is abandoned.
  std::int64_t advance(Simulation& sim, double wall_dt_s, ChartData& chart,
                       bool ignore_budget = false, StepGate* gate = nullptr);

  /// Simulated seconds per wall second (measured on the steady clock, whatever `wall_dt_s`
  /// the frames were paced with) over the last half second of playing.
  double measured_rtf() const { return rtf_meter_.rtf(); }
  /// True when the simulation cannot keep up with the requested speed.
  bool falling_behind() const { return falling_behind_; }

 private:
  /// One tick and its chart sample; false when the gate was abandoned during the tick.
  bool step_one(Simulation& sim, ChartData& chart, StepGate* gate);
  /// Runs `what` (a step or a reset) with the gate let go.
  template <class What>
  static void outside_gate(StepGate* gate, What&& what);

  std::int64_t pending_steps_ = 0;
  bool pending_reset_ = false;
  double owed_sim_s_ = 0;  ///< simulated time the pacing still owes
  RtfMeter rtf_meter_;
  bool falling_behind_ = false;
};

}  // namespace s2sim::viewer
