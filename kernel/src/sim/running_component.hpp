#pragma once
/// \file
/// Which component's code is running, for a fatal-signal handler (Simulation's
/// `running_component()`): the kernel sets a pointer to the component's pre-formatted label
/// around every call into a plugin and clears it after. One atomic store each way; reading it
/// from a signal handler is async-signal-safe.

#include <atomic>

namespace s2sim::sim {

/// Per thread: the parts' threads run components at once (component_parts.hpp), and a fatal
/// signal is handled on the thread that raised it.
inline thread_local std::atomic<const char*> g_running_component{nullptr};

/// Marks `label` (a string that outlives the call) as running for the scope.
class RunningComponent {
 public:
  explicit RunningComponent(const char* label) {
    g_running_component.store(label, std::memory_order_relaxed);
  }
  ~RunningComponent() { g_running_component.store(nullptr, std::memory_order_relaxed); }
  RunningComponent(const RunningComponent&) = delete;
  RunningComponent& operator=(const RunningComponent&) = delete;
};

}  // namespace s2sim::sim
