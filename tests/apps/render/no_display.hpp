#pragma once
/// \file
/// Every test of the including binary runs as on a machine without a display server, whatever
/// ctest's environment: the headless renderer must not need one.

#include <gtest/gtest.h>

#include <cstdlib>

namespace s2sim::test {

class NoDisplay : public ::testing::Environment {
 public:
  void SetUp() override {
    ::unsetenv("DISPLAY");
    ::unsetenv("WAYLAND_DISPLAY");
  }
};

// One per binary (an inline variable): registered before main() runs the tests.
inline ::testing::Environment* const kNoDisplay =
    ::testing::AddGlobalTestEnvironment(new NoDisplay);

}  // namespace s2sim::test
