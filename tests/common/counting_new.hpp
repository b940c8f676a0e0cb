#pragma once
/// \file
/// Counts every operator new of the test binary that includes this header (in exactly one of
/// its translation units): the "no allocation in the step" tests compare the counts.

#include <atomic>
#include <cstdlib>
#include <new>

namespace s2sim::test {
inline std::atomic<long> allocations{0};
}

// The replacements below pair malloc with free; GCC cannot see that they replace each other.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

void* operator new(std::size_t n) {
  ++s2sim::test::allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
