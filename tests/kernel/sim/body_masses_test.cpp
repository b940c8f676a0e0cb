// Mass properties set while running (Simulation::set_body_mass; SimTwo's SetSolidMass): a
// pendulum whose mass is doubled keeps its period, one whose centre of mass moves nearer the
// hinge swings as √(L) says, on both dynamics; snapshots, resets and repeated runs bring the
// loaded masses back exactly; bad values are refused with the body named.
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace s2sim {
namespace {

namespace fs = std::filesystem;

const fs::path kScene = fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/pendulum_mass";
constexpr double kLength_m = 0.5;     // hinge to the bob's centre
constexpr double kAmplitude = 0.1;    // rad, let go at rest
constexpr double kRadius_m = 0.02;    // the bob, a uniform sphere
constexpr double kGravity = 9.80665;  // the kernel's

std::unique_ptr<Simulation> load(bool simbody_only = false, bool check = false) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  o.simbody_dynamics_only = simbody_only;
  o.check_dynamics = check;
  return Simulation::load(kScene, o);
}

int bob(const Simulation& sim) {
  const auto& bodies = sim.scene().bodies;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (bodies[b].id == "bob") return static_cast<int>(b + 1);
  return -1;
}

/// A physical pendulum's small-swing period with the first amplitude correction: mass m,
/// centre of mass at `length` from the hinge, inertia `central` about it.
double period_s(double mass_kg, double length_m, double central_kg_m2) {
  const double pivot_inertia = central_kg_m2 + mass_kg * length_m * length_m;
  return 2 * M_PI * std::sqrt(pivot_inertia / (mass_kg * kGravity * length_m)) *
         (1 + kAmplitude * kAmplitude / 16);
}

/// The mean period over `swings` full swings from now: the times the hinge's rate crosses zero
/// from below, interpolated within the tick.
double measured_period_s(Simulation& sim, int swings) {
  std::vector<double> crossings;
  double last = sim.axis_velocity(0), last_t = sim.time_s();
  while (static_cast<int>(crossings.size()) < swings + 1 && sim.time_s() < 30) {
    sim.step();
    const double now = sim.axis_velocity(0), t = sim.time_s();
    if (last < 0 && now >= 0) crossings.push_back(last_t + (t - last_t) * (-last) / (now - last));
    last = now;
    last_t = t;
  }
  if (crossings.size() < 2) return 0;
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

double sphere_inertia(double mass_kg) {
  return 0.4 * mass_kg * kRadius_m * kRadius_m;
}

class BodyMasses : public ::testing::TestWithParam<bool> {};  // Simbody's dynamics alone?

TEST_P(BodyMasses, APendulumWhoseMassIsDoubledKeepsItsPeriod) {
  auto sim = load(GetParam());
  const int b = bob(*sim);
  ASSERT_GT(b, 0);
  const double before = measured_period_s(*sim, 2);
  sim->set_body_mass(b, 2.0);  // SimTwo's rule: the inertia doubles with it
  const Simulation::MassProperties m = sim->body_mass(b);
  EXPECT_EQ(m.mass_kg, 2.0);
  EXPECT_NEAR(m.inertia_kg_m2.m[0][0], sphere_inertia(2.0), 1e-12);
  const double after = measured_period_s(*sim, 2);
  const double expected = period_s(1.0, kLength_m, sphere_inertia(1.0));
  EXPECT_NEAR(before, expected, 2e-3 * expected);
  EXPECT_NEAR(after, expected, 2e-3 * expected);
  EXPECT_NEAR(after, before, 1e-4 * before);
}

TEST_P(BodyMasses, APendulumWhoseLengthIsHalvedSwingsAsTheRootOfItsLengthSays) {
  auto sim = load(GetParam());
  const int b = bob(*sim);
  const double before = measured_period_s(*sim, 2);
  // The centre of mass halfway up to the hinge (body frame: the bob's axes are the world's).
  Simulation::MassProperties m = sim->body_mass(b);
  m.com_m = {-0.5 * kLength_m * std::sin(kAmplitude), 0, 0.5 * kLength_m * std::cos(kAmplitude)};
  sim->set_body_mass(b, m);
  const double after = measured_period_s(*sim, 3);
  const double short_period = period_s(1.0, kLength_m / 2, sphere_inertia(1.0));
  EXPECT_NEAR(after, short_period, 3e-3 * short_period);
  // Nearly a point mass: the ratio is nearly √(1/2).
  EXPECT_NEAR(after / before, std::sqrt(0.5), 4e-3);
}

INSTANTIATE_TEST_SUITE_P(Dynamics, BodyMasses, ::testing::Values(false, true),
                         [](const auto& p) { return p.param ? "simbody" : "tree"; });

TEST(BodyMasses, TheTreeAgreesWithSimbodyAfterAChange) {
  auto sim = load(false, true);  // the dynamics check compares the two every substep
  const int b = bob(*sim);
  sim->run_until(0.2);
  Simulation::MassProperties m = sim->body_mass(b);
  m.mass_kg = 3;
  m.com_m = {0.01, 0.02, 0.1};
  m.inertia_kg_m2 = {{{0.002, 0.0001, 0}, {0.0001, 0.003, 0}, {0, 0, 0.004}}};
  sim->set_body_mass(b, m);
  EXPECT_NO_THROW(sim->run_until(1.0));
  const Simulation::DynamicsCheck check = sim->dynamics_check();
  EXPECT_GT(check.compared, 800);
  EXPECT_LE(check.worst_relative, check.agreement);
}

std::vector<double> swing(Simulation& sim, double until_s) {
  std::vector<double> out;
  while (sim.time_s() < until_s - 1e-9) {
    sim.step();
    out.push_back(sim.axis_position(0));
    out.push_back(sim.axis_velocity(0));
  }
  return out;
}

TEST(BodyMasses, SnapshotsResetsAndTwoRunsBringTheMassesBackExactly) {
  auto run = [](Simulation& sim) {
    sim.run_until(0.3);
    Simulation::MassProperties m = sim.body_mass(bob(sim));
    m.com_m = {0, 0, 0.2};
    sim.set_body_mass(bob(sim), m);
    return swing(sim, 1.0);
  };
  auto sim = load();
  const std::vector<double> loaded = swing(*sim, 1.0);
  sim->reset();
  const std::vector<double> first = run(*sim);
  EXPECT_NE(first, std::vector<double>(loaded.begin() + 300, loaded.end()));
  // Two runs of one scene: the same numbers, bit for bit.
  auto other = load();
  EXPECT_EQ(run(*other), first);
  // A snapshot after the change holds it; one before does not.
  sim->reset();
  sim->run_until(0.3);
  const Simulation::Snapshot before = sim->save();
  const std::vector<double> unchanged = swing(*sim, 1.0);
  sim->restore(before);
  Simulation::MassProperties m = sim->body_mass(bob(*sim));
  m.com_m = {0, 0, 0.2};
  sim->set_body_mass(bob(*sim), m);
  const Simulation::Snapshot after = sim->save();
  EXPECT_EQ(swing(*sim, 1.0), first);
  sim->restore(before);
  EXPECT_EQ(sim->body_mass(bob(*sim)).com_m.z, 0.0);
  EXPECT_EQ(swing(*sim, 1.0), unchanged);
  sim->restore(after);
  EXPECT_EQ(sim->body_mass(bob(*sim)).com_m.z, 0.2);
  EXPECT_EQ(swing(*sim, 1.0), first);
  // A reset: the scene's masses.
  sim->reset();
  EXPECT_EQ(sim->body_mass(bob(*sim)).com_m.z, 0.0);
  EXPECT_EQ(sim->body_mass(bob(*sim)).mass_kg, 1.0);
  EXPECT_EQ(swing(*sim, 1.0), loaded);
}

// SimTwo's damping scales the velocity by (1 - stokes) each step whatever the mass, so the
// terminal speed (1 - s)·g·h/s does not change when the mass does: the drag follows the mass.
TEST(BodyMasses, SimTwosDampingFollowsAMassSetWhileRunning) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  const fs::path scene = fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/falling_drag";
  auto changed = Simulation::load(scene, o), kept = Simulation::load(scene, o);
  const int ball = 1;
  const double stokes = 0.01, h = 0.001;
  const double terminal = (1 - stokes) * kGravity * h / stokes;
  changed->run_until(1.0);
  EXPECT_NEAR(-changed->body_twist(ball).linear_m_s.z, terminal, 0.03 * terminal);
  changed->set_body_mass(ball, 2.0);
  changed->run_until(2.0);
  kept->run_until(2.0);
  const double speed = -kept->body_twist(ball).linear_m_s.z;
  EXPECT_NEAR(-changed->body_twist(ball).linear_m_s.z, speed, 1e-9 * speed);
}

TEST(BodyMasses, BadMassesAreRefusedNamingTheBody) {
  auto sim = load();
  const int b = bob(*sim);
  auto message = [&](auto&& call) {
    try {
      call();
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::usage);
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([&] { sim->set_body_mass(b, -1.0); }).find("'bob'"), std::string::npos);
  EXPECT_NE(message([&] { sim->set_body_mass(b, NAN); }).find("mass must be positive"),
            std::string::npos);
  EXPECT_NE(message([&] { sim->set_body_mass(0, 1.0); }).find("no body 0"), std::string::npos);
  Simulation::MassProperties m = sim->body_mass(b);
  m.inertia_kg_m2 = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 3}}};
  EXPECT_NE(message([&] { sim->set_body_mass(b, m); }).find("A + B >= C"), std::string::npos);
  m = sim->body_mass(b);
  m.com_m.x = INFINITY;
  EXPECT_NE(message([&] { sim->set_body_mass(b, m); }).find("centre of mass"), std::string::npos);
  // Nothing refused changed anything.
  EXPECT_EQ(sim->body_mass(b).mass_kg, 1.0);
  EXPECT_EQ(sim->body_mass(b).com_m.x, 0.0);
}

}  // namespace
}  // namespace s2sim
