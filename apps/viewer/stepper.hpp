#pragma once
/// \file
/// The viewer's stepping thread. Each frame's run control runs there while the window waits
/// for it, so that a component whose call does not return leaves the window drawing: it names
/// the call and offers to give the simulation up (docs/viewer.md, "A component that does not
/// return").

#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

namespace s2sim::viewer {

class Stepper {
 public:
  Stepper() = default;
  /// Ends the thread; a job still running is abandoned, not waited for.
  ~Stepper();
  Stepper(const Stepper&) = delete;
  Stepper& operator=(const Stepper&) = delete;

  /// Runs `job` on the stepping thread (begun on first use). Only when idle().
  void start(std::function<void()> job);
  /// Waits up to `timeout_s` for the job: true once it has ended, rethrowing what it threw.
  bool wait(double timeout_s);
  /// No job is running: none was started, or the last one ended and was waited for.
  bool idle() const { return !running_; }

  /// Leaves the running job's thread to itself: it goes on, detached, until the job returns,
  /// and then ends. Whatever the job uses must outlive it: native code cannot be stopped
  /// safely. The next start() begins a new thread.
  void abandon();
  /// A job was ever abandoned: the process should end without running destructors that the
  /// abandoned thread may still need.
  bool abandoned_any() const { return abandoned_any_; }

 private:
  struct Shared {
    std::mutex mutex;
    std::condition_variable wake;
    std::function<void()> job;
    bool has_job = false, done = false, quit = false;
    std::exception_ptr error;
  };
  static void serve(const std::shared_ptr<Shared>& shared);

  std::shared_ptr<Shared> shared_;
  std::thread thread_;
  bool running_ = false;
  bool abandoned_any_ = false;
};

}  // namespace s2sim::viewer
