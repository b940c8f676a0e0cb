#pragma once
/// \file
/// The wall-clock waits of the links: the longest a scene may ask for (a lock-step period's
/// `wait_s`, a real-time `timeout_s`), and the cap an unattended run puts on lock-step waits.

#include <s2sim/error.hpp>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

namespace s2sim::links {

/// A longer wait is a hang, and past it a clock's duration would overflow.
constexpr double kMaxWait_s = 86400;  // a day

/// Caps every lock-step wait of the process: a CI job or a fuzzer that runs lock-step scenes
/// without their clients or devices sets it, so that a scene asking for a long wait cannot hang
/// the job. The scene's own value applies when it is shorter.
constexpr const char* kWaitCapVariable = "S2SIM_LINK_WAIT_MAX_S";

/// The lock-step wait a link applies for the scene's `wait_s`. A cap that is not a number in
/// (0, kMaxWait_s] is a usage error naming the variable and its value.
inline double applied_wait_s(double scene_wait_s) {
  const char* text = std::getenv(kWaitCapVariable);
  if (text == nullptr || *text == '\0') return scene_wait_s;
  char* end = nullptr;
  errno = 0;
  const double cap = std::strtod(text, &end);
  if (*end != '\0' || errno != 0 || !std::isfinite(cap) || cap <= 0 || cap > kMaxWait_s)
    throw Error(ErrorKind::usage, std::string("environment variable ") + kWaitCapVariable + "='" +
                                      text + "' is not a wait in seconds in (0, " +
                                      std::to_string(static_cast<long>(kMaxWait_s)) + "]");
  return cap < scene_wait_s ? cap : scene_wait_s;
}

}  // namespace s2sim::links
