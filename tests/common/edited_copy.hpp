#pragma once
/// \file
/// A scene folder copied to the test's temporary folder with one file's text replaced: error
/// cases and variants of a fixture or of a reference scene.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>

#include <unistd.h>
#include "common/temp_dir.hpp"

namespace s2sim::test {

/// Copies `source` (a scene folder) and replaces the first `from` in `file` with `to`; the
/// copy's name is derived from all four and the process, so distinct edits never share a
/// folder, nor do two tests making the same edit at once (CTest runs each test as its own
/// process, two at a time: one removed the folder the other was reading).
inline std::filesystem::path edited_copy(const std::filesystem::path& source,
                                         const std::string& file, const std::string& from,
                                         const std::string& to) {
  namespace fs = std::filesystem;
  const fs::path dir =
      s2sim::test::process_temp_dir() /
      ("s2sim_" + std::to_string(std::hash<std::string>{}(source.string() + file + from + to)) +
       "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::copy(source, dir, fs::copy_options::recursive);
  std::ifstream in(dir / file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from << " not in " << file;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  std::ofstream(dir / file) << text;
  return dir;
}

}  // namespace s2sim::test
