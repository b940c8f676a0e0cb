#include "run_control.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

namespace s2sim::viewer {

void RtfMeter::sample(double wall_clock_s, double sim_time_s) {
  newest_ = count_ == 0 ? 0 : (newest_ + 1) % ring_.size();
  ring_[newest_] = {wall_clock_s, sim_time_s};
  count_ = std::min(count_ + 1, ring_.size());
}

double RtfMeter::rtf() const {
  if (count_ < 2) return 0;
  const Sample& newest = ring_[newest_];
  // The oldest kept sample still inside the window (or the oldest kept, if the ring is full).
  std::size_t oldest = newest_;
  for (std::size_t k = 1; k < count_; ++k) {
    const std::size_t i = (newest_ + ring_.size() - k) % ring_.size();
    if (newest.wall_s - ring_[i].wall_s > window_s) break;
    oldest = i;
  }
  if (oldest == newest_) oldest = (newest_ + ring_.size() - 1) % ring_.size();  // one long frame
  const double wall_s = newest.wall_s - ring_[oldest].wall_s;
  return wall_s > 0 ? (newest.sim_s - ring_[oldest].sim_s) / wall_s : 0;
}

template <class What>
void RunControl::outside_gate(StepGate* gate, What&& what) {
  if (!gate) {
    what();
    return;
  }
  gate->mutex.unlock();
  struct Relock {  // also when `what` throws: the caller's lock owns the mutex again
    StepGate* gate;
    ~Relock() { gate->mutex.lock(); }
  } relock{gate};
  what();
}

bool RunControl::step_one(Simulation& sim, ChartData& chart, StepGate* gate) {
  outside_gate(gate, [&] { sim.step(1); });
  if (gate && gate->abandoned) return false;
  chart.record(sim);
  return true;
}

std::int64_t RunControl::advance(Simulation& sim, double wall_dt_s, ChartData& chart,
                                 bool ignore_budget, StepGate* gate) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  std::int64_t done = 0;
  if (pending_reset_) {
    pending_reset_ = false;
    rtf_meter_.clear();
    pending_steps_ = 0;
    owed_sim_s_ = 0;
    outside_gate(gate, [&] { sim.reset(); });
    if (gate && gate->abandoned) return done;
    for (const auto& [name, value] : held_inputs)  // reset() restores the scene's values
      sim.set_input(name, value);
    chart.clear_samples();
    chart.record(sim);
  }
  // Single steps happen whether playing or not (a step while playing is simply one more).
  for (; pending_steps_ > 0; --pending_steps_, ++done)
    if (!step_one(sim, chart, gate)) return done;

  // A SimTwo script's CloseSimTwo (signal controllers/script/close) stops the run too.
  const std::optional<std::size_t> close = sim.find_signal("controllers/script/close");
  auto at_pause_point = [&] {
    return (pause_at_s >= 0 && sim.time_s() >= pause_at_s - 0.5 * sim.tick_s()) ||
           (close && sim.signal(*close) != 0);
  };
  if (playing && !at_pause_point()) {
    const double tick_s = sim.tick_s();
    auto over_budget = [&] {
      return !ignore_budget &&
             std::chrono::duration<double>(Clock::now() - start).count() > frame_budget_s;
    };
    falling_behind_ = false;
    if (as_fast_as_possible) {
      // Step until the frame's wall budget is spent (or, scripted, a fixed 1/60 s of wall
      // time's worth at 1000x, i.e. about 17 s simulated).
      const std::int64_t cap =
          ignore_budget ? static_cast<std::int64_t>(std::llround(16.7 / tick_s)) : INT64_MAX;
      for (std::int64_t n = 0; n < cap && !at_pause_point(); ++n, ++done) {
        if (!step_one(sim, chart, gate)) return done;
        if ((n & 15) == 15 && over_budget()) break;
      }
    } else {
      owed_sim_s_ += std::min(wall_dt_s, 0.25) * speed;  // a long stall is not caught up
      while (owed_sim_s_ >= 0.5 * tick_s && !at_pause_point()) {
        if (!step_one(sim, chart, gate)) return done;
        ++done;
        owed_sim_s_ -= tick_s;
        if ((done & 15) == 15 && over_budget()) {
          falling_behind_ = true;
          owed_sim_s_ = 0;  // drop what cannot be done: slower than asked, never a backlog
          break;
        }
      }
    }
    if (at_pause_point()) {
      playing = false;
      owed_sim_s_ = 0;
    }
  }

  // Measured on the steady clock, not from `wall_dt_s`: scripted runs pace with a fixed
  // frame time, and the factor shown must be what a watch says. (It used to be summed from
  // wall_dt_s in half-second windows: 0.00x until the first window closed.)
  if (playing)
    rtf_meter_.sample(std::chrono::duration<double>(Clock::now().time_since_epoch()).count(),
                      sim.time_s());
  else
    rtf_meter_.clear();
  return done;
}

}  // namespace s2sim::viewer
