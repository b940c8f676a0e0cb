// The ziggurat normal generator of the sensors plugin: moments, tails, determinism.
#include "common.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace s2sim::sensors {
namespace {

TEST(ZigguratNormal, HasTheMomentsAndTailsOfAStandardNormal) {
  std::uint64_t state[4];
  RandomStream::seed(state, 2024);
  RandomStream r(state);
  const ZigguratTables& t = ziggurat_tables();
  constexpr int n = 2000000;
  double s1 = 0, s2 = 0, s4 = 0;
  int beyond1 = 0, beyond3 = 0, beyond4 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = ziggurat_normal(r, t);
    s1 += x;
    s2 += x * x;
    s4 += x * x * x * x;
    beyond1 += std::abs(x) > 1;
    beyond3 += std::abs(x) > 3;
    beyond4 += std::abs(x) > 4;
  }
  const double mean = s1 / n, var = s2 / n - mean * mean;
  EXPECT_NEAR(mean, 0, 5 / std::sqrt(double(n)));
  EXPECT_NEAR(var, 1, 0.005);
  EXPECT_NEAR(s4 / n, 3, 0.03);  // kurtosis of a normal
  // P(|x| > 1) = 0.31731, P(|x| > 3) = 0.0026998, P(|x| > 4) = 6.334e-5 (the tail algorithm).
  EXPECT_NEAR(double(beyond1) / n, 0.31731, 0.002);
  EXPECT_NEAR(double(beyond3) / n, 0.0026998, 0.0002);
  EXPECT_NEAR(double(beyond4) / n, 6.334e-5, 2.5e-5);
}

TEST(ZigguratNormal, SameSeedSameNumbers) {
  std::uint64_t a[4], b[4];
  RandomStream::seed(a, 7);
  RandomStream::seed(b, 7);
  RandomStream ra(a), rb(b);
  for (int i = 0; i < 1000; ++i)
    ASSERT_EQ(ziggurat_normal(ra, ziggurat_tables()), ziggurat_normal(rb, ziggurat_tables()));
}

}  // namespace
}  // namespace s2sim::sensors
