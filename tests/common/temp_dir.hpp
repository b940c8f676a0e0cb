#pragma once
/// \file
/// The test process's own temporary folder: every folder a test makes goes under it, so that
/// two test processes (CTest runs two at a time) never share, remove or overwrite each other's.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <unistd.h>

namespace s2sim::test {

/// `<gtest's TempDir>/s2sim-<pid>`, created on first use and removed when the process that
/// made it exits (not by a forked child).
inline std::filesystem::path process_temp_dir() {
  struct Owned {
    Owned()
        : owner(::getpid()),
          dir(std::filesystem::path(::testing::TempDir()) / ("s2sim-" + std::to_string(owner))) {
      std::filesystem::create_directories(dir);
    }
    Owned(const Owned&) = delete;
    Owned& operator=(const Owned&) = delete;
    ~Owned() {
      std::error_code ignored;
      if (::getpid() == owner) std::filesystem::remove_all(dir, ignored);
    }
    pid_t owner;
    std::filesystem::path dir;
  };
  static const Owned owned;
  return owned.dir;
}

}  // namespace s2sim::test
