#pragma once
/// \file
/// What the tests of s2sim-run share: the real binary run in a folder of the test's own, its
/// exit code and output, and readers of the CSV log and the JSON summary it writes.

#include "common/edited_copy.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

// Boost 1.74's JSON parser still includes the deprecated boost/bind.hpp, which warns unless
// the old global placeholders are asked for explicitly.
#define BOOST_BIND_GLOBAL_PLACEHOLDERS
#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>
#include "common/temp_dir.hpp"

namespace s2sim::runner_test {

namespace fs = std::filesystem;
namespace pt = boost::property_tree;
using ::testing::AllOf;
using ::testing::AnyOf;
using ::testing::Contains;
using ::testing::Each;
using ::testing::ElementsAreArray;
using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

inline const fs::path kRunner = fs::path(S2SIM_BIN_DIR) / "s2sim-run";
inline const fs::path kShared = S2SIM_SHARED_SCENES;
inline const fs::path kFixtures = fs::path(S2SIM_SOURCE_DIR) / "tests/apps/runner/fixtures";

#define SKIP_WITHOUT_SHARED_SCENES() \
  if (!fs::is_directory(kShared))    \
  GTEST_SKIP() << kShared.string()   \
               << " is absent: the shared SimTwo scenes are needed for this test"

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_file(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

inline std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, sep))
    parts.push_back(part);
  return parts;
}

// The shell sees every argument verbatim: glob patterns such as robots/*/z must not expand.
inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct Result {
  int status = -1;  ///< exit code; 128 + signal when the runner crashed
  std::string out;
  std::string err;
};

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

inline Csv read_csv(const fs::path& p) {
  Csv csv;
  const auto lines = split(read_file(p), '\n');
  if (lines.empty()) return csv;
  csv.header = split(lines[0], ',');
  for (std::size_t i = 1; i < lines.size(); ++i)
    csv.rows.push_back(split(lines[i], ','));
  return csv;
}

inline std::size_t column(const Csv& csv, const std::string& name) {
  for (std::size_t i = 0; i < csv.header.size(); ++i)
    if (csv.header[i] == name) return i;
  ADD_FAILURE() << "no column '" << name << "'";
  return 0;
}

inline pt::ptree read_json(const fs::path& p) {
  pt::ptree tree;
  pt::read_json(p.string(), tree);  // throws (test error) on malformed JSON
  return tree;
}

inline std::vector<std::string> names(const pt::ptree& summary, const std::string& key) {
  std::vector<std::string> out;
  for (const auto& [k, item] : summary.get_child(key))
    out.push_back(item.get<std::string>("name"));
  return out;
}

// Every test gets its own folder: ctest runs tests of this binary in parallel.
class Runner : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(kRunner)) << kRunner << " not built";
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    dir_ = s2sim::test::process_temp_dir() /
           ("s2sim_runner_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  // A failing test leaves its outputs behind for a look.
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }

  /// Runs s2sim-run in dir_ (relative output paths land there).
  /// `shell` goes before the runner's name in the shell's command (e.g. "ulimit -v 90000; exec").
  Result run(const std::vector<std::string>& args, const std::string& shell = "") const {
    // Appended piece by piece: `"literal" + std::string&&` trips a false GCC 12 -Wrestrict.
    std::string cmd = "cd ";
    cmd += quote(dir_.string());
    cmd += " && ";
    cmd += shell;
    cmd += ' ';
    cmd += quote(kRunner.string());
    for (const auto& a : args) {
      cmd += ' ';
      cmd += quote(a);
    }
    cmd += " >stdout.txt 2>stderr.txt </dev/null";
    const int status = std::system(cmd.c_str());
    Result r;
    if (WIFEXITED(status)) r.status = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) r.status = 128 + WTERMSIG(status);
    r.out = read_file(dir_ / "stdout.txt");
    r.err = read_file(dir_ / "stderr.txt");
    return r;
  }

  static std::string scene(const std::string& name) { return (kShared / name).string(); }
  static std::string motor() { return scene("MotorModel_V3AGM"); }

  fs::path dir_;
};

}  // namespace s2sim::runner_test
