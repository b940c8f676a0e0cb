#pragma once
/// \file
/// A small persistent pool of threads that runs the parts of the multibody
/// (multibody_islands.cpp). Created at load, joined at destruction; a run allocates nothing.
/// Task i's home is thread i mod threads: each thread runs its home tasks first, so that run
/// after run a part's data stays in its own core's cache (on this project's 2-vCPU machine a
/// part that changed threads at random cost 20–30 % more time, measured). Then it steals the
/// tasks not yet taken: a worker the operating system has not scheduled yet (a loaded machine)
/// delays nothing, the others doing its share. Idle workers
/// spin, then after 2 ms sleep on a condition variable (a paused simulation costs no CPU); a
/// worker that finds itself on the caller's core sleeps at once rather than take its time.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace s2sim::model {

class WorkerPool {
 public:
  /// The work of one run, task by task.
  class Job {
   public:
    /// Task `index` in [0, count) of the run, on `thread`: 0 is the calling thread; the task's
    /// home is index mod threads(), unless another thread stole it.
    virtual void run_task(int index, int thread) = 0;

   protected:
    ~Job() = default;
  };

  /// `threads` ≥ 1: threads − 1 workers beside the caller; runs of up to `max_tasks` tasks
  /// (at most 65535). With one thread a run calls its tasks in order on the caller's thread:
  /// the serial mode is the same code.
  WorkerPool(int threads, int max_tasks);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return static_cast<int>(threads_.size()) + 1; }

  /// Runs job.run_task(i, thread) for every i in [0, count), count ≤ max_tasks, and returns
  /// when all have finished. An exception of a task is kept; after every task finished, the
  /// one of the lowest index is rethrown (deterministic whatever the threads' timing).
  void run(Job& job, int count);
  /// The same for a callable f(index, thread), kept by reference for the run.
  template <class F>
  void run_each(F&& f, int count) {
    struct Call final : Job {
      explicit Call(F& f) : f_(f) {}
      void run_task(int index, int thread) override { f_(index, thread); }
      F& f_;
    } call(f);
    run(call, count);
  }

 private:
  void work(int thread);
  /// Takes and runs tasks of generation `generation` until none is left.
  void take_tasks(std::uint64_t generation, int thread) noexcept;
  /// Claims task `index` for `generation`: false if taken already (in this run or, for a late
  /// worker, in a later one).
  bool claim(int index, std::uint64_t generation) noexcept;
  void run_task(int index, int thread) noexcept;
  /// After a run of `count` tasks: the exception of the lowest task that threw, if any.
  void rethrow_first(int count);

  std::vector<std::thread> threads_;
  std::vector<std::exception_ptr> errors_;  // per task, preallocated
  Job* job_ = nullptr;
  // The run's ticket: generation (bits 16..63), task count (0..15). A worker that wakes late
  // sees another generation and takes nothing of a run it did not start.
  std::atomic<std::uint64_t> ticket_{0};
  // Per task, the generation of the last run that claimed it (claims only move it forward, so
  // a late worker's claim fails); a cache line each, as neighbours are claimed by other threads.
  struct alignas(64) Claim {
    std::atomic<std::uint64_t> generation{0};
  };
  std::unique_ptr<Claim[]> claims_;
  std::atomic<int> done_{0};  // tasks finished in this run
  std::atomic<bool> stop_{false};
  std::atomic<int> sleepers_{0};
  std::atomic<int> caller_cpu_{-1};  // the core the last run was started on
  std::mutex mutex_;
  std::condition_variable wake_;
};

}  // namespace s2sim::model
