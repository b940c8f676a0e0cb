#include "replay.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::viewer {

Replay::Replay(apps::Recording recording) : recording_(std::move(recording)) {
  time_s_ = start_s();
  snapshot_.layout = recording_.header.layout;
  snapshot_.segments = recording_.header.segments;
}

void Replay::seek(double time_s) {
  time_s_ = std::clamp(time_s, start_s(), end_s());
}

void Replay::step_frames(long frames) {
  const long last = static_cast<long>(recording_.frame_count()) - 1;
  const long k = std::clamp(static_cast<long>(frame()) + frames, 0L, last);
  time_s_ = recording_.times_s[static_cast<std::size_t>(k)];
}

void Replay::advance(double wall_dt_s) {
  if (!playing) return;
  time_s_ += std::min(wall_dt_s, 0.25) * speed;  // a long stall is not caught up
  if (time_s_ >= end_s() || time_s_ <= start_s()) {
    seek(time_s_);
    playing = false;
  }
}

void Replay::show(Simulation& sim, ChartData& chart) {
  const std::size_t k = frame();
  const bool chart_changed = chart.signals() != charted_;
  if (k == shown_frame_ && !chart_changed) return;
  if (k != shown_frame_) {
    const std::size_t begin = recording_.state_begin[k];
    const std::size_t end =
        k + 1 < recording_.frame_count() ? recording_.state_begin[k + 1] : recording_.states.size();
    snapshot_.values.assign(recording_.states.begin() + static_cast<long>(begin),
                            recording_.states.begin() + static_cast<long>(end));
    sim.restore(snapshot_);
    shown_frame_ = k;
  }
  // The chart as it would stand at this frame: its span of recorded rows up to it.
  charted_ = chart.signals();
  chart.clear_samples();
  const std::size_t first = recording_.frame_at(recording_.times_s[k] - chart.span_s());
  for (std::size_t i = first; i <= k; ++i)
    chart.record(recording_.times_s[i], recording_.header.tick_s, recording_.signal_row(i));
}

}  // namespace s2sim::viewer
