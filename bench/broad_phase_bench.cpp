// s2sim-broadphase-bench: cost of the contact broad phase (a uniform grid kept in a sorted
// array, collision/broad_phase.hpp) as objects are added, to check that it stays near N log N.
// Boxes of 0.1 m scattered over a floor whose area grows with N (constant density, as objects added
// to a world), each moving a little per step; the time per call is divided by N·log2(N).
#include "collision/broad_phase.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

int main() {
  using s2sim::Vec3;
  using s2sim::collision::Aabb;
  std::printf("%8s %12s %12s %16s\n", "objects", "pairs", "us/call", "ns/(N log2 N)");
  for (int n : {100, 300, 1000, 3000, 10000, 30000}) {
    std::mt19937 rng(1);
    const double side = std::sqrt(n * 0.05);  // 20 objects per square metre
    std::uniform_real_distribution<double> where(0, side), jitter(-0.002, 0.002);
    std::vector<Vec3> centres(n);
    for (auto& c : centres)
      c = {where(rng), where(rng), 0.05};
    std::vector<Aabb> boxes(n);
    s2sim::collision::BroadPhase bp;
    bp.resize(n);
    std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
    const int calls = 200;
    double best = 1e300;
    for (int repeat = 0; repeat < 3; ++repeat) {
      const auto start = std::chrono::steady_clock::now();
      for (int k = 0; k < calls; ++k) {
        for (int i = 0; i < n; ++i) {
          centres[i] += Vec3{jitter(rng), jitter(rng), 0};
          boxes[i] = {centres[i] - Vec3{0.05, 0.05, 0.05}, centres[i] + Vec3{0.05, 0.05, 0.05}};
        }
        bp.find_pairs(boxes.data(), pairs);
      }
      const double us =
          std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
              .count() /
          calls;
      best = std::min(best, us);
    }
    std::printf("%8d %12zu %12.1f %16.2f\n", n, pairs.size(), best,
                best * 1e3 / (n * std::log2(static_cast<double>(n))));
  }
  return 0;
}
