/// \file
/// The fatal-signal handler (see the header). It runs on the thread's alternate stack, so a
/// stack overflow is reported too, and uses only what is safe there in practice: write(2),
/// _exit(2), dladdr and backtrace (warmed up at install, so that it does not load or
/// allocate in the handler), on strings that exist before the signal.

#include "crash_report.hpp"

#include "outputs.hpp"

#include <s2sim/kernel/simulation.hpp>

#include <dlfcn.h>
#include <execinfo.h>
#include <ucontext.h>
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <cstdlib>
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

/// Where the faulting thread was: its instruction and stack pointers, when the platform says.
struct Faulting {
  const void* instruction = nullptr;
  std::uintptr_t stack = 0;
};
Faulting faulting(void* context) {
  Faulting at;
  const auto* uc = static_cast<const ucontext_t*>(context);
  if (!uc) return at;
#if defined(__x86_64__)
  at.instruction = reinterpret_cast<const void*>(uc->uc_mcontext.gregs[REG_RIP]);
  at.stack = static_cast<std::uintptr_t>(uc->uc_mcontext.gregs[REG_RSP]);
#elif defined(__aarch64__)
  at.instruction = reinterpret_cast<const void*>(uc->uc_mcontext.pc);
  at.stack = static_cast<std::uintptr_t>(uc->uc_mcontext.sp);
#endif
  return at;
}

/// The shared library (not s2sim-run itself, not the C and C++ runtimes) that holds `address`,
/// or null: a plugin's or a compiled script's code, even on a thread of its own.
const char* foreign_library(const void* address) {
  Dl_info info{};
  if (!address || ::dladdr(address, &info) == 0 || !info.dli_fname || !info.dli_fname[0])
    return nullptr;
  Dl_info self{};
  if (::dladdr(reinterpret_cast<const void*>(&foreign_library), &self) != 0 &&
      info.dli_fbase == self.dli_fbase)
    return nullptr;
  const char* base = std::strrchr(info.dli_fname, '/');
  base = base ? base + 1 : info.dli_fname;
  for (const char* runtime : {"libc.so", "libstdc++.so", "libgcc_s.so", "libm.so", "ld-linux"})
    if (std::strncmp(base, runtime, std::strlen(runtime)) == 0) return nullptr;
  return info.dli_fname;
}

/// The first foreign library on the faulting thread's stack, from the faulting instruction up.
const char* library_at_fault(const Faulting& at) {
  if (const char* lib = foreign_library(at.instruction)) return lib;
  void* frames[64];
  const int n = ::backtrace(frames, 64);
  for (int i = 0; i < n; ++i)
    if (const char* lib = foreign_library(frames[i])) return lib;
  return nullptr;
}

void on_fatal_signal(int sig, siginfo_t* info, void* context) {
  const Faulting at = faulting(context);
  say("s2sim-run: fatal signal ");
  say(signal_name(sig));
  // A fault just below the stack pointer: the stack ran out (an endless recursion).
  const auto address = reinterpret_cast<std::uintptr_t>(info ? info->si_addr : nullptr);
  const bool overflow = sig == SIGSEGV && at.stack != 0 && address != 0 &&
                        address <= at.stack + 4096 && at.stack - address < (1u << 20);
  if (overflow) say(", a stack overflow (endless recursion?),");
  if (const char* component = running_component()) {
    say(" in ");
    say(component);
    say("\n");
  } else if (const char* library = library_at_fault(at)) {
    say(" in the code of ");
    say(library);
    say(", outside any call of the kernel into a component (on a thread of its own?)\n");
  } else {
    say(" in S2Sim itself (no component was running): please report it\n");
  }
  say("s2sim-run: the --log file keeps every complete row written before it\n");
  end_process_now(kExitComponentCrashed);
}

/// exit() from inside a call into a component (a plugin's `exit(0)`): the run did not end, it
/// was ended. Named and given its own code instead of passing for a completed run (0) or a
/// plugin error (3).
void on_exit_call() {
  const char* component = running_component();
  if (!component) return;  // the runner's own return from main
  say("s2sim-run: ");
  say(component);
  say(" called exit() during its call: the run is stopped there; the --log file keeps every "
      "complete row\n");
  end_process_now(kExitComponentExited);
}

}  // namespace

void install_crash_report() {
  std::atexit(on_exit_call);
  use_alternate_signal_stack();
  void* warm[1];
  (void)::backtrace(warm, 1);  // loads libgcc's unwinder now, not in the handler
  struct sigaction action {};
  action.sa_sigaction = on_fatal_signal;
  sigemptyset(&action.sa_mask);
  // SA_ONSTACK: on the alternate stack; a fault in the handler itself ends the process.
  action.sa_flags = SA_SIGINFO | SA_ONSTACK | SA_RESETHAND | SA_NODEFER;
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT})
    ::sigaction(sig, &action, nullptr);
}

}  // namespace s2sim::runner
