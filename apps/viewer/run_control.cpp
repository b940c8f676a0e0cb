#include "run_control.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace s2sim::viewer {

void RunControl::step_one(Simulation& sim, ChartData& chart) {
  sim.step(1);
  chart.record(sim);
}

std::int64_t RunControl::advance(Simulation& sim, double wall_dt_s, ChartData& chart,
                                 bool ignore_budget) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  std::int64_t done = 0;
  if (pending_reset_) {
    pending_reset_ = false;
    pending_steps_ = 0;
    owed_sim_s_ = 0;
    sim.reset();
    for (const auto& [name, value] : held_inputs)  // reset() restores the scene's values
      sim.set_input(name, value);
    chart.clear_samples();
    chart.record(sim);
  }
  const double before_s = sim.time_s();
  // Single steps happen whether playing or not (a step while playing is simply one more).
  for (; pending_steps_ > 0; --pending_steps_, ++done)
    step_one(sim, chart);

  auto at_pause_point = [&] {
    return pause_at_s >= 0 && sim.time_s() >= pause_at_s - 0.5 * sim.tick_s();
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
        step_one(sim, chart);
        if ((n & 15) == 15 && over_budget()) break;
      }
    } else {
      owed_sim_s_ += std::min(wall_dt_s, 0.25) * speed;  // a long stall is not caught up
      while (owed_sim_s_ >= 0.5 * tick_s && !at_pause_point()) {
        step_one(sim, chart);
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

  if (playing) {
    rtf_window_wall_s_ += wall_dt_s;
    rtf_window_sim_s_ += sim.time_s() - before_s;
    if (rtf_window_wall_s_ >= 0.5) {
      measured_rtf_ = rtf_window_sim_s_ / rtf_window_wall_s_;
      rtf_window_wall_s_ = rtf_window_sim_s_ = 0;
    }
  } else {
    measured_rtf_ = 0;
    rtf_window_wall_s_ = rtf_window_sim_s_ = 0;
  }
  return done;
}

}  // namespace s2sim::viewer
