/// \file
/// s2sim-fuzz-scenes: the seeded mutation fuzzer CI runs (docs/reliability.md, "Fuzzing").
/// Each case copies a seed scene, mutates one of its XML files (xml_mutator.hpp), and loads and
/// runs it for a short simulated time in a child process, as the runner would. A located
/// refusal (exit 2, 3, 4) or a located divergence (exit 5) is a correct answer to hostile
/// input; a crash, a sanitizer report, an internal error (exit 1, anything but s2sim::Error)
/// or a hang is a finding: its mutated scene is kept for a regression test.
///
///   s2sim-fuzz-scenes --corpus scenes --corpus ../shared/simtwo-scenes --cases 2000 --jobs 2

#include "xml_mutator.hpp"

#include <s2sim/kernel/simulation.hpp>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

struct Options {
  std::vector<fs::path> corpus;  // scene folders
  long cases = 200;
  std::uint64_t seed = 1;
  int jobs = 2;
  double timeout_s = 10;
  double sim_time_s = 0.05;
  fs::path work = fs::temp_directory_path() / "s2sim-fuzz";
  fs::path findings = "fuzz-findings";
  std::vector<fs::path> plugin_path;
};

[[noreturn]] void usage(const std::string& message) {
  std::cerr << "s2sim-fuzz-scenes: " << message
            << "\nusage: s2sim-fuzz-scenes --corpus DIR... [--cases N] [--seed S] [--jobs J]"
               " [--timeout-s T] [--sim-time S] [--work DIR] [--findings DIR]"
               " [--plugin-path DIR]\n";
  std::exit(4);
}

/// A corpus entry is a scene folder, or a folder of scene folders.
void add_corpus(const fs::path& dir, std::vector<fs::path>& out) {
  if (fs::exists(dir / "scene.xml")) {
    out.push_back(dir);
    return;
  }
  if (!fs::is_directory(dir)) usage("corpus '" + dir.string() + "' is not a folder");
  std::vector<fs::path> found;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_directory() && fs::exists(e.path() / "scene.xml")) found.push_back(e.path());
  std::sort(found.begin(), found.end());  // the order, hence every case, is reproducible
  out.insert(out.end(), found.begin(), found.end());
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(a + " needs a value");
      return argv[++i];
    };
    try {
      if (a == "--corpus") {
        add_corpus(value(), o.corpus);
      } else if (a == "--cases") {
        o.cases = std::stol(value());
      } else if (a == "--seed") {
        o.seed = std::stoull(value());
      } else if (a == "--jobs") {
        o.jobs = std::stoi(value());
      } else if (a == "--timeout-s") {
        o.timeout_s = std::stod(value());
      } else if (a == "--sim-time") {
        o.sim_time_s = std::stod(value());
      } else if (a == "--work") {
        o.work = value();
      } else if (a == "--findings") {
        o.findings = value();
      } else if (a == "--plugin-path") {
        o.plugin_path.push_back(value());
      } else {
        usage("unknown option " + a);
      }
    } catch (const std::logic_error&) {
      usage("bad value for " + a);
    }
  }
  if (o.corpus.empty()) usage("no --corpus scene");
  if (o.cases < 0 || o.jobs < 1 || !(o.timeout_s > 0) || !(o.sim_time_s >= 0))
    usage("cases >= 0, jobs >= 1, timeout > 0 and sim time >= 0");
  return o;
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Copies the seed's small files (textures and the like are not needed headless) and mutates
/// one of its XML files 1 to 3 times. Returns what was done.
std::string make_case(const fs::path& seed, const fs::path& dir, s2sim::fuzz::Rng& rng) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::vector<fs::path> xml_files;
  for (const auto& e : fs::directory_iterator(seed)) {
    if (!e.is_regular_file() || e.file_size() > (1u << 20)) continue;
    fs::copy_file(e.path(), dir / e.path().filename());
    if (e.path().extension() == ".xml") xml_files.push_back(e.path().filename());
  }
  std::sort(xml_files.begin(), xml_files.end());
  const fs::path file = xml_files[rng.below(xml_files.size())];
  std::string text = read(dir / file), log = file.string() + ":";
  const std::size_t count = 1 + rng.below(3);
  for (std::size_t k = 0; k < count; ++k) {
    s2sim::fuzz::Mutation m = s2sim::fuzz::mutate(text, rng);
    text = std::move(m.text);
    log += " " + m.description + ";";
  }
  std::ofstream(dir / file, std::ios::binary | std::ios::trunc) << text;
  return log;
}

/// The child: load and run as the runner does, exit with the runner's codes.
[[noreturn]] void run_case(const fs::path& dir, const Options& o) {
  const int out = ::open((dir / "output.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (out >= 0) {
    ::dup2(out, 1);
    ::dup2(out, 2);
  }
#if !defined(__SANITIZE_ADDRESS__)
  // Runaway memory is a finding (bad_alloc, exit 1), not the machine's death. ASan reserves
  // terabytes of address space, so the bound is left to it there.
  const rlim_t limit = rlim_t{4} << 30;
  const rlimit as{limit, limit};
  ::setrlimit(RLIMIT_AS, &as);
#endif
  int code = 0;
  try {
    s2sim::SimulationOptions so;
    so.plugin_path = o.plugin_path;
    auto sim = s2sim::Simulation::load(dir, so);
    sim->run_until(o.sim_time_s);
  } catch (const s2sim::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    code = s2sim::exit_code(e.kind());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "internal error: %s\n", e.what());
    code = 1;
  } catch (...) {
    std::fprintf(stderr, "internal error: unknown exception\n");
    code = 1;
  }
  std::fflush(nullptr);
  ::_exit(code);
}

struct Running {
  pid_t pid = 0;
  long index = 0;
  fs::path dir;
  std::string description;
  Clock::time_point start;
};

std::string seed_name(const fs::path& seed) {
  return seed.filename().string();
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  fs::create_directories(o.work);
  std::map<std::string, long> outcomes;
  std::vector<std::string> findings;
  std::vector<Running> running;
  const auto t0 = Clock::now();
  long next = 0;

  auto finish = [&](const Running& r, const std::string& outcome, bool finding) {
    ++outcomes[outcome];
    if (finding) {
      const fs::path kept =
          o.findings / (seed_name(o.corpus[static_cast<std::size_t>(r.index) % o.corpus.size()]) +
                        "-case" + std::to_string(r.index));
      fs::create_directories(o.findings);
      fs::remove_all(kept);
      fs::copy(r.dir, kept, fs::copy_options::recursive);
      std::ofstream(kept / "mutation.txt") << r.description << "\n" << outcome << "\n";
      findings.push_back(kept.string() + ": " + outcome + " (" + r.description + ")");
    }
    fs::remove_all(r.dir);
  };

  while (next < o.cases || !running.empty()) {
    while (next < o.cases && static_cast<int>(running.size()) < o.jobs) {
      Running r;
      r.index = next++;
      const fs::path& seed = o.corpus[static_cast<std::size_t>(r.index) % o.corpus.size()];
      s2sim::fuzz::Rng rng(o.seed * 0x100000001B3ull + static_cast<std::uint64_t>(r.index));
      r.dir = o.work / ("case" + std::to_string(r.index));
      r.description = seed_name(seed) + "/" + make_case(seed, r.dir, rng);
      std::fflush(nullptr);
      r.start = Clock::now();
      r.pid = ::fork();
      if (r.pid < 0) {
        std::perror("fork");
        return 1;
      }
      if (r.pid == 0) run_case(r.dir, o);
      running.push_back(std::move(r));
    }
    bool reaped = false;
    for (std::size_t k = 0; k < running.size();) {
      Running& r = running[k];
      int status = 0;
      const pid_t done = ::waitpid(r.pid, &status, WNOHANG);
      const double elapsed = std::chrono::duration<double>(Clock::now() - r.start).count();
      if (done == 0 && elapsed > o.timeout_s) {
        ::kill(r.pid, SIGKILL);
        ::waitpid(r.pid, &status, 0);
        finish(r, "hang (> " + std::to_string(o.timeout_s) + " s)", true);
      } else if (done == r.pid) {
        if (WIFSIGNALED(status)) {
          finish(r, std::string("crash (signal ") + ::strsignal(WTERMSIG(status)) + ")", true);
        } else {
          const int code = WEXITSTATUS(status);
          static const char* const kNames[] = {"ran",
                                               "internal error (exit 1)",
                                               "refused: scene (exit 2)",
                                               "refused: plugin (exit 3)",
                                               "refused: usage (exit 4)",
                                               "diverged, located (exit 5)"};
          const bool known = code >= 0 && code <= 5;
          finish(r, known ? kNames[code] : "exit " + std::to_string(code), !known || code == 1);
        }
      } else {
        ++k;
        continue;
      }
      running.erase(running.begin() + static_cast<std::ptrdiff_t>(k));
      reaped = true;
    }
    if (!reaped) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }

  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  std::printf("s2sim-fuzz-scenes: %ld cases from %zu seed scenes in %.1f s (seed %llu)\n", o.cases,
              o.corpus.size(), wall, static_cast<unsigned long long>(o.seed));
  for (const auto& [outcome, n] : outcomes)
    std::printf("  %6ld  %s\n", n, outcome.c_str());
  for (const auto& f : findings)
    std::printf("FINDING %s\n", f.c_str());
  std::printf("%zu findings\n", findings.size());
  return findings.empty() ? 0 : 1;
}
