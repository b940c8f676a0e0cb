#pragma once
/// \file
/// A seeded random stream of a component's own. The kernel keeps its 256-bit state inside the
/// simulation state, so resetting, copying or restoring a simulation reproduces the same
/// numbers, and one component drawing more numbers never shifts another's.

#include <s2sim/math.hpp>

#include <cmath>
#include <cstdint>

namespace s2sim {

/// xoshiro256** over four words owned by the kernel. Not thread-safe; never allocates.
class RandomStream {
 public:
  explicit RandomStream(std::uint64_t* state_words) : s_(state_words) {}

  /// Fills the state from a 64-bit seed with splitmix64 (the generator's authors' advice).
  static void seed(std::uint64_t* state_words, std::uint64_t seed) {
    for (int i = 0; i < 4; ++i) {
      seed += 0x9e3779b97f4a7c15ULL;
      std::uint64_t z = seed;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      state_words[i] = z ^ (z >> 31);
    }
  }

  /// Next 64 uniformly distributed bits.
  std::uint64_t next_u64() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }

  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

  /// Normal with the given mean and standard deviation (Box-Muller, one value per call so that
  /// no hidden cached value lives outside the kernel-owned state).
  double normal(double mean = 0.0, double stdev = 1.0) {
    double u1 = uniform();
    while (u1 <= 0.0)
      u1 = uniform();
    const double u2 = uniform();
    return mean + stdev * std::sqrt(-2.0 * std::log(u1)) * std::cos(2 * kPi * u2);
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t* s_;
};

}  // namespace s2sim
