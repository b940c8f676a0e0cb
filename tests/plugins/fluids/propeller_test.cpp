// The propeller plugin: thrust k_T w|w| along its axis and reaction torque k_Q w|w| at five
// spin rates, measured by what they do to a weightless sphere (1 kg, I = 2/5 m r^2).
#include "fixture.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

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

TEST(Propeller, MotorDrivenPropellerSpinsWhereTheMotorMeetsItsDragTorque) {
  // Steady state at V: K (V - K w) / R = k_Q w^2, so k_Q w^2 + (K^2/R) w - K V / R = 0.
  const double K = 0.02, R = 0.2, kq = 2.5e-7, kt = 1.6e-5, V = 8;
  const double b = K * K / R, c = K * V / R;
  const double w = (-b + std::sqrt(b * b + 4 * kq * c)) / (2 * kq);
  const std::string p = "robots/stand/actuators/prop/";
  {
    auto sim = fluids_test::load("motor_prop");
    sim->set_input("robots/stand/axes/motor/ref_voltage", V);
    sim->run_until(1.0);
    const double spin = sim->signal(p + "spin_rate");
    std::printf("  8 V: %.3f rad/s, analytic %.3f; thrust %.4f N (k_T w^2 %.4f)\n", spin, w,
                sim->signal(p + "thrust"), kt * w * w);
    EXPECT_NEAR(spin, w, 1e-3 * w);
    EXPECT_NEAR(sim->signal(p + "thrust"), kt * spin * spin, 1e-12);
  }
  {  // A 1 A current limit: the torque K i_max holds the drag torque at a lower spin.
    auto sim = fluids_test::load("motor_prop", {{"imax", 1}});
    sim->set_input("robots/stand/axes/motor/ref_voltage", V);
    sim->run_until(1.0);
    const double limited = std::sqrt(K * 1 / kq);
    std::printf("  1 A limit: %.3f rad/s, analytic %.3f\n", sim->signal(p + "spin_rate"), limited);
    EXPECT_NEAR(sim->signal(p + "spin_rate"), limited, 1e-3 * limited);
  }
}

}  // namespace
}  // namespace s2sim
