#pragma once
/// \file
/// What the viewer's tests share: running s2sim-view under xvfb-run (the `Viewer` fixture)
/// and s2sim-run, reading their output.

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>
#include "common/temp_dir.hpp"

namespace viewer_test {

namespace fs = std::filesystem;

const fs::path kViewer = fs::path(S2SIM_BIN_DIR) / "s2sim-view";
const fs::path kRunner = fs::path(S2SIM_BIN_DIR) / "s2sim-run";
const fs::path kSource = S2SIM_SOURCE_DIR;

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

inline Result run(const std::string& command, const fs::path& dir) {
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string full = command + " >" + quote(out.string()) + " 2>" + quote(err.string());
  const int raw = std::system(full.c_str());
  Result r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

/// Lines of `out` that start with `prefix`, without it.
inline std::vector<std::string> lines_with(const std::string& out, const std::string& prefix) {
  std::vector<std::string> found;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(prefix, 0) == 0) found.push_back(line.substr(prefix.size()));
  return found;
}

inline double number_after(const std::string& out, const std::string& prefix, std::size_t nth = 0) {
  const auto found = lines_with(out, prefix);
  return nth < found.size() ? std::stod(found[nth]) : NAN;
}

inline bool have_xvfb() {
  return std::system("command -v xvfb-run >/dev/null 2>&1") == 0;
}

/// The robot scene of the viewer's tests: scenes/nxt once it exists, the default scene until then.
inline fs::path robot_scene() {
  return fs::exists(kSource / "scenes/nxt/scene.xml") ? kSource / "scenes/nxt"
                                                      : kSource / "scenes/default";
}

class Viewer : public ::testing::Test {
 protected:
  void SetUp() override {
    // A SimTwo project's script listens on UDP 9808 (SimTwo's default), as does
    // scenes/cartpole_remote's link: a free port for the scripts, so parallel tests do not
    // collide there.
    const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t length = sizeof address;
    if (fd >= 0 && ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0 &&
        ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) == 0)
      ::setenv("S2SIM_UDP_PORT", std::to_string(ntohs(address.sin_port)).c_str(), 1);
    if (fd >= 0) ::close(fd);
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is missing: install xvfb to run the viewer tests";
    ASSERT_TRUE(fs::exists(kViewer)) << kViewer << " not built";
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info->name();
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    dir_ = s2sim::test::process_temp_dir() /
           ("s2sim_viewer_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!dir_.empty() && !HasFailure()) fs::remove_all(dir_);
  }

  /// s2sim-view under a virtual display of 1280x720. The viewer's exit status goes through a
  /// file: xvfb-run replaces it with its own when its clean-up races with another xvfb-run.
  Result view(const std::string& scene, const std::vector<std::string>& args) {
    const fs::path status = dir_ / "status.txt";
    fs::remove(status);
    std::string command = "xvfb-run -a -s '-screen 0 1280x720x24' sh -c '\"$0\" \"$@\"; echo $? >" +
                          status.string() + "' " + quote(kViewer.string()) + " " + quote(scene);
    for (const auto& a : args) {
      command += ' ';  // two appends: GCC 12 warns (-Wrestrict) on " " + std::string
      command += quote(a);
    }
    Result r = run(command, dir_);
    const std::string code = read_file(status);
    r.status = code.empty() ? -1 : std::stoi(code);
    return r;
  }

  fs::path dir_;
};

}  // namespace viewer_test
