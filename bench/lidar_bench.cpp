// s2sim-lidar-bench: what a 16 × 1 800 lidar3d scan costs (docs/benchmarks.md, "Ray casting";
// docs/models/sensors.md, lidar3d). Each scene is stepped with the lidar scanning on every
// tick and without it; the difference per tick is one scan (28 800 rays through
// StepContext::cast_ray, the range image and the point cloud written). Times are the thread's
// CPU time, best of several repeats, the scenes taking turns.
//   room:    a closed 6 m × 4 m × 3 m box room, every ray a hit (5 obstacles: fan culling);
//   base:    SimTwo's `base` (a differential robot, a belt, 5 things, 4 obstacles), the lidar
//            0.3 m up at the robot's start: the typical small scene (most rays up escape);
//   clutter: 200 obstacles and 20 free things over 20 m × 20 m (the static grid, no fan).
#include <s2sim/error.hpp>
#include <s2sim/kernel/simulation.hpp>

#include <time.h>
#include <algorithm>
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

double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("s2sim_lidar_bench_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// The benchmark's lidar: 16 channels from -15° to 15°, 1 800 steps over a full turn, 0.1 to
/// 100 m, scanning every `period` seconds, world-fixed at `pos`.
std::string lidar(const std::string& pos, double period) {
  return "<sensors>\n  <lidar3d>\n    <ID value='lidar'/>\n    <pos " + pos +
         "/>\n    <channels count='16' lowest='-15' highest='15'/>\n"
         "    <azimuth steps='1800' start='-180' stop='180'/>\n"
         "    <range min='0.1' max='100'/>\n    <period value='" +
         std::to_string(period) + "'/>\n  </lidar3d>\n</sensors>\n";
}

/// A copy of `scene` with the lidar added as a scene-level sensor file.
fs::path with_lidar(const fs::path& scene, const std::string& name, const std::string& pos,
                    double period) {
  const fs::path d = temp_dir(name + "_lidar");
  fs::copy(scene, d, fs::copy_options::recursive);
  std::ofstream(d / "bench_lidar.xml") << lidar(pos, period);
  std::ifstream in(d / "scene.xml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.rfind("</scene>"), 8, "  <sensors file='bench_lidar.xml'/>\n</scene>\n");
  std::ofstream(d / "scene.xml") << text;
  return d;
}

fs::path room() {
  const fs::path d = temp_dir("room");
  std::ofstream(d / "scene.xml") << "<scene>\n  <obstacles file='room.xml'/>\n</scene>\n";
  std::ofstream f(d / "room.xml");
  f << "<obstacles>\n";
  const char* walls[5][2] = {{"x='0.2' y='4.4' z='3.2'", "x='3.1' y='0' z='1.6'"},
                             {"x='0.2' y='4.4' z='3.2'", "x='-3.1' y='0' z='1.6'"},
                             {"x='6.4' y='0.2' z='3.2'", "x='0' y='2.1' z='1.6'"},
                             {"x='6.4' y='0.2' z='3.2'", "x='0' y='-2.1' z='1.6'"},
                             {"x='6.4' y='4.4' z='0.2'", "x='0' y='0' z='3.1'"}};
  for (int i = 0; i < 5; ++i)
    f << "  <cuboid><ID value='w" << i << "'/><size " << walls[i][0] << "/><pos " << walls[i][1]
      << "/></cuboid>\n";
  f << "</obstacles>\n";
  return d;
}

/// 200 random boxes, cylinders and spheres (static) and 20 free gravity-free things over
/// 20 m × 20 m, none within 1.5 m of the origin (where the lidar stands).
fs::path clutter() {
  const fs::path d = temp_dir("clutter");
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  const char* kinds[3] = {"cuboid", "cylinder", "sphere"};
  auto solid = [&](std::ofstream& f, int i, bool thing) {
    double x = 0, y = 0;
    while (std::hypot(x, y) < 1.5) {
      x = -10 + 20 * u(rng);
      y = -10 + 20 * u(rng);
    }
    f << "  <" << kinds[i % 3] << "><ID value='" << (thing ? "t" : "o") << i << "'/>"
      << "<size x='" << 0.1 + 0.4 * u(rng) << "' y='" << 0.1 + 0.4 * u(rng) << "' z='"
      << 0.2 + 1.5 * u(rng) << "'/><radius value='" << 0.05 + 0.2 * u(rng) << "'/><pos x='" << x
      << "' y='" << y << "' z='" << (thing ? 2.5 + 0.2 * i : 0.6) << "'/><rot_deg z='"
      << 360 * u(rng) << "'/>" << (thing ? "<mass value='1'/><nogravity/>" : "") << "</"
      << kinds[i % 3] << ">\n";
  };
  {
    std::ofstream f(d / "obstacles.xml");
    f << "<obstacles>\n";
    for (int i = 0; i < 200; ++i)
      solid(f, i, false);
    f << "</obstacles>\n";
  }
  {
    std::ofstream f(d / "things.xml");
    f << "<things>\n";
    for (int i = 0; i < 20; ++i)
      solid(f, i, true);
    f << "</things>\n";
  }
  std::ofstream(d / "scene.xml")
      << "<scene>\n  <obstacles file='obstacles.xml'/>\n  <things file='things.xml'/>\n</scene>\n";
  return d;
}

struct Case {
  std::string name;
  fs::path plain, scanning;  ///< without the lidar; with it scanning on every tick
  std::unique_ptr<s2sim::Simulation> a, b;
  double plain_us = std::numeric_limits<double>::infinity();
  double scanning_us = std::numeric_limits<double>::infinity();
  double hit_fraction = 0;
};

double us_per_step(s2sim::Simulation& sim, std::int64_t steps) {
  sim.reset();
  sim.step(2);
  const double start = cpu_now();
  sim.step(steps);
  return (cpu_now() - start) * 1e6 / static_cast<double>(steps);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const double duration = argc > 1 ? std::atof(argv[1]) : 1.0;  // scanning seconds per run
    const int repeats = duration < 0.1 ? 1 : 7;
    std::vector<Case> cases;
    auto add = [&](const std::string& name, const fs::path& scene, const std::string& pos) {
      Case c;
      c.name = name;
      c.plain = scene;
      auto probe = s2sim::Simulation::load(scene);
      c.scanning = with_lidar(scene, name, pos, probe->tick_s());
      cases.push_back(std::move(c));
    };
    add("room", room(), "x='0.7' y='-0.4' z='1.25'");
    const fs::path base = (fs::path(S2SIM_SOURCE_DIR) / ".." / "shared" / "simtwo-scenes" / "base")
                              .lexically_normal();
    if (fs::exists(base / "scene.xml"))
      add("base", base, "x='0' y='-1' z='0.3'");
    else
      std::printf("no %s: the base case is skipped\n", base.string().c_str());
    add("clutter", clutter(), "x='0' y='0' z='0.5'");
    for (Case& c : cases) {
      c.a = s2sim::Simulation::load(c.plain);
      c.b = s2sim::Simulation::load(c.scanning);
      for (const auto& w : c.b->warnings())
        std::printf("%s: warning: %s\n", c.name.c_str(), w.c_str());
    }
    for (int r = 0; r < repeats; ++r)
      for (Case& c : cases) {
        // About `duration` seconds of scanning per run (a scan takes a few milliseconds).
        const auto steps = std::max<std::int64_t>(2, std::llround(duration * 200));
        c.plain_us = std::min(c.plain_us, us_per_step(*c.a, steps));
        c.scanning_us = std::min(c.scanning_us, us_per_step(*c.b, steps));
      }
    std::printf(
        "lidar3d 16 x 1800 (28 800 rays, 0.1-100 m), one scan per tick against none, "
        "best of %d:\n",
        repeats);
    for (Case& c : cases) {
      c.b->reset();
      c.b->step(1);
      c.hit_fraction = c.b->signal("sensors/lidar/hits") / 28800.0;
      const double scan_us = c.scanning_us - c.plain_us;
      std::printf(
          "  %-8s %7.2f ms/scan  %6.0f scans/s  %5.1f ns/ray  (%3.0f %% hit; step "
          "%.1f us without; at 10 Hz %.1f %% of real time)\n",
          c.name.c_str(), scan_us / 1e3, 1e6 / scan_us, scan_us * 1e3 / 28800, 100 * c.hit_fraction,
          c.plain_us, scan_us * 10 / 1e6 * 100);
    }
  } catch (const s2sim::Error& e) {
    std::fprintf(stderr, "s2sim-lidar-bench: %s\n", e.what());
    return s2sim::exit_code(e.kind());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "s2sim-lidar-bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
