#pragma once
// Running the real s2sim-view under xvfb-run and reading its screenshots, for the viewer's
// screenshot tests, on viewer_test_support.hpp's helpers.

#include "viewer_png.hpp"
#include "viewer_test_support.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include "common/temp_dir.hpp"

namespace s2sim::viewer_test {

namespace fs = std::filesystem;

using ::viewer_test::Image;
using ::viewer_test::kSource;
using ::viewer_test::kViewer;
using ::viewer_test::luminance;
using ::viewer_test::quote;
using ::viewer_test::read_file;
using ::viewer_test::read_png;
using ::viewer_test::Result;
inline const fs::path kSharedScenes = S2SIM_SHARED_SCENES;

/// A test that runs s2sim-view in its own temporary folder (kept when the test fails).
class ViewerRun : public ::testing::Test {
 protected:
  void SetUp() override {
    if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0)
      GTEST_SKIP() << "xvfb-run is missing: install xvfb to run the viewer tests";
    ASSERT_TRUE(fs::exists(kViewer)) << kViewer << " not built";
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    dir_ = s2sim::test::process_temp_dir() /
           ("s2sim_viewer_render_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!dir_.empty() && !HasFailure()) fs::remove_all(dir_);
  }

  /// s2sim-view under a virtual display of 1280x720; the exit status goes through a file
  /// (xvfb-run replaces it with its own when its clean-up races with another xvfb-run).
  Result view(const std::string& scene, const std::vector<std::string>& args) {
    const fs::path status = dir_ / "status.txt", out = dir_ / "stdout.txt",
                   err = dir_ / "stderr.txt";
    fs::remove(status);
    std::string command = "xvfb-run -a -s '-screen 0 1280x720x24' sh -c '\"$0\" \"$@\"; echo $? >" +
                          status.string() + "' " + quote(kViewer.string()) + " " + quote(scene);
    for (const auto& a : args) {
      command += ' ';
      command += quote(a);
    }
    command += " >" + quote(out.string()) + " 2>" + quote(err.string());
    (void)std::system(command.c_str());
    Result r;
    r.out = read_file(out);
    r.err = read_file(err);
    const std::string code = read_file(status);
    r.status = code.empty() ? -1 : std::stoi(code);
    return r;
  }

  /// A screenshot of the 3-D view alone after `frames` frames, with extra arguments.
  Image screenshot(const std::string& scene, const std::string& name, std::vector<std::string> args,
                   int frames = 3) {
    const fs::path png = dir_ / (name + ".png");
    args.insert(args.end(),
                {"--screenshot", png.string(), "--frames", std::to_string(frames), "--hide-ui"});
    const Result r = view(scene, args);
    EXPECT_EQ(r.status, 0) << r.err;
    return read_png(png);
  }

  fs::path dir_;
};

}  // namespace s2sim::viewer_test
