// s2sim-peers: S2Sim side by side with MuJoCo, ODE and Bullet on the same scenes
// (docs/benchmarks-peers.md). Every engine steps each scene in turn, several rounds in a
// rotating order; the report gives medians of thread CPU time and wall time per 1 ms step, S2Sim's
// speed-up over each peer, and each engine's physical outcome, so that a faster wrong answer shows.
// The engine s2sim-par2 (two hardware threads or more) is S2Sim stepping its islands on two
// threads: its speed-up column is the serial run's wall time over its own. The engine s2sim-copies2
// is two serial copies of the scene stepped at once on two threads: its speed-up column, twice the
// serial run's wall time over its own, is what the machine gives two threads on the scene's
// work, the ceiling for s2sim-par2 in the same rounds; s2sim-par2-lockstep is s2sim-par2
// without running ahead (the parts wait for each other at every tick). The engine s2sim-simbody is
// S2Sim without the small-tree fast path (Simbody's realize chain): its speed-up column is
// what the fast path gains.
//   s2sim-peers [--scenes A,B,...] [--engines A,B,...] [--duration S] [--warmup S]
//               [--rounds N] [--csv FILE] [--markdown FILE] [--rounds-csv FILE] [--check]
#include "engine.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace peers {

namespace {
/// `relative` under bench/peers of the source tree, or else under the build's generated folder
/// (the large robots_N, bench/peers/CMakeLists.txt); the source tree's path if neither has it.
std::filesystem::path committed_or_generated(const std::filesystem::path& source_dir,
                                             const std::filesystem::path& relative) {
  const auto committed = source_dir / "bench/peers" / relative;
#ifdef S2SIM_PEERS_GENERATED_DIR
  const auto generated = std::filesystem::path(S2SIM_PEERS_GENERATED_DIR) / relative;
  if (!std::filesystem::exists(committed) && std::filesystem::exists(generated)) return generated;
#endif
  return committed;
}
}  // namespace

std::filesystem::path SceneSpec::s2sim_scene() const {
  switch (kind) {
    case Kind::robots:
      return committed_or_generated(source_dir, std::filesystem::path("scenes") / name);
    case Kind::pile:
      return source_dir / "scenes/pile";
    default:
      return source_dir / "bench/peers/scenes" / name;
  }
}
std::filesystem::path SceneSpec::mjcf() const {
  if (kind == Kind::robots)
    return committed_or_generated(source_dir, std::filesystem::path("mjcf") / (name + ".xml"));
  return source_dir / "bench/peers/mjcf" / (name + ".xml");
}
std::filesystem::path SceneSpec::ode_table() const {
  return source_dir / "bench/peers/scenes" / name / "model.txt";
}

std::vector<EngineFactory> available_engines() {
  std::vector<EngineFactory> engines{{"s2sim", &make_s2sim}};
  if (std::thread::hardware_concurrency() >= 2) {
    engines.push_back({"s2sim-par2", &make_s2sim_par2});
    engines.push_back({"s2sim-par2-lockstep", &make_s2sim_par2_lockstep});
    engines.push_back({"s2sim-copies2", &make_s2sim_copies2});
  }
  engines.push_back({"s2sim-simbody", &make_s2sim_simbody});
#ifdef S2SIM_PEERS_HAVE_MUJOCO
  engines.push_back({"mujoco", &make_mujoco});
#endif
#ifdef S2SIM_PEERS_HAVE_ODE
  engines.push_back({"ode-quick20", &make_ode_quickstep});
  engines.push_back({"ode-step", &make_ode_worldstep});
#endif
#ifdef S2SIM_PEERS_HAVE_BULLET
  engines.push_back({"bullet", &make_bullet});
#endif
#ifdef S2SIM_PEERS_HAVE_DART
  engines.push_back({"dart", &make_dart});
  engines.push_back({"dart-fcl", &make_dart_fcl});
#endif
  return engines;
}

}  // namespace peers

namespace {

using peers::SceneSpec;

struct Options {
  std::vector<std::string> scenes{"robots_1", "robots_4", "robots_16", "robots_64",
                                  "pile",     "humanoid", "arm_loop"};
  std::vector<std::string> engines;  // empty: every engine built
  double duration_s = 2.0;
  double warmup_s = 0.2;
  int rounds = 5;
  std::string csv, markdown;
  std::string rounds_csv;  // every round's times, not only their medians
  bool check = false;      // exit 5 unless every outcome is finite
};

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  std::istringstream in(list);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Each vCPU's time as the guest kernel counts it (/proc/stat, in USER_HZ ticks): `steal` is
/// what the hypervisor gave another guest while this vCPU had work. Empty where unreadable.
struct VcpuTimes {
  long long steal = 0, total = 0;
};
std::vector<VcpuTimes> read_vcpu_times() {
  std::vector<VcpuTimes> out;
  std::ifstream stat("/proc/stat");
  for (std::string line; std::getline(stat, line);) {
    // "cpuN user nice system idle iowait irq softirq steal guest guest_nice"; not the "cpu" sum.
    if (line.rfind("cpu", 0) != 0 || line.size() < 4 || line[3] < '0' || line[3] > '9') continue;
    std::istringstream fields(line.substr(line.find(' ')));
    VcpuTimes t;
    long long v = 0;
    for (int k = 0; k < 8 && (fields >> v); ++k) {
      t.total += v;  // guest time is counted in user already
      if (k == 7) t.steal = v;
    }
    out.push_back(t);
  }
  return out;
}

/// The largest share of a vCPU's time that the hypervisor took between two readings (0..1;
/// NaN without /proc/stat): a round where it is large ran on a host that was busy elsewhere.
double largest_steal_share(const std::vector<VcpuTimes>& before,
                           const std::vector<VcpuTimes>& after) {
  if (before.empty() || before.size() != after.size()) return NAN;
  double largest = 0;
  for (std::size_t c = 0; c < before.size(); ++c) {
    const long long total = after[c].total - before[c].total;
    if (total > 0)
      largest = std::max(largest, static_cast<double>(after[c].steal - before[c].steal) /
                                      static_cast<double>(total));
  }
  return largest;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Outcome {
  double distance_m = 0;             ///< mean horizontal displacement of the tracked bodies
  double lateral_m = 0;              ///< largest |Δy| (the robots drive along +x)
  double yaw_deg = 0;                ///< largest |Δyaw|
  double rise_m = 0;                 ///< mean change of height
  double penetration_m = 0;          ///< deepest over every step
  double settled_penetration_m = 0;  ///< deepest over the second half of the run
  bool finite = true;
};

struct Result {
  std::string scene, engine;
  int robots = 1;
  std::vector<double> cpu_us, wall_us;  // per step, one per round
  std::vector<double> steal_share;      // per round, largest_steal_share over the round
  Outcome outcome;
  std::string error;  // the engine could not load the scene
};

Outcome measure_outcome(peers::Engine& engine, long steps) {
  engine.reset();
  std::vector<peers::TrackedPose> start;
  for (int i = 0; i < engine.tracked_count(); ++i)
    start.push_back(engine.tracked(i));
  Outcome out;
  for (long s = 0; s < steps; ++s) {
    engine.step(1);
    const double depth = engine.deepest_penetration_m();
    out.penetration_m = std::max(out.penetration_m, depth);
    if (2 * s >= steps) out.settled_penetration_m = std::max(out.settled_penetration_m, depth);
  }
  const int n = engine.tracked_count();
  for (int i = 0; i < n; ++i) {
    const auto& a = start[static_cast<std::size_t>(i)];
    const auto b = engine.tracked(i);
    for (double v : b.position_m)
      out.finite = out.finite && std::isfinite(v);
    out.finite = out.finite && std::isfinite(b.yaw_rad);
    const double dx = b.position_m[0] - a.position_m[0], dy = b.position_m[1] - a.position_m[1];
    out.distance_m += std::hypot(dx, dy) / n;
    out.lateral_m = std::max(out.lateral_m, std::abs(dy));
    const double dyaw = std::remainder(b.yaw_rad - a.yaw_rad, 2 * M_PI);
    out.yaw_deg = std::max(out.yaw_deg, std::abs(dyaw) * 180 / M_PI);
    out.rise_m += (b.position_m[2] - a.position_m[2]) / n;
  }
  out.finite = out.finite && std::isfinite(out.penetration_m) && std::isfinite(out.distance_m);
  return out;
}

SceneSpec scene_spec(const std::string& name, const std::filesystem::path& source_dir) {
  SceneSpec s;
  s.name = name;
  s.source_dir = source_dir;
  if (name.rfind("robots_", 0) == 0) {
    s.kind = SceneSpec::Kind::robots;
    s.robot_count = std::atoi(name.c_str() + 7);
    if (s.robot_count <= 0) throw std::runtime_error("bad scene name '" + name + "'");
  } else if (name == "pile") {
    s.kind = SceneSpec::Kind::pile;
  } else if (name == "humanoid") {
    s.kind = SceneSpec::Kind::humanoid;
  } else if (name == "arm_loop") {
    s.kind = SceneSpec::Kind::arm_loop;
  } else {
    throw std::runtime_error("unknown scene '" + name + "' (robots_<N>, pile, humanoid, arm_loop)");
  }
  return s;
}

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

bool is_parallel(const Result& r) {
  return r.engine == "s2sim-par2" || r.engine == "s2sim-par2-lockstep" ||
         r.engine == "s2sim-copies2";
}

const Result* s2sim_of(const std::vector<Result>& results, const std::string& scene) {
  for (const auto& r : results)
    if (r.scene == scene && r.engine == "s2sim" && r.error.empty()) return &r;
  return nullptr;
}

/// S2Sim's speed-up over `r`: the peer's median CPU time per step over S2Sim's (> 1: S2Sim faster).
/// For s2sim-par2, the parallel run's over the serial one in WALL time (serial / parallel: > 1,
/// the threads pay); thread CPU time counts only the calling thread's share there.
double speedup(const std::vector<Result>& results, const Result& r) {
  const Result* s = s2sim_of(results, r.scene);
  if (s == nullptr || r.cpu_us.empty() || s->cpu_us.empty()) return NAN;
  // Two copies do twice the serial run's work: the throughput two threads give.
  const double work = r.engine == "s2sim-copies2" ? 2.0 : 1.0;
  if (is_parallel(r)) return work * median(s->wall_us) / median(r.wall_us);
  return median(r.cpu_us) / median(s->cpu_us);
}

void write_reports(const std::vector<Result>& results, const Options& o) {
  std::ostringstream md;
  md << "| scene | engine | CPU µs/step (median) | CPU min–max | wall µs/step | CPU µs per robot"
        " | S2Sim speed-up | distance m | lateral m | yaw ° | rise m | deepest mm | settled mm |\n"
     << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  std::ostringstream csv;
  csv << "scene,engine,rounds,cpu_us_median,cpu_us_min,cpu_us_max,wall_us_median,cpu_us_per_robot,"
         "s2sim_speedup,distance_m,lateral_m,yaw_deg,rise_m,penetration_mm,settled_penetration_mm,"
         "finite,largest_vcpu_steal_pct_median\n";
  for (const auto& r : results) {
    if (!r.error.empty()) {
      md << "| " << r.scene << " | " << r.engine << " | failed: " << r.error
         << " | | | | | | | | | | |\n";
      csv << r.scene << ',' << r.engine << ",0,,,,,,,,,,,,,0,\n";
      continue;
    }
    const double cpu = median(r.cpu_us), wall = median(r.wall_us);
    const auto [lo, hi] = std::minmax_element(r.cpu_us.begin(), r.cpu_us.end());
    const double up = speedup(results, r);
    const auto& oc = r.outcome;
    md << "| " << r.scene << " | " << r.engine << " | " << fixed(cpu, 1) << " | " << fixed(*lo, 1)
       << "–" << fixed(*hi, 1) << " | " << fixed(wall, 1) << " | " << fixed(cpu / r.robots, 2)
       << " | "
       << (r.engine == "s2sim" || std::isnan(up) ? std::string("")
                                                 : fixed(up, 2) + (is_parallel(r) ? "× wall" : "×"))
       << " | " << fixed(oc.distance_m, 4) << " | " << fixed(oc.lateral_m, 4) << " | "
       << fixed(oc.yaw_deg, 2) << " | " << fixed(oc.rise_m, 4) << " | "
       << fixed(oc.penetration_m * 1e3, 2) << " | " << fixed(oc.settled_penetration_m * 1e3, 2)
       << (oc.finite ? "" : " NON-FINITE") << " |\n";
    csv << r.scene << ',' << r.engine << ',' << r.cpu_us.size() << ',' << cpu << ',' << *lo << ','
        << *hi << ',' << wall << ',' << cpu / r.robots << ',' << (std::isnan(up) ? 1.0 : up) << ','
        << oc.distance_m << ',' << oc.lateral_m << ',' << oc.yaw_deg << ',' << oc.rise_m << ','
        << oc.penetration_m * 1e3 << ',' << oc.settled_penetration_m * 1e3 << ','
        << (oc.finite ? 1 : 0) << ',' << 100 * median(r.steal_share) << '\n';
  }
  // The parallel step against what the machine gave two threads on the same work, in the same
  // rounds: how much of the shortfall is S2Sim's and how much the host's.
  for (const auto& par : results) {
    if ((par.engine != "s2sim-par2" && par.engine != "s2sim-par2-lockstep") || !par.error.empty())
      continue;
    for (const auto& copies : results)
      if (copies.scene == par.scene && copies.engine == "s2sim-copies2" && copies.error.empty()) {
        const double up = speedup(results, par), ceiling = speedup(results, copies);
        if (std::isnan(up) || std::isnan(ceiling)) continue;
        md << "\n"
           << par.scene << ": " << par.engine << " " << fixed(up, 2)
           << "× the serial run, where two threads gave " << fixed(ceiling, 2)
           << "× on two copies (s2sim-copies2): " << fixed(up / ceiling, 2) << " of it";
        const double steal_par = median(par.steal_share), steal_copies = median(copies.steal_share);
        if (!std::isnan(steal_par) && !std::isnan(steal_copies))
          md << "; the hypervisor took up to " << fixed(100 * steal_par, 1) << " % and "
             << fixed(100 * steal_copies, 1) << " % of a vCPU (median rounds)";
        md << "\n";
      }
  }
  std::fputs(md.str().c_str(), stdout);
  if (!o.markdown.empty()) std::ofstream(o.markdown) << md.str();
  if (!o.csv.empty()) std::ofstream(o.csv) << csv.str();
  if (!o.rounds_csv.empty()) {
    std::ofstream raw(o.rounds_csv);
    raw << "scene,engine,round,cpu_us,wall_us,largest_vcpu_steal_pct\n";
    for (const auto& r : results)
      for (std::size_t i = 0; i < r.cpu_us.size(); ++i)
        raw << r.scene << ',' << r.engine << ',' << i << ',' << r.cpu_us[i] << ',' << r.wall_us[i]
            << ',' << 100 * r.steal_share[i] << '\n';
  }
}

/// The untimed steps before a round: `steps` (none: none), and more until kWarmupWall has
/// passed. A vCPU that idled runs the first milliseconds of a second thread's work at a
/// fraction of its speed on this machine's host (two threads at once against one: 1.0× over
/// 3 ms, 1.25× over 10 ms, 1.6–2.1× over 30 ms; bench/peers/results/history.md, "What the host
/// gives two threads"): the parallel engines would otherwise time the host waking up.
constexpr auto kWarmupWall = std::chrono::milliseconds(30);
void warm_up(peers::Engine& engine, long steps) {
  if (steps <= 0) return;
  const auto start = std::chrono::steady_clock::now();
  engine.step(steps);
  while (std::chrono::steady_clock::now() - start < kWarmupWall)
    engine.step(1);
}

int run(const Options& o) {
  std::vector<peers::EngineFactory> engines;
  for (const auto& e : peers::available_engines())
    if (o.engines.empty() ||
        std::find(o.engines.begin(), o.engines.end(), e.name) != o.engines.end())
      engines.push_back(e);
  std::printf("engines built: ");
  for (const auto& e : peers::available_engines())
    std::printf("%s ", e.name.c_str());
#ifndef S2SIM_PEERS_HAVE_MUJOCO
  std::printf("(MuJoCo skipped: libmujoco-dev not found at configure time) ");
#endif
#ifndef S2SIM_PEERS_HAVE_ODE
  std::printf("(ODE skipped: libode-dev not found at configure time) ");
#endif
#ifndef S2SIM_PEERS_HAVE_BULLET
  std::printf("(Bullet skipped: libbullet-dev not found at configure time) ");
#endif
#ifndef S2SIM_PEERS_HAVE_DART
  std::printf("(DART skipped: libdart-dev not found at configure time) ");
#endif
  std::printf("\n");

  const long steps = std::max(1L, std::lround(o.duration_s / 0.001));
  const long warmup = std::lround(o.warmup_s / 0.001);
  std::vector<Result> results;
  bool all_finite = true;
  for (const auto& scene_name : o.scenes) {
    const SceneSpec spec = scene_spec(scene_name, S2SIM_SOURCE_DIR);
    std::vector<std::unique_ptr<peers::Engine>> loaded;
    const std::size_t first = results.size();
    for (const auto& e : engines) {
      Result r;
      r.scene = scene_name;
      r.engine = e.name;
      r.robots = spec.kind == SceneSpec::Kind::robots ? spec.robot_count : 1;
      try {
        loaded.push_back(e.make(spec));
        r.outcome = measure_outcome(*loaded.back(), steps);
        all_finite = all_finite && r.outcome.finite;
      } catch (const std::exception& ex) {
        loaded.push_back(nullptr);
        r.error = ex.what();
        all_finite = false;
      }
      results.push_back(r);
    }
    for (int round = 0; round < o.rounds; ++round) {
      for (std::size_t k = 0; k < loaded.size(); ++k) {
        const std::size_t i = (k + static_cast<std::size_t>(round)) % loaded.size();
        if (!loaded[i]) continue;
        loaded[i]->reset();
        warm_up(*loaded[i], warmup);
        const auto vcpus0 = read_vcpu_times();
        const double cpu0 = thread_cpu_s();
        const auto wall0 = std::chrono::steady_clock::now();
        loaded[i]->step(steps);
        const auto wall1 = std::chrono::steady_clock::now();
        const double cpu1 = thread_cpu_s();
        Result& r = results[first + i];
        r.steal_share.push_back(largest_steal_share(vcpus0, read_vcpu_times()));
        r.cpu_us.push_back(1e6 * (cpu1 - cpu0) / static_cast<double>(steps));
        r.wall_us.push_back(1e6 * std::chrono::duration<double>(wall1 - wall0).count() /
                            static_cast<double>(steps));
      }
    }
    std::fprintf(stderr, "%s done\n", scene_name.c_str());
  }
  write_reports(results, o);
  if (o.check && !all_finite) {
    std::fprintf(stderr, "s2sim-peers: an engine failed or produced a non-finite outcome\n");
    return 5;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
        return argv[++i];
      };
      if (a == "--scenes")
        o.scenes = split(value());
      else if (a == "--engines")
        o.engines = split(value());
      else if (a == "--duration")
        o.duration_s = std::stod(value());
      else if (a == "--warmup")
        o.warmup_s = std::stod(value());
      else if (a == "--rounds")
        o.rounds = std::stoi(value());
      else if (a == "--csv")
        o.csv = value();
      else if (a == "--markdown")
        o.markdown = value();
      else if (a == "--rounds-csv")
        o.rounds_csv = value();
      else if (a == "--check")
        o.check = true;
      else
        throw std::invalid_argument("unknown option " + a);
    }
    if (o.duration_s <= 0 || o.warmup_s < 0 || o.rounds < 1)
      throw std::invalid_argument("--duration > 0, --warmup >= 0 and --rounds >= 1");
  } catch (const std::exception& e) {
    std::fprintf(stderr,
                 "s2sim-peers: %s\nusage: s2sim-peers [--scenes A,B] [--engines A,B] [--duration S]"
                 " [--warmup S] [--rounds N] [--csv FILE] [--markdown FILE] [--rounds-csv FILE]"
                 " [--check]\n",
                 e.what());
    return 4;
  }
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "s2sim-peers: %s\n", e.what());
    return 2;
  }
}
