// The propeller plugin: thrust k_T w|w| along its axis and reaction torque k_Q w|w| at five
// spin rates, measured by what they do to a weightless sphere (1 kg, I = 2/5 m r^2).
#include "fixture.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace s2sim {
namespace {

TEST(Propeller, ThrustAndReactionTorqueFollowTheLawAtFiveSpinRates) {
  const double kt = 2e-5, kq = 3e-7, m = 1, inertia = 0.4 * 1 * 0.1 * 0.1, t = 0.1;
  for (double w : {-600.0, -150.0, 100.0, 400.0, 900.0}) {
    auto sim = fluids_test::load("spin_sphere");
    sim->set_input("robots/probe/actuators/prop/spin", w);
    sim->run_until(t);
    const double thrust = kt * w * std::abs(w), torque = kq * w * std::abs(w);
    // The sphere's own acceleration says what force and torque it felt; the velocities read
    // are the leapfrog's, half a tick behind the time (docs/models/multibody.md).
    const double t_v = t - 0.5 * sim->tick_s();
    const double felt_thrust = m * sim->signal("robots/probe/solids/core/vz") / t_v;
    const double felt_torque = -inertia * sim->signal("robots/probe/solids/core/wz") / t_v;
    std::printf("  w = %6.1f rad/s: thrust %.6f N (law %.6f), torque %.4g N*m (law %.4g)\n", w,
                felt_thrust, thrust, felt_torque, torque);
    EXPECT_NEAR(felt_thrust, thrust, 1e-6 * std::abs(thrust));
    EXPECT_NEAR(felt_torque, torque, 1e-6 * std::abs(torque));
    EXPECT_NEAR(sim->signal("robots/probe/actuators/prop/thrust"), thrust, 1e-12);
    EXPECT_NEAR(sim->signal("robots/probe/actuators/prop/torque"), torque, 1e-12);
  }
}

}  // namespace
}  // namespace s2sim
