#pragma once
/// \file
/// s2sim-run's watchdog (docs/reliability.md): a thread that samples what every thread runs
/// (s2sim::running_calls(), every 50 ms). One call into a component that lasts longer than the
/// budget ends the run: the component is named, the --log file keeps its complete rows, and
/// the runner exits with kExitWatchdog (8). A component that holds more than half of the wall
/// time over a window of the run while the run is slower than real time gets one warning that
/// names it.

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace s2sim::runner {

class Watchdog {
 public:
  /// `budget_s` > 0: the longest one call may last.
  explicit Watchdog(double budget_s);
  ~Watchdog();
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

  /// The simulated time reached (the stepping thread, after each chunk of steps).
  void progressed(double time_s) { time_s_.store(time_s, std::memory_order_relaxed); }

 private:
  void watch();

  double budget_s_;
  std::atomic<double> time_s_{0.0};
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace s2sim::runner
