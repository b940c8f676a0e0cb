// The drive train's numerics alone (plugins/drive_train/drive_train_math.hpp).
#include "drive_train_math.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace s2sim::drive_train {
namespace {

TEST(DriveTrainMath, CurrentUpdateIsTheExactExponentialAtAnyStep) {
  const double R = 7.6, L = 4.88e-3, U = 9;
  for (double dt : {1e-5, 1e-4, 1e-3, 1e-2, 0.1, 1.0}) {
    double i = 0, t = 0;
    for (int k = 0; k < 50; ++k) {
      const CurrentStep s = advance_current(i, U, 0, R, L, 1e9, false, dt);
      // Mean over the step = (1/dt) ∫ U/R (1 − e^{−tR/L}) dt, from the step's start.
      const double exact_mean =
          U / R - U / R * L / (R * dt) * (std::exp(-t * R / L) - std::exp(-(t + dt) * R / L));
      i = s.end;
      t += dt;
      const double exact = U / R * (1 - std::exp(-t * R / L));
      EXPECT_NEAR(i, exact, 1e-12 * U / R) << "dt " << dt << " step " << k;
      EXPECT_NEAR(s.mean, exact_mean, 1e-12 * U / R) << "dt " << dt << " step " << k;
      EXPECT_LE(i, U / R * (1 + 1e-15));  // never overshoots: stable and monotonic
    }
  }
}

TEST(DriveTrainMath, CurrentCasesAndLimit) {
  EXPECT_DOUBLE_EQ(advance_current(0, 9, 1, 2, 0, 100, false, 1e-3).end, 4.0);      // algebraic
  EXPECT_DOUBLE_EQ(advance_current(0, 9, 1, 0, 0.5, 100, false, 1e-3).end, 0.016);  // R = 0
  EXPECT_DOUBLE_EQ(advance_current(0, 9, 1, 0, 0.5, 100, false, 1e-3).mean, 0.008);
  EXPECT_DOUBLE_EQ(advance_current(0, -9, 1, 0, 0, 3, false, 1e-3).end, -3.0);   // R = L = 0
  EXPECT_DOUBLE_EQ(advance_current(0, 9, 5, 2, 0.1, 100, true, 1e-3).end, 4.5);  // simple
  const CurrentStep s = advance_current(0, 9, 0, 1, 0, 0.5, false, 1e-3);
  EXPECT_EQ(s.end, 0.5);
  EXPECT_EQ(s.mean, 0.5);
  EXPECT_EQ(advance_current(0, -9, 0, 1, 1e-3, 0.5, false, 1.0).end, -0.5);
}

TEST(DriveTrainMath, WrapPiIsInMinusPiPi) {
  EXPECT_DOUBLE_EQ(wrap_pi(1.5 * kPi), -0.5 * kPi);
  EXPECT_DOUBLE_EQ(wrap_pi(-1.5 * kPi), 0.5 * kPi);
  EXPECT_DOUBLE_EQ(wrap_pi(kPi), kPi);
  EXPECT_DOUBLE_EQ(wrap_pi(-kPi), kPi);
  EXPECT_NEAR(wrap_pi(10 * kPi + 0.25), 0.25, 1e-12);
}

TEST(DriveTrainMath, TextbookPidIsDiscreteAtTheControllerPeriodWithoutWindUp) {
  const PidGains g{2, 10, 0.1, 0.5, 9};
  PidState s;
  const double T = 0.01;
  // First tick: no derivative kick; integral Ki·e·T.
  EXPECT_DOUBLE_EQ(pid_textbook(s, g, 1, 2, T), 2 * 1 + 10 * 1 * T + 0 + 0.5 * 2);
  EXPECT_DOUBLE_EQ(pid_textbook(s, g, 0.5, 2, T),
                   2 * 0.5 + 10 * 1.5 * T + 0.1 * (0.5 - 1) / T + 0.5 * 2);
  // Saturated in the error's direction: the integral holds.
  PidState w;
  for (int k = 0; k < 1000; ++k)
    EXPECT_EQ(pid_textbook(w, g, 100, 0, T), 9.0);
  EXPECT_DOUBLE_EQ(w.integral, 0.0);
  // The error changes sign: the output leaves saturation at once.
  EXPECT_LT(pid_textbook(w, g, -0.5, 0, T), 0.0);
}

TEST(DriveTrainMath, SimTwoPidUsesThePhysicsStep) {
  const PidGains g{2, 10, 0.1, 0.5, 9};
  PidState s;
  const double dt = 0.001;
  EXPECT_DOUBLE_EQ(pid_simtwo(s, g, 1, 2, dt), 2 + 10 * 1 * dt + 0.1 * 1 / dt > 9 ? 9 : 0);
  EXPECT_DOUBLE_EQ(s.integral, 0.0);  // undone: |u| >= saturation
}

}  // namespace
}  // namespace s2sim::drive_train
