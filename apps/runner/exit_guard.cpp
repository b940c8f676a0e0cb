// _exit() and _Exit() from inside a call into a component, named as exit() is
// (crash_report.hpp). The runner exports these two symbols (exit_symbols.list), so a plugin's
// call binds to them before the C library's; the runner's own quick ends go through
// runner::end_process_now, which no component can be running on.
#include "crash_report.hpp"
#include "outputs.hpp"

#include <s2sim/kernel/simulation.hpp>

#include <sys/syscall.h>
#include <unistd.h>

#include <cstring>

namespace s2sim::runner {

[[noreturn]] void end_process_now(int code) noexcept {
  for (;;)
    ::syscall(SYS_exit_group, code);
}

namespace {

[[noreturn]] void exited_from_component(int code) noexcept {
  if (const char* component = running_component()) {
    auto say = [](const char* text) { (void)!::write(2, text, std::strlen(text)); };
    say("s2sim-run: ");
    say(component);
    say(" called _exit() during its call: the run is stopped there; the --log file keeps every "
        "complete row\n");
    end_process_now(kExitComponentExited);
  }
  end_process_now(code);
}

}  // namespace
}  // namespace s2sim::runner

extern "C" [[noreturn]] void _exit(int status) {
  s2sim::runner::exited_from_component(status);
}

extern "C" [[noreturn]] void _Exit(int status) {
  s2sim::runner::exited_from_component(status);
}
