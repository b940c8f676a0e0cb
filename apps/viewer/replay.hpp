#pragma once
/// \file
/// Playing a recording (`s2sim-view --replay FILE`, docs/recording.md): a clock over the
/// recorded times that runs forwards or backwards at any speed, or is dragged on the timeline;
/// the frame shown is the last recorded one at or before the clock. Showing a frame restores
/// its snapshot into the simulation (so the world view, the body window and the signals are
/// exactly the recorded run's) and refills the chart from the recorded signals up to it.

#include "chart_data.hpp"

#include <recording.hpp>

#include <s2sim/kernel/simulation.hpp>

#include <cstddef>
#include <vector>

namespace s2sim::viewer {

class Replay {
 public:
  explicit Replay(apps::Recording recording);

  const apps::Recording& recording() const { return recording_; }
  bool playing = true;
  /// Recorded seconds per wall second; negative plays backwards.
  double speed = 1.0;

  double start_s() const { return recording_.times_s.front(); }
  double end_s() const { return recording_.times_s.back(); }
  /// The clock (between start_s() and end_s()).
  double time_s() const { return time_s_; }
  /// The frame the clock is on.
  std::size_t frame() const { return recording_.frame_at(time_s_); }
  /// Moves the clock (clamped to the recording).
  void seek(double time_s);
  /// Moves `frames` frames (negative: back) from the current one.
  void step_frames(long frames);
  /// Advances the clock by `wall_dt_s` times the speed while playing; pauses at either end.
  void advance(double wall_dt_s);
  /// Shows the clock's frame: restores it into `sim` and refills `chart`, when either
  /// changed since the last call.
  void show(Simulation& sim, ChartData& chart);

 private:
  apps::Recording recording_;
  double time_s_ = 0;
  std::size_t shown_frame_ = static_cast<std::size_t>(-1);
  std::vector<std::size_t> charted_;  ///< the chart's signals when last refilled
  Simulation::Snapshot snapshot_;     ///< reused for every restore
};

}  // namespace s2sim::viewer
