// s2sim-ray-bench: the cost of ray casting (docs/benchmarks.md). Times are the thread's CPU
// time, best of several repeats.
//  1. rays per second on a generated cluttered scene (obstacles and free things), through
//     Simulation::cast_ray, the path every sensor takes (broad phase + exact tests);
//  2. the cost of a 768-ray, 270° ranger2d swept at 10 ms (SimTwo's default sensors.xml ranger,
//     horizontal, 4 m) added to the differential robot scene (`base` of SimTwo's scenes), as a
//     fraction of that scene's step time; the instantaneous mode too.
#include <s2sim/error.hpp>
#include <s2sim/kernel/simulation.hpp>
#include <s2sim/math.hpp>

#include <time.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
/// This thread's CPU time: the machine is shared (2 cores, parallel builds), and CPU time is
/// far less disturbed by other processes than wall time.
struct Clock {
  using time_point = double;
  static double now() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }
};

double seconds_since(double t) {
  return Clock::now() - t;
}

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("s2sim_ray_bench_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// A 21.6 m x 21.6 m area cluttered with `obstacles` static primitives and `things` free,
/// gravity-free bodies (so they stay put while the scene steps). The area is cut into 1.2 m
/// cells: each thing has a cell of its own, the obstacles share the others (overlapping one
/// another, which static geometry may), and nothing reaches out of its cell, so that no thing
/// starts in contact (with a contact engine, interpenetration at load would blow up).
fs::path cluttered_scene(int obstacles, int things) {
  const fs::path d = temp_dir("clutter");
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  constexpr int kCells = 18;
  constexpr double kCell = 1.2, kOrigin = -kCells * kCell / 2;
  std::vector<int> cells(kCells * kCells);
  for (std::size_t i = 0; i < cells.size(); ++i)
    cells[i] = static_cast<int>(i);
  std::shuffle(cells.begin(), cells.end(), rng);
  const int thing_cells = std::min(things, kCells * kCells / 2);
  const char* kinds[3] = {"cuboid", "cylinder", "sphere"};
  auto solid = [&](std::ofstream& f, int i, bool thing, int cell) {
    const char* k = kinds[i % 3];
    const double cx = kOrigin + (cell % kCells + 0.5) * kCell;
    const double cy = kOrigin + (cell / kCells + 0.5) * kCell;
    // Bounding radius at most 0.5 m: boxes and cylinders up to 0.45 m, radii up to 0.22 m.
    f << "  <" << k << ">\n    <ID value='" << (thing ? "t" : "o") << i << "'/>\n";
    f << "    <size x='" << 0.1 + 0.35 * u(rng) << "' y='" << 0.1 + 0.35 * u(rng) << "' z='"
      << 0.1 + 0.35 * u(rng) << "'/>\n";
    f << "    <radius value='" << 0.05 + 0.17 * u(rng) << "'/>\n";
    f << "    <pos x='" << cx << "' y='" << cy << "' z='" << 0.55 << "'/>\n";
    f << "    <rot_deg x='" << 30 * u(rng) << "' y='" << 30 * u(rng) << "' z='" << 360 * u(rng)
      << "'/>\n";
    if (thing) f << "    <mass value='1'/>\n    <nogravity/>\n";
    f << "  </" << k << ">\n";
  };
  {
    std::ofstream f(d / "obstacles.xml");
    f << "<obstacles>\n";
    for (int i = 0; i < obstacles; ++i)
      solid(f, i, false,
            cells[static_cast<std::size_t>(thing_cells + i % (kCells * kCells - thing_cells))]);
    f << "</obstacles>\n";
  }
  {
    std::ofstream f(d / "things.xml");
    f << "<things>\n";
    for (int i = 0; i < thing_cells; ++i)
      solid(f, i, true, cells[static_cast<std::size_t>(i)]);
    f << "</things>\n";
  }
  std::ofstream(d / "scene.xml")
      << "<scene>\n  <obstacles file='obstacles.xml'/>\n  <things file='things.xml'/>\n</scene>\n";
  return d;
}

void rays_per_second(int obstacles, int things, int ticks) {
  auto sim = s2sim::Simulation::load(cluttered_scene(obstacles, things));
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(0, 1);
  const int kTicks = ticks;
  constexpr int kRaysPerTick = 5000;
  std::vector<s2sim::Vec3> o(kRaysPerTick), d(kRaysPerTick);
  for (int i = 0; i < kRaysPerTick; ++i) {
    o[static_cast<std::size_t>(i)] = {-10.8 + 21.6 * u(rng), -10.8 + 21.6 * u(rng),
                                      0.1 + 0.9 * u(rng)};
    const double a = 2 * s2sim::kPi * u(rng);
    d[static_cast<std::size_t>(i)] = {std::cos(a), std::sin(a), -0.1 * u(rng)};
  }
  double best = std::numeric_limits<double>::infinity();
  long hits = 0;
  for (int repeat = 0; repeat < 3; ++repeat) {
    double cast_s = 0;
    hits = 0;
    for (int t = 0; t < kTicks; ++t) {
      sim->step(1);  // the moving boxes are recomputed on the first ray of each tick
      const auto start = Clock::now();
      for (int i = 0; i < kRaysPerTick; ++i)
        hits +=
            sim->cast_ray(o[static_cast<std::size_t>(i)], d[static_cast<std::size_t>(i)], 5.0).hit;
      cast_s += seconds_since(start);
    }
    best = std::min(best, cast_s);
  }
  const double rays = static_cast<double>(kTicks) * kRaysPerTick;
  std::printf(
      "cluttered scene: %d obstacles, %d things, 5 m rays: %.2f Mrays/s (%.0f ns/ray, "
      "%.0f %% hit)\n",
      obstacles, things, rays / best / 1e6, best / rays * 1e9, 100.0 * hits / rays);
}

/// Microseconds per step of each scene, best of `repeats` runs of `duration` simulated
/// seconds. The scenes take turns, so that a busy moment of the machine hits them alike.
std::vector<double> us_per_step(const std::vector<fs::path>& scenes, double duration, int repeats) {
  std::vector<std::unique_ptr<s2sim::Simulation>> sims;
  for (const auto& scene : scenes)
    sims.push_back(s2sim::Simulation::load(scene));
  std::vector<double> best(scenes.size(), std::numeric_limits<double>::infinity());
  for (int r = 0; r < repeats; ++r)
    for (std::size_t k = 0; k < sims.size(); ++k) {
      auto& sim = *sims[k];
      const auto steps = std::llround(duration / sim.tick_s());
      sim.reset();
      sim.step(50);
      const auto start = Clock::now();
      sim.step(steps);
      best[k] = std::min(best[k], seconds_since(start) * 1e6 / static_cast<double>(steps));
    }
  return best;
}

/// A copy of `base` with a world-fixed ranger at the robot's start, 0.2 m up.
fs::path base_with_ranger(const fs::path& base, const std::string& mode, bool noise = true) {
  const fs::path d = temp_dir("base_" + mode + (noise ? "" : "_quiet"));
  fs::copy(base, d, fs::copy_options::recursive);
  std::ofstream(d / "bench_ranger.xml")
      << "<sensors>\n  <ranger2d>\n    <ID value='lidar'/>\n    <pos x='0' y='-1' z='0.2'/>\n"
         "    <beam length='4' angle='270' rays='768'/>\n    <period value='0.01'/>\n"
      << (noise ? "    <noise stdev='0.002'/>\n" : "") << "    <scan mode='" << mode
      << "'/>\n  </ranger2d>\n</sensors>\n";
  std::ifstream in(d / "scene.xml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.rfind("</scene>"), 8, "  <sensors file='bench_ranger.xml'/>\n</scene>\n");
  std::ofstream(d / "scene.xml") << text;
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const fs::path shared =
        (fs::path(S2SIM_SOURCE_DIR) / ".." / "shared" / "simtwo-scenes").lexically_normal();
    const double duration = argc > 1 ? std::atof(argv[1]) : 1.0;
    // A short duration (the smoke test) shortens the ray counts too.
    const int ticks = std::clamp(static_cast<int>(200 * duration), 2, 200);
    rays_per_second(100, 20, ticks);
    rays_per_second(1000, 100, ticks);
    const fs::path base = shared / "base";
    if (!fs::exists(base / "scene.xml")) {
      std::printf("no %s: ranger cost not measured\n", base.string().c_str());
      return 0;
    }
    {
      // The rays alone: the ranger's 768 directions from its mount, through the façade.
      auto sim = s2sim::Simulation::load(base);
      sim->step(1);
      const double a = 270 * s2sim::kPi / 180;
      std::vector<s2sim::Vec3> dirs;
      for (int i = 0; i < 768; ++i) {
        const double phi = -a / 2 + a * i / 767;
        dirs.push_back({std::cos(phi), std::sin(phi), 0});
      }
      double best = std::numeric_limits<double>::infinity();
      for (int r = 0; r < 20; ++r) {
        const auto start = Clock::now();
        for (int k = 0; k < 100; ++k)
          for (const auto& dir : dirs)
            sim->cast_ray({0, -1, 0.2}, dir, 4.0);
        best = std::min(best, seconds_since(start));
      }
      std::printf("base: the ranger's rays alone: %.0f ns/ray\n", best / 76800 * 1e9);
    }
    const auto t =
        us_per_step({base, base_with_ranger(base, "sweep"), base_with_ranger(base, "instant"),
                     base_with_ranger(base, "sweep", false)},
                    duration, 15);
    const double plain = t[0];
    std::printf("base (differential robot): %.2f us/step\n", plain);
    const char* what[] = {"", "swept over 10 ms", "all rays every 10 ms", "swept, without noise"};
    for (int k = 1; k < 4; ++k)
      std::printf("  + 768-ray ranger, %s: %.2f us/step, +%.1f %%\n", what[k], t[k],
                  100 * (t[k] - plain) / plain);
  } catch (const s2sim::Error& e) {
    std::fprintf(stderr, "s2sim-ray-bench: %s\n", e.what());
    return s2sim::exit_code(e.kind());
  }
  return 0;
}
