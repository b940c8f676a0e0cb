/// \file
/// The fatal-signal handler (see the header). Only async-signal-safe calls: write(2) and
/// _exit(2), on strings that exist before the signal.

#include "crash_report.hpp"

#include "outputs.hpp"

#include <s2sim/kernel/simulation.hpp>

#include <unistd.h>

#include <csignal>
#include <cstring>

namespace s2sim::runner {
namespace {

void say(const char* text) {
  const std::size_t n = std::strlen(text);
  std::size_t done = 0;
  while (done < n) {
    const ssize_t w = ::write(STDERR_FILENO, text + done, n - done);
    if (w <= 0) return;
    done += static_cast<std::size_t>(w);
  }
}

const char* signal_name(int sig) {
  switch (sig) {
    case SIGSEGV:
      return "SIGSEGV (invalid memory access)";
    case SIGBUS:
      return "SIGBUS (bus error)";
    case SIGFPE:
      return "SIGFPE (arithmetic exception)";
    case SIGILL:
      return "SIGILL (illegal instruction)";
    case SIGABRT:
      return "SIGABRT (abort)";
    default:
      return "a fatal signal";
  }
}

void on_fatal_signal(int sig) {
  say("s2sim-run: fatal signal ");
  say(signal_name(sig));
  if (const char* component = running_component()) {
    say(" in ");
    say(component);
    say("\n");
  } else {
    say(" in S2Sim itself (no component was running): please report it\n");
  }
  say("s2sim-run: the --log file keeps every complete row written before it\n");
  ::_exit(kExitComponentCrashed);
}

}  // namespace

void install_crash_report() {
  struct sigaction action {};
  action.sa_handler = on_fatal_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND | SA_NODEFER;  // a fault in the handler ends the process
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT})
    ::sigaction(sig, &action, nullptr);
}

}  // namespace s2sim::runner
