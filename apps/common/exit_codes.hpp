#pragma once
/// \file
/// Exit codes of s2sim-run and s2sim-view beyond s2sim::exit_code()'s (0 ok, 2 scene,
/// 3 plugin, 4 usage, 5 runtime); the table is docs/reliability.md's.

namespace s2sim::apps {

/// S2Sim could not go on: the system refused memory or a thread (said so), or an internal error
/// (a bug).
inline constexpr int kExitCannotGoOn = 1;
/// The words of exit 1 when the system refused memory (std::bad_alloc) or another resource
/// (std::system_error: a thread, a mutex), after the program's name.
inline constexpr const char* kOutOfMemoryText =
    "out of memory: the system refused the memory this run needs (a process limit such as "
    "ulimit -v, or the machine's memory)";
inline constexpr const char* kResourceRefusedText =
    "the system refused a resource this run needs (a process limit such as ulimit -u, or the "
    "machine's)";

inline constexpr int kExitOutputFailed = 6;      ///< --log or --summary could not be written
inline constexpr int kExitComponentCrashed = 7;  ///< a fatal signal in a component
inline constexpr int kExitWatchdog = 8;          ///< one call into a component outlasted --watchdog
inline constexpr int kExitComponentExited = 9;   ///< a component called exit()

/// --watchdog's default: the wall seconds one call into a component may last, far beyond what
/// an honest scene's call takes.
inline constexpr double kDefaultWatchdogS = 120.0;

}  // namespace s2sim::apps
