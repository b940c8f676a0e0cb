#pragma once
/// \file
/// Exit codes of s2sim-run and s2sim-view beyond s2sim::exit_code()'s (0 ok, 2 scene,
/// 3 plugin, 4 usage, 5 runtime); the table is docs/reliability.md's.

namespace s2sim::apps {

inline constexpr int kExitOutputFailed = 6;      ///< --log or --summary could not be written
inline constexpr int kExitComponentCrashed = 7;  ///< a fatal signal in a component
inline constexpr int kExitWatchdog = 8;          ///< one call into a component outlasted --watchdog
inline constexpr int kExitComponentExited = 9;   ///< a component called exit()

/// --watchdog's default: the wall seconds one call into a component may last, far beyond what
/// an honest scene's call takes.
inline constexpr double kDefaultWatchdogS = 120.0;

}  // namespace s2sim::apps
