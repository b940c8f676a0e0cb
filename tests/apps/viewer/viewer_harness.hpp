#pragma once
// Running the real s2sim-view under xvfb-run and reading its screenshots, for the viewer's
// screenshot tests (the same approach as viewer_test.cpp's helpers).

#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace s2sim::viewer_test {

namespace fs = std::filesystem;

inline const fs::path kViewer = fs::path(S2SIM_BIN_DIR) / "s2sim-view";
inline const fs::path kSource = S2SIM_SOURCE_DIR;
inline const fs::path kSharedScenes = S2SIM_SHARED_SCENES;

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct Result {
  int status = -1;
  std::string out;
  std::string err;
};

struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  const unsigned char* at(int x, int y) const {
    return &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
  }
};

inline Image read_png(const fs::path& file) {
  Image image;
  int channels = 0;
  unsigned char* data = stbi_load(file.string().c_str(), &image.width, &image.height, &channels, 3);
  if (data == nullptr) return image;
  image.rgb.assign(data, data + static_cast<std::size_t>(image.width) * image.height * 3);
  stbi_image_free(data);
  return image;
}

inline double luminance(const unsigned char* p) {
  return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
}

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
    dir_ = fs::path(::testing::TempDir()) /
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
