// The worker pool of the island-parallel step (worker_pool.hpp). No Simbody here.
#include "model/worker_pool.hpp"

#include <sched.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace s2sim::model {

namespace {

/// How long an idle worker busy-waits before sleeping, and the caller waits for the others
/// before yielding: between two runs (the serial stages of a tick) lie tens of microseconds,
/// while paused, forever. Not yield in between: on a core shared with another process (even a
/// niced one) a yield hands it the core for a whole time slice, and the next run starts
/// without the worker.
constexpr auto kSpinFor = std::chrono::milliseconds(2);
constexpr int kClockEvery = 64;  // spins between two reads of the clock
constexpr std::size_t kMaxTasks = 0xffff;

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

inline std::uint32_t generation_of(std::uint64_t ticket) {
  return static_cast<std::uint32_t>(ticket >> 32);
}

}  // namespace

WorkerPool::WorkerPool(int threads, int max_tasks)
    : errors_(std::min(kMaxTasks, static_cast<std::size_t>(max_tasks < 1 ? 1 : max_tasks))) {
  const int workers = threads < 1 ? 0 : threads - 1;
  threads_.reserve(static_cast<std::size_t>(workers));
  for (int t = 1; t <= workers; ++t)
    threads_.emplace_back([this, t] { work(t); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_.store(true);
    ticket_.store((static_cast<std::uint64_t>(generation_of(ticket_.load()) + 1) << 32));
  }
  wake_.notify_all();
  for (auto& t : threads_)
    t.join();
}

void WorkerPool::take_tasks(std::uint32_t generation, int thread) noexcept {
  std::uint64_t ticket = ticket_.load(std::memory_order_acquire);
  for (;;) {
    if (generation_of(ticket) != generation) return;
    // A worker on the caller's core would only take the caller's time (and the caller would
    // then wait for it): leave the tasks to the caller.
    if (thread != 0 && sched_getcpu() == caller_cpu_.load(std::memory_order_relaxed)) return;
    const auto next = static_cast<int>(ticket & 0xffff);
    const auto count = static_cast<int>((ticket >> 16) & 0xffff);
    if (next >= count) return;
    if (!ticket_.compare_exchange_weak(ticket, ticket + 1, std::memory_order_acq_rel,
                                       std::memory_order_acquire))
      continue;  // `ticket` now holds the current value
    try {
      task_(context_, next, thread);
    } catch (...) {
      errors_[static_cast<std::size_t>(next)] = std::current_exception();
    }
    done_.fetch_add(1, std::memory_order_acq_rel);
    ticket = ticket_.load(std::memory_order_acquire);
  }
}

void WorkerPool::run(Task task, void* context, int count) {
  if (count <= 0) return;
  if (static_cast<std::size_t>(count) > errors_.size())
    throw std::logic_error("WorkerPool::run: more tasks than the pool was made for");
  task_ = task;
  context_ = context;
  for (int i = 0; i < count; ++i)
    errors_[static_cast<std::size_t>(i)] = nullptr;
  done_.store(0, std::memory_order_relaxed);
  caller_cpu_.store(sched_getcpu(), std::memory_order_relaxed);
  const std::uint32_t generation = generation_of(ticket_.load()) + 1;
  // Sequentially consistent with the sleepers' count (a worker going to sleep increments it,
  // then reads the ticket): either it sees this generation or this run sees it asleep.
  ticket_.store((static_cast<std::uint64_t>(generation) << 32) |
                (static_cast<std::uint64_t>(count) << 16));  // publishes task_, context_
  if (sleepers_.load() > 0) {
    std::lock_guard<std::mutex> lock(mutex_);
    wake_.notify_all();
  }
  take_tasks(generation, 0);
  // The others are running their last tasks: wait for them, yielding only if it lasts.
  const auto start = std::chrono::steady_clock::now();
  bool yield = false;
  for (int spin = 1; done_.load(std::memory_order_acquire) != count; ++spin) {
    if (yield) {
      std::this_thread::yield();
    } else {
      cpu_relax();
      if (spin % kClockEvery == 0) yield = std::chrono::steady_clock::now() - start > kSpinFor;
    }
  }
  for (int i = 0; i < count; ++i)
    if (errors_[static_cast<std::size_t>(i)])
      std::rethrow_exception(errors_[static_cast<std::size_t>(i)]);
}

void WorkerPool::work(int thread) {
  std::uint32_t seen = 0;
  for (;;) {
    // Wait for the next run: spin, then sleep.
    const auto start = std::chrono::steady_clock::now();
    for (int spin = 1; generation_of(ticket_.load(std::memory_order_acquire)) == seen; ++spin) {
      cpu_relax();
      if (spin % kClockEvery != 0) continue;
      // Spinning on the caller's own core would take its time (a loaded machine put both
      // there): sleep instead, and let the scheduler place the wake-up.
      if (sched_getcpu() != caller_cpu_.load(std::memory_order_relaxed) &&
          std::chrono::steady_clock::now() - start < kSpinFor)
        continue;
      std::unique_lock<std::mutex> lock(mutex_);
      sleepers_.fetch_add(1);
      wake_.wait(lock, [&] { return generation_of(ticket_.load()) != seen; });
      sleepers_.fetch_sub(1);
    }
    seen = generation_of(ticket_.load(std::memory_order_acquire));
    if (stop_.load()) return;
    take_tasks(seen, thread);
  }
}

}  // namespace s2sim::model
