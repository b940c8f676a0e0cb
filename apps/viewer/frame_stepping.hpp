#pragma once
/// \file
/// Each frame's run control on the stepping thread (stepper.hpp), and what the window does
/// while it has not come back: wait in a run paced by frames (past --watchdog: name the call,
/// exit 8), go on drawing by hand with ViewerState::stuck saying what runs, and give the run up
/// on request (docs/viewer.md, "A component that does not return").

#include "call_watch.hpp"
#include "run_control.hpp"
#include "stepper.hpp"
#include "viewer_state.hpp"

#include <chrono>
#include <memory>
#include <string>
#include <vector>

namespace s2sim::viewer {

class FrameStepping {
 public:
  /// How long the first wait for a frame's stepping lasts before the window shows the call
  /// that has not returned and goes on drawing.
  static constexpr double kStuckAfterS = 1.0;

  /// No frame's stepping is running.
  bool idle() const { return stepper_.idle(); }
  /// Starts this frame's RunControl::advance on the stepping thread.
  void start(ViewerState& state, double wall_dt_s, bool fixed_pacing);
  /// Waits for it: with `fixed_pacing` until it is done (past --watchdog on one call it names
  /// the call and quits with exit 8), else at most `wait_s`. True once done; false while it
  /// runs on, with state.stuck saying what runs.
  bool wait(ViewerState& state, bool fixed_pacing, double wait_s);
  /// Leaves the stepping thread in its call with the simulation it uses (never freed) and,
  /// with `reload`, loads the scene again, paused.
  void give_up(ViewerState& state, bool reload = true);
  /// A stepping thread was given up: the process should end without the destructors it may
  /// still need.
  bool abandoned_any() const { return stepper_.abandoned_any(); }

  /// The call that has not returned, as messages name it.
  static std::string what_runs(const ViewerState::Stuck& stuck);

 private:
  using Clock = std::chrono::steady_clock;
  Stepper stepper_;
  std::unique_ptr<StepGate> gate_ = std::make_unique<StepGate>();
  apps::CallWatch calls_;
  std::vector<RunningCall> given_up_;  ///< calls of given-up runs, never named again
  Clock::time_point since_;
};

}  // namespace s2sim::viewer
