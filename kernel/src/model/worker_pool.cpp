// The worker pool of the island-parallel step (worker_pool.hpp). No Simbody here.
#include "model/worker_pool.hpp"

#include "common/signal_stack.hpp"

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

inline std::uint64_t generation_of(std::uint64_t ticket) {
  return ticket >> 16;
}
inline int count_of(std::uint64_t ticket) {
  return static_cast<int>(ticket & 0xffff);
}

}  // namespace

WorkerPool::WorkerPool(int threads, int max_tasks)
    : errors_(std::min(kMaxTasks, static_cast<std::size_t>(max_tasks < 1 ? 1 : max_tasks))),
      claims_(std::make_unique<Claim[]>(errors_.size())) {
  const int workers = threads < 1 ? 0 : threads - 1;
  threads_.reserve(static_cast<std::size_t>(workers));
  for (int t = 1; t <= workers; ++t)
    threads_.emplace_back([this, t] { work(t); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_.store(true);
    ticket_.store((generation_of(ticket_.load()) + 1) << 16);
  }
  wake_.notify_all();
  for (auto& t : threads_)
    t.join();
}

bool WorkerPool::claim(int index, std::uint64_t generation) noexcept {
  std::atomic<std::uint64_t>& claimed = claims_[static_cast<std::size_t>(index)].generation;
  std::uint64_t seen = claimed.load(std::memory_order_relaxed);
  while (seen < generation)
    if (claimed.compare_exchange_weak(seen, generation, std::memory_order_acq_rel,
                                      std::memory_order_relaxed))
      return true;
  return false;
}

void WorkerPool::run_task(int index, int thread) noexcept {
  try {
    job_->run_task(index, thread);
  } catch (...) {
    errors_[static_cast<std::size_t>(index)] = std::current_exception();
  }
  done_.fetch_add(1, std::memory_order_acq_rel);
}

void WorkerPool::take_tasks(std::uint64_t generation, int thread) noexcept {
  const std::uint64_t ticket = ticket_.load(std::memory_order_acquire);
  if (generation_of(ticket) != generation) return;
  // A worker on the caller's core would only take the caller's time (and the caller would
  // then wait for it): leave the tasks to the caller.
  if (thread != 0 && sched_getcpu() == caller_cpu_.load(std::memory_order_relaxed)) return;
  const int count = count_of(ticket);
  const int threads = this->threads();
  for (int i = thread; i < count; i += threads)  // home first
    if (claim(i, generation)) run_task(i, thread);
  for (int i = 0; i < count; ++i)  // then what the others have not taken
    if (i % threads != thread && claim(i, generation)) run_task(i, thread);
}

void WorkerPool::run(Job& job, int count) {
  if (count <= 0) return;
  if (static_cast<std::size_t>(count) > errors_.size())
    throw std::logic_error("WorkerPool::run: more tasks than the pool was made for");
  job_ = &job;
  for (int i = 0; i < count; ++i)
    errors_[static_cast<std::size_t>(i)] = nullptr;
  if (threads_.empty()) {  // the serial mode: the same tasks, called here in order
    for (int i = 0; i < count; ++i)
      run_task(i, 0);
    rethrow_first(count);
    return;
  }
  done_.store(0, std::memory_order_relaxed);
  caller_cpu_.store(sched_getcpu(), std::memory_order_relaxed);
  const std::uint64_t generation = generation_of(ticket_.load()) + 1;
  // Sequentially consistent with the sleepers' count (a worker going to sleep increments it,
  // then reads the ticket): either it sees this generation or this run sees it asleep.
  ticket_.store((generation << 16) | static_cast<std::uint64_t>(count));  // publishes job_
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
  rethrow_first(count);
}

void WorkerPool::rethrow_first(int count) {
  for (int i = 0; i < count; ++i)
    if (errors_[static_cast<std::size_t>(i)])
      std::rethrow_exception(errors_[static_cast<std::size_t>(i)]);
}

void WorkerPool::work(int thread) {
  common::use_alternate_signal_stack();  // a crash report even when a part's stack overflows
  std::uint64_t seen = 0;
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
