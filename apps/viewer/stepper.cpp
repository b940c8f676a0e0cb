// The viewer's stepping thread (stepper.hpp).
#include "stepper.hpp"

#include <s2sim/kernel/simulation.hpp>

#include <chrono>
#include <utility>

namespace s2sim::viewer {

Stepper::~Stepper() {
  if (running_) abandon();  // never wait on a call that may not return
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->quit = true;
  }
  shared_->wake.notify_all();
  thread_.join();
}

void Stepper::serve(const std::shared_ptr<Shared>& shared) {
  use_alternate_signal_stack();  // a stack overflow in a component still gets reported
  Shared& s = *shared;
  std::unique_lock<std::mutex> lock(s.mutex);
  for (;;) {
    s.wake.wait(lock, [&] { return s.has_job || s.quit; });
    if (!s.has_job) return;
    std::function<void()> job = std::move(s.job);
    s.has_job = false;
    lock.unlock();
    std::exception_ptr error;
    try {
      job();
    } catch (...) {
      error = std::current_exception();
    }
    job = nullptr;
    lock.lock();
    s.error = error;
    s.done = true;
    s.wake.notify_all();
  }
}

void Stepper::start(std::function<void()> job) {
  if (!thread_.joinable()) {
    shared_ = std::make_shared<Shared>();
    thread_ = std::thread([shared = shared_] { serve(shared); });
  }
  {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->job = std::move(job);
    shared_->has_job = true;
    shared_->done = false;
  }
  shared_->wake.notify_all();
  running_ = true;
}

bool Stepper::wait(double timeout_s) {
  if (!running_) return true;
  std::unique_lock<std::mutex> lock(shared_->mutex);
  if (!shared_->wake.wait_for(lock, std::chrono::duration<double>(timeout_s),
                              [&] { return shared_->done; }))
    return false;
  running_ = false;
  if (std::exception_ptr error = std::exchange(shared_->error, nullptr))
    std::rethrow_exception(error);
  return true;
}

void Stepper::abandon() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->quit = true;  // the thread ends once its job returns, if ever
  }
  shared_->wake.notify_all();
  thread_.detach();
  shared_.reset();
  running_ = false;
  abandoned_any_ = true;
}

}  // namespace s2sim::viewer
