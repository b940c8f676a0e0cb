#pragma once
/// \file
/// `S2SIM_ASSERT(cond, message)`: an internal invariant of the kernel, one that no scene, plugin
/// or caller can break, only a bug of the kernel's own (a parallel array out of step, a handle
/// past its table).
///
/// A failed assertion throws `s2sim::Error` of kind `runtime` with the message
/// "internal error: <message> (<cond>) at <file>:<line>", in every build, instead of aborting:
/// - every front end already turns an Error into a message and an exit code (the runner exits
///   with 5, the viewer shows it, a test fails with the text), so a broken invariant is
///   reported like any other failure, with where it was caught, and is not lost with the
///   process;
/// - release builds are the ones users and the golden behaviour check run, so an assertion
///   compiled out there would hide exactly the bug it is for.
/// The cost is a compare and a branch; keep assertions out of per-substep and per-contact loops
/// (they belong where a table is built or a handle is resolved, not in the step's hot path).
/// In a `noexcept` function the throw ends the process (std::terminate): an abort with the
/// message, which is what an assertion there must do anyway.

#include <s2sim/error.hpp>

#include <string>
#include <string_view>

namespace s2sim::internal {

[[noreturn]] inline void assertion_failed(const char* condition, const char* message,
                                          std::string_view file, int line) {
  // A kernel source by its path in the tree, not the build machine's absolute path.
  if (const auto k = file.rfind("kernel/src/"); k != std::string_view::npos) file.remove_prefix(k);
  throw Error(ErrorKind::runtime, std::string("internal error: ") + message + " (" + condition +
                                      ") at " + std::string(file) + ":" + std::to_string(line));
}

}  // namespace s2sim::internal

#define S2SIM_ASSERT(cond, message)                                            \
  do {                                                                         \
    if (!(cond)) [[unlikely]]                                                  \
      ::s2sim::internal::assertion_failed(#cond, message, __FILE__, __LINE__); \
  } while (false)
