#pragma once
/// \file
/// How long each call into a component has been running, from samples of
/// s2sim::running_calls(): a call seen with the same component and call number in two samples
/// has not returned in between. The runner's watchdog samples on its own thread; the viewer
/// samples once a frame while its stepping thread has not come back.

#include <s2sim/kernel/simulation.hpp>

#include <chrono>
#include <cstddef>
#include <vector>

namespace s2sim::apps {

class CallWatch {
 public:
  using Clock = std::chrono::steady_clock;
  /// One call running now, and since when it has been seen running.
  struct Call {
    RunningCall call;
    Clock::time_point since;
    double running_s(Clock::time_point now) const {
      return std::chrono::duration<double>(now - since).count();
    }
  };

  /// `max_threads`: how many threads' calls one sample reads.
  explicit CallWatch(std::size_t max_threads = 256);

  /// Samples what runs at `now`; calls() then lists it.
  void sample(Clock::time_point now);
  const std::vector<Call>& calls() const { return seen_; }
  /// The call running longest in the last sample, leaving out the `ignored` ones (calls given
  /// up on), or nullptr when none runs.
  const Call* longest(const std::vector<RunningCall>& ignored = {}) const;

 private:
  std::vector<RunningCall> now_running_;
  std::vector<Call> seen_, next_;
};

}  // namespace s2sim::apps
