// s2sim-run's watchdog (watchdog.hpp).
#include "watchdog.hpp"

#include "call_watch.hpp"
#include "crash_report.hpp"
#include "outputs.hpp"

#include <s2sim/kernel/simulation.hpp>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <vector>

namespace s2sim::runner {

namespace {
using Clock = std::chrono::steady_clock;
constexpr auto kSample = std::chrono::milliseconds(50);
constexpr std::size_t kMaxThreads = 256;
/// The slow-component warning: its window, and the share of the window's samples above which
/// one component is named (when the run is slower than real time over it).
constexpr double kWindowS = 2.0;
constexpr double kSlowShare = 0.5;
}  // namespace

Watchdog::Watchdog(double budget_s) : budget_s_(budget_s), thread_([this] { watch(); }) {}

Watchdog::~Watchdog() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void Watchdog::watch() {
  apps::CallWatch calls(kMaxThreads);
  // The window's samples: how many, and per component how many found it running.
  struct Share {
    const char* component;
    int samples;
  };
  std::vector<Share> shares;
  std::vector<const char*> warned;
  int window_samples = 0;
  Clock::time_point window_start = Clock::now();
  double window_sim_start = time_s_.load(std::memory_order_relaxed);

  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, kSample, [&] { return stop_; })) {
    const Clock::time_point now = Clock::now();
    calls.sample(now);
    for (const apps::CallWatch::Call& c : calls.calls()) {
      if (c.running_s(now) > budget_s_) {
        std::fprintf(stderr,
                     "s2sim-run: watchdog: %s has not returned from one call for %.1f s (the "
                     "budget, --watchdog %g s): the run is stopped; the --log file keeps every "
                     "complete row\n",
                     c.call.component, c.running_s(now), budget_s_);
        std::fflush(stderr);
        end_process_now(kExitWatchdog);
      }
      bool counted = false;
      for (Share& s : shares)
        if (s.component == c.call.component) counted = (++s.samples, true);
      if (!counted) shares.push_back({c.call.component, 1});
    }
    ++window_samples;
    const double window_s = std::chrono::duration<double>(now - window_start).count();
    if (window_s < kWindowS) continue;
    const double sim_s = time_s_.load(std::memory_order_relaxed) - window_sim_start;
    for (const Share& s : shares) {
      const double share = static_cast<double>(s.samples) / window_samples;
      if (share <= kSlowShare || sim_s >= window_s) continue;
      bool already = false;
      for (const char* w : warned)
        already = already || w == s.component;
      if (already) continue;
      warned.push_back(s.component);
      std::fprintf(stderr,
                   "s2sim-run: warning: %s ran %.0f %% of the wall time over %.1f s, in which "
                   "the simulation advanced %.3g s (%.2f x real time)\n",
                   s.component, 100 * share, window_s, sim_s, sim_s / window_s);
    }
    shares.clear();
    window_samples = 0;
    window_start = now;
    window_sim_start = time_s_.load(std::memory_order_relaxed);
  }
}

}  // namespace s2sim::runner
