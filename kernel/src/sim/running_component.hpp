#pragma once
/// \file
/// Which component's code is running, for a fatal-signal handler and for a watchdog on another
/// thread (Simulation's `running_component()`, `running_calls()`): the kernel marks every call
/// into a plugin (its factory, configure, initialize, update, destruction) with a pointer to the
/// component's pre-formatted label, and counts the calls. A few relaxed atomic stores each way:
/// no clock is read on the stepping path; a watchdog samples.

#include <atomic>
#include <cstddef>
#include <cstdint>

namespace s2sim::sim {

/// What one thread runs now: the label (null: the kernel's own code) and how many calls into
/// components it has begun, so that a watchdog tells one long call from many short ones. A
/// thread takes a slot at its first call; a cache line each (written by its own thread).
struct alignas(64) CallSlot {
  std::atomic<const char*> label{nullptr};
  std::atomic<std::uint64_t> calls{0};
};
inline constexpr std::size_t kMaxCallSlots = 256;  // threads that ever call a component
inline CallSlot g_call_slots[kMaxCallSlots];
inline std::atomic<std::size_t> g_call_slots_used{0};

/// The calling thread's slot (null past kMaxCallSlots threads: then unwatched).
inline CallSlot* this_thread_slot() {
  thread_local CallSlot* slot = [] {
    const std::size_t i = g_call_slots_used.fetch_add(1, std::memory_order_relaxed);
    return i < kMaxCallSlots ? &g_call_slots[i] : nullptr;
  }();
  return slot;
}

/// Per thread: the parts' threads run components at once (component_parts.hpp), and a fatal
/// signal is handled on the thread that raised it.
inline thread_local std::atomic<const char*> g_running_component{nullptr};

/// Marks `label` (a string that outlives the call) as running for the scope.
class RunningComponent {
 public:
  explicit RunningComponent(const char* label) : slot_(this_thread_slot()) {
    g_running_component.store(label, std::memory_order_relaxed);
    if (slot_) {
      slot_->calls.store(slot_->calls.load(std::memory_order_relaxed) + 1,
                         std::memory_order_relaxed);
      slot_->label.store(label, std::memory_order_release);
    }
  }
  ~RunningComponent() {
    g_running_component.store(nullptr, std::memory_order_relaxed);
    if (slot_) slot_->label.store(nullptr, std::memory_order_release);
  }
  RunningComponent(const RunningComponent&) = delete;
  RunningComponent& operator=(const RunningComponent&) = delete;

 private:
  CallSlot* slot_;
};

}  // namespace s2sim::sim
