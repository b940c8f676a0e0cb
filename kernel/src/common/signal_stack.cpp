// The calling thread's alternate signal stack (signal_stack.hpp).
#include "common/signal_stack.hpp"

#include <signal.h>

#include <memory>
#include <new>

namespace s2sim::common {

namespace {
// Room for the handler's own calls (dladdr, backtrace, write): the default SIGSTKSZ is too
// small for the dynamic loader's lookups.
constexpr std::size_t kAlternateStackBytes = 256 * 1024;

struct AlternateStack {
  std::unique_ptr<char[]> memory;
  ~AlternateStack() {
    if (!memory) return;
    stack_t off{};
    off.ss_flags = SS_DISABLE;
    ::sigaltstack(&off, nullptr);
  }
};
}  // namespace

void use_alternate_signal_stack() noexcept {
  thread_local AlternateStack stack;
  if (stack.memory) return;
  stack.memory.reset(new (std::nothrow) char[kAlternateStackBytes]);
  if (!stack.memory) return;
  stack_t on{};
  on.ss_sp = stack.memory.get();
  on.ss_size = kAlternateStackBytes;
  if (::sigaltstack(&on, nullptr) != 0) stack.memory.reset();
}

}  // namespace s2sim::common
