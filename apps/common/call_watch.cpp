// Calls into components and how long they run (call_watch.hpp).
#include "call_watch.hpp"

#include <algorithm>

namespace s2sim::apps {

CallWatch::CallWatch(std::size_t max_threads) : now_running_(max_threads) {
  seen_.reserve(max_threads);
  next_.reserve(max_threads);
}

void CallWatch::sample(Clock::time_point now) {
  const std::size_t n = running_calls(now_running_.data(), now_running_.size());
  next_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const RunningCall& c = now_running_[i];
    Clock::time_point since = now;
    for (const Call& s : seen_)
      if (s.call.component == c.component && s.call.call == c.call) since = s.since;
    next_.push_back({c, since});
  }
  seen_.swap(next_);
}

const CallWatch::Call* CallWatch::longest(const std::vector<RunningCall>& ignored) const {
  const Call* longest = nullptr;
  for (const Call& c : seen_) {
    const bool left_out = std::any_of(ignored.begin(), ignored.end(), [&](const RunningCall& i) {
      return i.component == c.call.component && i.call == c.call.call;
    });
    if (!left_out && (!longest || c.since < longest->since)) longest = &c;
  }
  return longest;
}

}  // namespace s2sim::apps
