#pragma once
/// \file
/// The longest wall-clock wait a link may be given (a lock-step period's `wait_s`, a real-time
/// `timeout_s`): a longer one is a hang, and past it a clock's duration would overflow.

namespace s2sim::links {

constexpr double kMaxWait_s = 86400;  // a day

}  // namespace s2sim::links
