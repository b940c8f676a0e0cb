#pragma once
/// \file
/// A small persistent pool of threads that runs the parts of the multibody
/// (multibody_islands.cpp). Created at load, joined at destruction; a run allocates nothing.
/// The tasks of a run are taken, not assigned: the calling thread and every worker that is
/// awake take the next task until none is left, so a worker the operating system has not
/// scheduled yet (a loaded machine) delays nothing, the caller doing its share. Idle workers
/// spin, then after 2 ms sleep on a condition variable (a paused simulation costs no CPU); a
/// worker that finds itself on the caller's core sleeps at once rather than take its time.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace s2sim::model {

class WorkerPool {
 public:
  /// One task: `index` in [0, count) of the run; `thread` 0 is the calling thread.
  using Task = void (*)(void* context, int index, int thread);

  /// `threads` ≥ 1: threads − 1 workers beside the caller; runs of up to `max_tasks` tasks
  /// (at most 65535).
  WorkerPool(int threads, int max_tasks);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return static_cast<int>(threads_.size()) + 1; }

  /// Runs task(context, i, thread) for every i in [0, count), count ≤ max_tasks, and returns
  /// when all have finished. An exception of a
  /// task is kept; after every task finished, the one of the lowest index is rethrown
  /// (deterministic whatever the threads' timing).
  void run(Task task, void* context, int count);

 private:
  void work(int thread);
  /// Takes and runs tasks of generation `generation` until none is left.
  void take_tasks(std::uint32_t generation, int thread) noexcept;

  std::vector<std::thread> threads_;
  std::vector<std::exception_ptr> errors_;  // per task, preallocated
  Task task_ = nullptr;
  void* context_ = nullptr;
  // The run's ticket: generation (bits 32..63), task count (16..31), next task (0..15). A worker
  // that wakes late sees another generation and takes nothing of a run it did not start.
  std::atomic<std::uint64_t> ticket_{0};
  std::atomic<int> done_{0};  // tasks finished in this run
  std::atomic<bool> stop_{false};
  std::atomic<int> sleepers_{0};
  std::atomic<int> caller_cpu_{-1};  // the core the last run was started on
  std::mutex mutex_;
  std::condition_variable wake_;
};

}  // namespace s2sim::model
