/// \file
/// s2sim-fuzz-scenes: the seeded mutation fuzzer CI runs (docs/reliability.md, "Fuzzing").
/// Each case copies a seed scene, mutates one of its XML files (xml_mutator.hpp), and loads and
/// runs it for a short simulated time in a child process, as the runner would. A located
/// refusal (exit 2, 3, 4) or a located divergence (exit 5) is a correct answer to hostile
/// input; a crash, a sanitizer report, an internal error (exit 1, anything but s2sim::Error)
/// or a hang is a finding: its mutated scene is kept for a regression test.
///
/// With `--threads N` (N ≥ 2) each case is run twice, on one thread and on N, every axis's
/// `ref_voltage` input driven at its own value (robots ahead): the two must end with the same
/// signals bit for bit, or fail with the same error (the parallel step, its parts'
/// components and running ahead are exact). A difference is a finding (exit 6).
///
///   s2sim-fuzz-scenes --corpus scenes --corpus ../shared/simtwo-scenes --cases 2000 --jobs 2
///   s2sim-fuzz-scenes --corpus tests/fuzz/seeds/parallel --corpus bench/peers/scenes
///                     --threads 2 --sim-time 0.3 --cases 500

#include "xml_mutator.hpp"

#include <s2sim/kernel/simulation.hpp>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/resource.h>
#include <sys/socket.h>
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
#include <iterator>
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
  fs::path work = fs::temp_directory_path() / ("s2sim-fuzz-" + std::to_string(::getpid()));
  fs::path findings = "fuzz-findings";
  std::vector<fs::path> plugin_path;
  int threads = 1;  // ≥ 2: each case also on that many threads, compared with one
};

[[noreturn]] void usage(const std::string& message) {
  std::cerr << "s2sim-fuzz-scenes: " << message
            << "\nusage: s2sim-fuzz-scenes --corpus DIR... [--cases N] [--seed S] [--jobs J]"
               " [--timeout-s T] [--sim-time S] [--work DIR] [--findings DIR]"
               " [--plugin-path DIR] [--threads N]\n";
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
      } else if (a == "--threads") {
        o.threads = std::stoi(value());
      } else {
        usage("unknown option " + a);
      }
    } catch (const std::logic_error&) {
      usage("bad value for " + a);
    }
  }
  if (o.corpus.empty()) usage("no --corpus scene");
  if (o.cases < 0 || o.jobs < 1 || !(o.timeout_s > 0) || !(o.sim_time_s >= 0) || o.threads < 1)
    usage("cases >= 0, jobs >= 1, timeout > 0, sim time >= 0 and threads >= 1");
  if (o.threads > static_cast<int>(std::max(1u, std::thread::hardware_concurrency())))
    usage("--threads " + std::to_string(o.threads) + " is more than this machine's " +
          std::to_string(std::thread::hardware_concurrency()) + " hardware threads");
  return o;
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Copies the seed's small files (textures and the like are not needed headless) and mutates
/// one of its XML files 1 to 3 times. Returns what was done.
std::string make_case(const fs::path& seed, const fs::path& dir, s2sim::fuzz::Rng& rng) {
  fs::remove_all(dir.parent_path());
  fs::create_directories(dir);
  // A seed may name files in its parent folder (bench/peers/scenes/robots_4: ../diffbot.xml):
  // they go beside the case's folder, unmutated, in a folder of the case's own (the cases
  // running at once must not write each other's).
  for (const auto& e : fs::directory_iterator(seed.parent_path()))
    if (e.is_regular_file() && e.path().extension() == ".xml" && e.file_size() <= (1u << 20))
      fs::copy_file(e.path(), dir.parent_path() / e.path().filename(),
                    fs::copy_options::overwrite_existing);
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

/// The exit code of a case whose run on several threads differs from its run on one.
constexpr int kParallelDiffers = 6;

/// One run of a case: the runner's exit code, its error, and every signal at its end.
struct Run {
  int code = 0;
  std::string error;
  std::vector<std::string> names;
  std::vector<double> signals;
};

/// A UDP port on loopback that is free now (0 if none can be had): the case's remote links
/// bind it, the same one in the run on one thread and in the run on several, whose `port`
/// signals must agree.
int free_udp_port() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return 0;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t size = sizeof address;
  int port = 0;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0 &&
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size) == 0)
    port = ntohs(address.sin_port);
  ::close(fd);
  return port;
}

/// Loads and runs the case on `threads` threads, as the runner would; with the differential
/// check, every `ref_voltage` input first driven at its own value (the same in every run).
Run run_on(const fs::path& dir, const Options& o, int threads, int remote_port) {
  Run run;
  try {
    s2sim::SimulationOptions so;
    so.plugin_path = o.plugin_path;
    so.threads = threads;
    // The shipped remote scenes name their port in a define, which a case sets to a free one
    // (the child caps the links' waits, see run_case).
    if (read(dir / "scene.xml").find("name='remote_port'") != std::string::npos)
      so.constants.emplace_back("remote_port", remote_port);
    auto sim = s2sim::Simulation::load(dir, so);
    if (o.threads > 1) {
      std::size_t k = 0;
      for (std::size_t i = 0; i < sim->input_count(); ++i) {
        const std::string& name = sim->input_info(i).name;
        // Each robot's wheels ahead (a left wheel turns the other way), at their own speeds.
        if (name.size() > 12 && name.compare(name.size() - 12, 12, "/ref_voltage") == 0)
          sim->set_input(i, (name.find("/left/") != std::string::npos ? -1.0 : 1.0) *
                                (4.0 + 0.37 * static_cast<double>(k++ % 13)));
      }
    }
    sim->run_until(o.sim_time_s);
    for (std::size_t i = 0; i < sim->signal_count(); ++i) {
      run.names.push_back(sim->signal_info(i).name);
      run.signals.push_back(sim->signal(i));
    }
  } catch (const s2sim::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    run.code = s2sim::exit_code(e.kind());
    run.error = e.what();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "internal error: %s\n", e.what());
    run.code = 1;
  } catch (...) {
    std::fprintf(stderr, "internal error: unknown exception\n");
    run.code = 1;
  }
  return run;
}

/// How the run on several threads differs from the one on one thread (empty: it does not).
std::string difference(const Run& serial, const Run& parallel) {
  if (serial.code != parallel.code || serial.error != parallel.error)
    return "exit " + std::to_string(parallel.code) + " (" + parallel.error + ") against exit " +
           std::to_string(serial.code) + " (" + serial.error + ") on one";
  if (serial.names != parallel.names) return "other signals than on one thread";
  for (std::size_t i = 0; i < serial.signals.size(); ++i) {
    const std::string& name = serial.names[i];
    if (std::memcmp(&serial.signals[i], &parallel.signals[i], sizeof(double)) != 0) {
      char values[80];  // every digit: they may differ in the last bit only
      std::snprintf(values, sizeof values, " is %.17g, %.17g on one thread", parallel.signals[i],
                    serial.signals[i]);
      return "signal " + name + values;
    }
  }
  return {};
}

/// The child: load and run as the runner does, exit with the runner's codes (and with
/// kParallelDiffers when the run on several threads differs).
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
  // A lock-step link waits for a client or a device that never comes here, as long as the
  // (mutated) scene asks: 10 ms a period at most, so a long wait is not taken for a hang.
  ::setenv("S2SIM_LINK_WAIT_MAX_S", "0.01", 1);
  const int remote_port = free_udp_port();
  Run serial = run_on(dir, o, 1, remote_port);
  int code = serial.code;
  if (o.threads > 1 && code != 1) {
    const Run parallel = run_on(dir, o, o.threads, remote_port);
    const std::string differs = difference(serial, parallel);
    if (!differs.empty()) {
      std::fprintf(stderr, "on %d threads: %s\n", o.threads, differs.c_str());
      code = kParallelDiffers;
    }
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
      fs::copy(r.dir.parent_path(), kept, fs::copy_options::recursive);
      std::ofstream(kept / "mutation.txt") << r.description << "\n" << outcome << "\n";
      findings.push_back(kept.string() + ": " + outcome + " (" + r.description + ")");
    }
    fs::remove_all(r.dir.parent_path());
  };

  while (next < o.cases || !running.empty()) {
    while (next < o.cases && static_cast<int>(running.size()) < o.jobs) {
      Running r;
      r.index = next++;
      const fs::path& seed = o.corpus[static_cast<std::size_t>(r.index) % o.corpus.size()];
      s2sim::fuzz::Rng rng(o.seed * 0x100000001B3ull + static_cast<std::uint64_t>(r.index));
      r.dir = o.work / ("case" + std::to_string(r.index)) / "scene";
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
                                               "diverged, located (exit 5)",
                                               "differs on several threads (exit 6)"};
          const bool known = code >= 0 && code <= kParallelDiffers;
          finish(r, known ? kNames[code] : "exit " + std::to_string(code),
                 !known || code == 1 || code == kParallelDiffers);
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
