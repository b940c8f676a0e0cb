// s2sim-facade-step-bench: the C++ façade's cost per Simulation::step(1) call against one
// step(n) call, the reference for the Python bindings' overhead (bench/python_bench.py,
// docs/benchmarks.md "Python and remote overhead").
//   s2sim-facade-step-bench SCENE [TICKS]
#include <s2sim/kernel/simulation.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE [TICKS]\n", argv[0]);
    return 4;
  }
  const long ticks = argc > 2 ? std::atol(argv[2]) : 20000;
  try {
    auto sim = s2sim::Simulation::load(argv[1]);
    using Clock = std::chrono::steady_clock;
    double best_one = 1e9, best_many = 1e9;
    for (int repeat = 0; repeat < 5; ++repeat) {
      sim->reset();
      auto t0 = Clock::now();
      for (long i = 0; i < ticks; ++i)
        sim->step(1);
      auto t1 = Clock::now();
      sim->reset();
      auto t2 = Clock::now();
      sim->step(ticks);
      auto t3 = Clock::now();
      best_one = std::min(best_one, std::chrono::duration<double>(t1 - t0).count());
      best_many = std::min(best_many, std::chrono::duration<double>(t3 - t2).count());
    }
    std::printf(
        "{\"ticks\": %ld, \"us_per_step1_call\": %.4f, \"us_per_tick_in_one_call\": %.4f}\n", ticks,
        1e6 * best_one / static_cast<double>(ticks), 1e6 * best_many / static_cast<double>(ticks));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
