// A frame's stepping on its own thread, and the window's part while it runs
// (frame_stepping.hpp).
#include "frame_stepping.hpp"

#include "exit_codes.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <mutex>

namespace s2sim::viewer {

void FrameStepping::start(ViewerState& state, double wall_dt_s, bool fixed_pacing) {
  Simulation* sim = state.sim.get();
  StepGate* gate = gate_.get();
  since_ = Clock::now();
  stepper_.start([&state, sim, gate, wall_dt_s, fixed_pacing] {
    std::lock_guard<std::mutex> lock(gate->mutex);
    state.run.advance(*sim, wall_dt_s, state.chart, fixed_pacing, gate);
  });
}

bool FrameStepping::wait(ViewerState& state, bool fixed_pacing, double wait_s) {
  const auto until = Clock::now() + std::chrono::duration<double>(wait_s);
  const double slice_s = std::clamp(wait_s, 0.005, 0.05);
  for (;;) {
    if (stepper_.wait(slice_s)) {
      state.stuck = {};
      return true;
    }
    const auto now = Clock::now();
    calls_.sample(now);
    const apps::CallWatch::Call* call = calls_.longest(given_up_);
    state.stuck.component = call ? call->call.component : "";
    state.stuck.running_s =
        call ? call->running_s(now) : std::chrono::duration<double>(now - since_).count();
    const double budget_s = state.options.watchdog_s;
    if (fixed_pacing && budget_s > 0 && state.stuck.running_s > budget_s) {
      std::fprintf(stderr,
                   "s2sim-view: watchdog: %s has not returned for %.1f s (the budget, "
                   "--watchdog %g s): the viewer quits\n",
                   what_runs(state.stuck).c_str(), state.stuck.running_s, budget_s);
      std::fflush(nullptr);
      std::_Exit(apps::kExitWatchdog);  // the stuck thread may still need what exit() frees
    }
    if (!fixed_pacing && now >= until) {
      state.stuck.now = true;
      return false;
    }
  }
}

void FrameStepping::give_up(ViewerState& state, bool reload) {
  {
    std::lock_guard<std::mutex> lock(gate_->mutex);
    gate_->abandoned = true;
  }
  stepper_.abandon();
  for (const apps::CallWatch::Call& c : calls_.calls())  // still running, but no longer ours
    given_up_.push_back(c.call);
  (void)state.sim.release();  // the thread may still be in it: never freed
  (void)gate_.release();
  gate_ = std::make_unique<StepGate>();
  const std::string what = what_runs(state.stuck);
  const double running_s = state.stuck.running_s;
  state.stuck = {};
  if (!reload) return;
  RunControl paused;  // the user's settings kept; what the given-up run owed forgotten
  paused.playing = false;
  paused.speed = state.run.speed;
  paused.as_fast_as_possible = state.run.as_fast_as_possible;
  paused.frame_budget_s = state.run.frame_budget_s;
  paused.held_inputs = state.run.held_inputs;
  state.run = std::move(paused);
  state.pending_simulation = load_simulation_keeping_script_errors(state, state.options);
  char text[64];
  std::snprintf(text, sizeof text, " for %.1f s", running_s);
  state.log_message("stopped: " + what + " had not returned" + text +
                        "; it runs on in its own thread, and the scene is loaded again, paused",
                    true);
}

std::string FrameStepping::what_runs(const ViewerState::Stuck& stuck) {
  return stuck.component.empty() ? "the simulation's step (the kernel's own code)"
                                 : stuck.component;
}

}  // namespace s2sim::viewer
