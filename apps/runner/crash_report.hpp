#pragma once
/// \file
/// What s2sim-run does on a fatal signal (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT): it says
/// which component's code was running (s2sim::running_component(): the plugin and kind), else
/// which plugin's or script's library the faulting thread was in (a thread of a plugin's own),
/// else that the kernel's code was; a stack overflow is named as one (the handler runs on an
/// alternate stack). It exits with kExitComponentCrashed (7). A component that calls exit() is
/// named too, and the runner exits with kExitComponentExited (9) instead of the code it asked; so
/// is one that calls _exit() or _Exit() (exit_guard.cpp). The
/// CSV log already holds every complete row (CsvLog writes each row through), so nothing else needs
/// flushing.

namespace s2sim::runner {

/// Installs the handlers; call once at start.
void install_crash_report();

/// Ends the process at once with `code` (no handlers, no destructors): the runner's own quick
/// ends, which must not pass for a component's _exit(). Async-signal-safe.
[[noreturn]] void end_process_now(int code) noexcept;

}  // namespace s2sim::runner
