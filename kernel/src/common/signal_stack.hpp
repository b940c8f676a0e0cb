#pragma once
/// \file
/// An alternate stack for the calling thread's signal handlers, so that a fatal-signal handler
/// still runs when the thread's own stack is exhausted (an endless recursion in a script or a
/// plugin). Handlers use it when installed with SA_ONSTACK (s2sim-run's crash report).

namespace s2sim::common {

/// Gives the calling thread its own alternate signal stack, once per thread (freed when the
/// thread ends). Async-signal handlers installed with SA_ONSTACK then run on it.
void use_alternate_signal_stack() noexcept;

}  // namespace s2sim::common
