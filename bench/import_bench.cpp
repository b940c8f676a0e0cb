// s2sim-import-bench: load time and step time of a robot file in S2Sim and in MuJoCo 2.2
// loading the same file (docs/benchmarks.md, "Robot files"). Wall times, best of `repeats`;
// both at 1 ms, MuJoCo with its defaults (Euler, contacts on).
//
//   s2sim-import-bench [FILE] [--seconds S] [--repeats N]
//   (FILE: default bench/models/chain30/chain30.urdf)

#include <s2sim/kernel/simulation.hpp>

#include <mujoco/mujoco.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  fs::path file = fs::path(S2SIM_SOURCE_DIR) / "bench/models/chain30/chain30.urdf";
  double seconds = 5;
  int repeats = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--seconds" && i + 1 < argc) {
      seconds = std::atof(argv[++i]);
    } else if (a == "--repeats" && i + 1 < argc) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else {
      file = a;
    }
  }
  const auto steps = static_cast<long>(seconds / 1e-3 + 0.5);
  double s2_load = 1e300, s2_step = 1e300, mj_load = 1e300, mj_step_s = 1e300;
  std::size_t bodies = 0, contacts = 0;
  int mj_contacts = 0;
  try {
    for (int r = 0; r < repeats; ++r) {
      s2sim::SimulationOptions o;
      o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
      double t0 = now_s();
      auto sim = s2sim::Simulation::load(file, o);
      s2_load = std::min(s2_load, now_s() - t0);
      t0 = now_s();
      sim->step(steps);
      s2_step = std::min(s2_step, (now_s() - t0) / static_cast<double>(steps));
      bodies = sim->scene().bodies.size();
      contacts = sim->contact_count();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "s2sim-import-bench: %s\n", e.what());
    return 2;
  }
  for (int r = 0; r < repeats; ++r) {
    char error[1000] = "";
    double t0 = now_s();
    mjModel* m = mj_loadXML(file.string().c_str(), nullptr, error, sizeof error);
    if (!m) {
      std::fprintf(stderr, "s2sim-import-bench: MuJoCo: %s\n", error);
      return 2;
    }
    mjData* d = mj_makeData(m);
    mj_load = std::min(mj_load, now_s() - t0);
    m->opt.timestep = 1e-3;
    t0 = now_s();
    for (long k = 0; k < steps; ++k)
      mj_step(m, d);
    mj_step_s = std::min(mj_step_s, (now_s() - t0) / static_cast<double>(steps));
    mj_contacts = d->ncon;
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  std::printf("file %s, %ld steps of 1 ms, best of %d\n", file.filename().c_str(), steps, repeats);
  std::printf("  s2sim : load %8.2f ms, step %8.2f us (%zu bodies, %zu contacts at the end)\n",
              1e3 * s2_load, 1e6 * s2_step, bodies, contacts);
  std::printf("  mujoco: load %8.2f ms, step %8.2f us (%d contacts at the end)\n", 1e3 * mj_load,
              1e6 * mj_step_s, mj_contacts);
  return 0;
}
