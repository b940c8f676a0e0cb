// Acceptance of the drive train (docs/models/dc-motor.md) on scenes/motor_bench: the Lego NXT motor
// of the SimTwo paper (Table 2) driving a 1e-3 kg·m² flywheel. Each test prints what it measured;
// docs/models/dc-motor.md quotes these numbers.
#include "bench_util.hpp"

#include <gmock/gmock.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include "common/temp_dir.hpp"

namespace s2sim::test {
namespace {

using ::testing::HasSubstr;

/// (3.11) with Table 2: w = (Ua − Ra·Tc/Ks) / (Ks + Ra·B/Ks).
double eq_3_11(double u) {
  return (u - kRa * kTc / kKs) / (kKs + kRa * kB / kKs);
}

/// Mean of a signal over `seconds` of further simulation.
double mean_over(Simulation& sim, std::size_t signal, double seconds) {
  const auto n = static_cast<int>(std::llround(seconds / sim.tick_s()));
  double sum = 0;
  for (int k = 0; k < n; ++k) {
    sim.step();
    sum += sim.signal(signal);
  }
  return sum / n;
}

TEST(DcMotor, FreeRunningSpeedFollowsEq311From1To9Volts) {
  auto sim = load_bench();
  const auto speed = sim->signal_index(axis("speed"));
  double worst = 0;
  for (int u = 1; u <= 9; ++u) {
    sim->reset();
    sim->set_input(axis("ref_voltage"), u);
    sim->run_until(1.0);  // 33 mechanical time constants
    const double w = mean_over(*sim, speed, 0.2);
    const double paper = 1.9211 * u - 0.0106;
    const double rel = (w - paper) / paper;
    worst = std::max(worst, std::abs(rel));
    std::printf("  Ua = %d V: w = %.5f rad/s, (3.11) 1.9211*Ua - 0.0106 = %.5f (%+.4f %%)\n", u, w,
                paper, 100 * rel);
    EXPECT_NEAR(w, paper, 0.01 * paper) << "Ua = " << u << " V";
    EXPECT_NEAR(w, eq_3_11(u), 1e-4 * eq_3_11(u)) << "Ua = " << u << " V, exact (3.11)";
  }
  RecordProperty("worst_relative_error", std::to_string(worst));
}

TEST(DcMotor, OpenCircuitBackEmfIsKsTimesSpeedAndFitsKsBack) {
  // Open circuit: no current can flow (imax = 0); the flywheel is spun through ref_torque at
  // Table 1's speeds and the back-EMF is read.
  auto sim = load_bench({{"imax", 0}});
  const auto speed = sim->signal_index(axis("speed"));
  const auto emf = sim->signal_index(axis("back_emf"));
  const auto current = sim->signal_index(axis("current"));
  const auto torque = sim->input_index(axis("ref_torque"));
  double sum_ew = 0, sum_ww = 0;
  for (double target : {6.91, 12.04, 16.23, 20.42, 24.39, 27.75}) {
    for (int k = 0; k < 600; ++k) {  // a P loop on the torque: friction + 0.05 (target − w)
      const double w = sim->signal(speed);
      sim->set_input(torque, kTc + kB * target + 0.05 * (target - w));
      sim->step();
      EXPECT_EQ(sim->signal(current), 0.0);
    }
    const double w = sim->signal(speed), e = sim->signal(emf);
    std::printf("  w = %.3f rad/s: e = %.4f V, e/w = %.6f\n", w, e, e / w);
    EXPECT_NEAR(w, target, 0.01 * target);
    EXPECT_NEAR(e, kKs * w, 0.01 * kKs * w);
    sum_ew += e * w;
    sum_ww += w * w;
  }
  const double ks = sum_ew / sum_ww;
  std::printf("  Ks fitted through the origin: %.6f V*s/rad (paper 0.4908)\n", ks);
  EXPECT_NEAR(ks, 0.4908, 0.005 * 0.4908);
  RecordProperty("ks_fit", std::to_string(ks));
}

TEST(DcMotor, BelowBreakAwayVoltageTheJointStaysStillAboveItTurns) {
  const double vc = kRa * kTc / kKs;  // 5.51 mV
  auto sim = load_bench();
  const auto speed = sim->signal_index(axis("speed"));
  const auto pos = sim->signal_index(axis("pos"));
  sim->set_input(axis("ref_voltage"), 0.95 * vc);
  double max_w = 0;
  while (sim->time_s() < 10.0) {
    sim->step();
    max_w = std::max(max_w, std::abs(sim->signal(speed)));
  }
  std::printf("  0.95 Vc = %.4g V for 10 s: max |w| = %.3g rad/s, pos = %.3g rad\n", 0.95 * vc,
              max_w, sim->signal(pos));
  EXPECT_LT(max_w, 1e-3);
  EXPECT_LT(std::abs(sim->signal(pos)), 1e-9) << "creep";

  sim->reset();
  sim->set_input(axis("ref_voltage"), 2 * vc);
  sim->run_until(10.0);
  const double w = sim->signal(speed);
  std::printf("  2 Vc = %.4g V: w = %.4g rad/s, (3.11) %.4g, pos after 10 s = %.4g rad\n", 2 * vc,
              w, eq_3_11(2 * vc), sim->signal(pos));
  EXPECT_NEAR(w, eq_3_11(2 * vc), 0.01 * eq_3_11(2 * vc));
  EXPECT_GT(sim->signal(pos), 0.09);
}

TEST(DcMotor, StallCurrentStepFollowsTheExponentialAtAnyStep) {
  // Stalled by a Coulomb brake far above the stall torque (0.58 N·m).
  const double u = 9;
  for (double dt : {1e-3, 1e-4, 5e-3, 2e-2}) {
    auto sim = load_bench({{"fc", 100}}, dt);
    const auto current = sim->signal_index(axis("current"));
    sim->set_input(axis("ref_voltage"), u);
    double worst = 0;
    while (sim->time_s() < 0.02 - 1e-12) {
      sim->step();
      const double t = sim->time_s();
      const double exact = u / kRa * (1 - std::exp(-t * kRa / kLa));
      const double i = sim->signal(current);
      worst = std::max(worst, std::abs(i - exact) / exact);
      ASSERT_LE(i, u / kRa * (1 + 1e-12)) << "dt " << dt << " t " << t;
      EXPECT_EQ(sim->signal(axis("speed")), 0.0);
    }
    std::printf("  dt = %g s: worst |i - U/Ra (1 - exp(-t Ra/La))| / i = %.3g\n", dt, worst);
    EXPECT_LT(worst, 0.02) << "dt " << dt;
    EXPECT_NEAR(sim->signal(current), u / kRa, 1e-3 * u / kRa);
  }
}

TEST(DcMotor, VoltageAndCurrentLimitsHoldExactlyAndEnergyIsTheIntegralOfVi) {
  // Voltage: a 12 V reference on a 6 V supply, both signs.
  auto sim = load_bench({{"vmax", 6}});
  const auto v = sim->signal_index(axis("voltage"));
  const auto i = sim->signal_index(axis("current"));
  const auto p = sim->signal_index(axis("power"));
  const auto energy = sim->signal_index(axis("energy"));
  sim->set_input(axis("ref_voltage"), 12);
  double integral = 0, trapezoid = 0, i_prev = 0;
  for (int k = 0; k < 500; ++k) {
    sim->step();
    EXPECT_EQ(sim->signal(v), 6.0);
    integral += sim->signal(p) * sim->tick_s();
    trapezoid += sim->signal(v) * 0.5 * (i_prev + sim->signal(i)) * sim->tick_s();
    i_prev = sim->signal(i);
  }
  std::printf("  energy %.9f J, sum of V*i_mean*dt %.9f J, trapezoid of V*i %.9f J\n",
              sim->signal(energy), integral, trapezoid);
  EXPECT_NEAR(sim->signal(energy), integral, 1e-12);
  EXPECT_NEAR(sim->signal(energy), trapezoid, 2e-3 * trapezoid);
  sim->set_input(axis("ref_voltage"), -12);
  sim->step();
  EXPECT_EQ(sim->signal(v), -6.0);

  // Current: 0.5 A limit at stall (9 V would give 1.18 A).
  auto stall = load_bench({{"fc", 100}, {"imax", 0.5}});
  stall->set_input(axis("ref_voltage"), 9);
  double max_i = 0;
  for (int k = 0; k < 100; ++k) {
    stall->step();
    max_i = std::max(max_i, std::abs(stall->signal(axis("current"))));
  }
  EXPECT_EQ(max_i, 0.5);
  EXPECT_EQ(stall->signal(axis("motor_torque")), kKs * 0.5);
  EXPECT_NEAR(stall->signal(axis("energy")), 9 * 0.5 * 0.1, 0.02);  // after the rise
}

TEST(MotorController, PidSpeedReaches10RadPerSecondAndSettlesWithoutWindUp) {
  auto sim = load_bench();
  const auto speed = sim->signal_index(axis("speed"));
  const auto voltage = sim->signal_index(axis("voltage"));
  sim->set_input(axis("controller_active"), 1);
  sim->set_input(axis("ref_speed"), 10);
  double settled_at = -1, peak = 0;
  while (sim->time_s() < 2.0) {
    sim->step();
    const double w = sim->signal(speed);
    peak = std::max(peak, w);
    if (std::abs(w - 10) > 0.2)
      settled_at = -1;
    else if (settled_at < 0)
      settled_at = sim->time_s();
  }
  std::printf(
      "  from rest: within 2 %% of 10 rad/s from t = %.3f s on, peak %.4f rad/s, final %.5f\n",
      settled_at, peak, sim->signal(speed));
  ASSERT_GT(settled_at, 0) << "never settled within 2 %";
  EXPECT_LT(settled_at, 0.5);
  EXPECT_NEAR(mean_over(*sim, speed, 0.5), 10, 0.01);

  // Saturated: 30 rad/s is out of reach at 9 V (17.3 rad/s) for 3 s, then back to 10.
  sim->set_input(axis("ref_speed"), 30);
  sim->run_until(5.0);
  EXPECT_EQ(sim->signal(voltage), 9.0);
  sim->set_input(axis("ref_speed"), 10);
  const double t0 = sim->time_s();
  double unsaturated_at = -1, settled_again = -1, low = 1e9;
  while (sim->time_s() < t0 + 2.0) {
    sim->step();
    const double w = sim->signal(speed);
    low = std::min(low, w);
    if (unsaturated_at < 0 && sim->signal(voltage) < 9.0) unsaturated_at = sim->time_s() - t0;
    if (std::abs(w - 10) > 0.2)
      settled_again = -1;
    else if (settled_again < 0)
      settled_again = sim->time_s() - t0;
  }
  std::printf(
      "  after 3 s saturated: voltage leaves 9 V after %.3f s, within 2 %% after %.3f s, "
      "lowest %.4f rad/s\n",
      unsaturated_at, settled_again, low);
  EXPECT_LE(unsaturated_at, 0.0105) << "the integral wound up";
  ASSERT_GT(settled_again, 0);
  EXPECT_LT(settled_again, 0.3);
  EXPECT_GT(low, 9.0) << "undershoot";
}

TEST(MotorController, ReferencesHoldUntilSetAndDeactivationReleasesTheMotor) {
  auto sim = load_bench();
  sim->set_input(axis("ref_voltage"), 4);
  sim->run_until(2.0);  // a reference holds until it is set again
  EXPECT_EQ(sim->signal(axis("voltage")), 4.0);
  sim->set_input(axis("controller_active"), 1);
  sim->set_input(axis("ref_speed"), 5);
  sim->step(1);  // tick 2000: the controller's tick overwrites ref_voltage
  EXPECT_NE(sim->input(sim->input_index(axis("ref_voltage"))), 4.0);
  sim->run_until(2.5);
  EXPECT_NEAR(sim->signal(axis("speed")), 5, 0.05);
  sim->set_input(axis("controller_active"), 0);
  sim->step(10);  // within one controller period
  EXPECT_EQ(sim->input(sim->input_index(axis("ref_voltage"))), 0.0);
  EXPECT_EQ(sim->signal(axis("voltage")), 0.0);
}

TEST(DcMotor, ParameterInputsSwitchTheMotorAndChangeItsLawAtRunTime) {
  auto sim = load_bench();
  EXPECT_EQ(sim->signal(axis("motor_active")), 1.0);
  EXPECT_EQ(sim->signal(axis("motor_ri")), kRa);
  sim->set_input(axis("ref_voltage"), 6);
  sim->run_until(1.0);
  const double w6 = sim->signal(axis("speed"));
  EXPECT_NEAR(w6, eq_3_11(6), 1e-3 * eq_3_11(6));
  // Off: no current, the flywheel coasts down under its friction; the controller waits.
  sim->set_input(axis("controller_active"), 1);
  sim->set_input(axis("ref_speed"), 3);
  sim->set_input(axis("motor_active"), 0);
  sim->run_until(1.5);
  EXPECT_EQ(sim->signal(axis("current")), 0.0);
  EXPECT_EQ(sim->signal(axis("motor_torque")), 0.0);
  EXPECT_LT(sim->signal(axis("speed")), 0.5 * w6);
  EXPECT_EQ(sim->input(sim->input_index(axis("ref_voltage"))), 6.0) << "the controller ran";
  // On again under the controller, then open loop with twice the resistance: (3.11) again.
  sim->set_input(axis("motor_active"), 1);
  sim->run_until(2.5);
  EXPECT_NEAR(sim->signal(axis("speed")), 3, 0.05);
  sim->set_input(axis("controller_active"), 0);
  sim->set_input(axis("motor_ri"), 2 * kRa);
  sim->step(10);
  sim->set_input(axis("ref_voltage"), 6);
  sim->run_until(4.0);
  const double w_2r = (6 - 2 * kRa * kTc / kKs) / (kKs + 2 * kRa * kB / kKs);
  EXPECT_NEAR(sim->signal(axis("speed")), w_2r, 1e-3 * w_2r);
  // A value the motor cannot take stops the run, naming the input and the value, as soon as
  // the motor uses it: not while it is switched off (its parameters unread), at once when on.
  sim->set_input(axis("motor_active"), 0);
  sim->set_input(axis("gear_ratio"), 0);
  EXPECT_NO_THROW(sim->step(10));
  EXPECT_EQ(sim->signal(axis("current")), 0.0);
  sim->set_input(axis("motor_active"), 1);
  try {
    sim->step();
    FAIL() << "a zero gear ratio was accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr(axis("gear_ratio") + "' = 0: must be positive"));
  }
}

TEST(MotorController, SimTwoLawAndStateFeedbackAlsoRegulate) {
  // SimTwo's law (integral and derivative with the physics step) on the bench's pidspeed.
  auto simtwo = Simulation::load(
      bench_with({{"mode='pidspeed' kp='kp'", "mode='pidspeed' law='simtwo' kp='kp'"}}),
      bench_options({{"ki", 0.1}}));
  simtwo->set_input(axis("controller_active"), 1);
  simtwo->set_input(axis("ref_speed"), 10);
  simtwo->run_until(2.0);
  std::printf("  SimTwo law, pidspeed 10 rad/s: %.4f rad/s after 2 s\n",
              simtwo->signal(axis("speed")));
  EXPECT_NEAR(simtwo->signal(axis("speed")), 10, 0.2);
  // State feedback to 1 rad: u = Kp e + Ki ∫e + Kd (w_ref − w).
  auto state = Simulation::load(bench_with({{"mode='pidspeed' kp='kp' ki='ki' kd='kd' kf='kf'",
                                             "mode='state' kp='8' ki='0' kd='0.3' kf='0'"}}),
                                bench_options());
  state->set_input(axis("controller_active"), 1);
  state->set_input(axis("ref_pos"), 1.0);
  state->run_until(2.0);
  std::printf("  state feedback to 1 rad: %.5f rad after 2 s\n", state->signal(axis("pos")));
  EXPECT_NEAR(state->signal(axis("pos")), 1.0, 0.002);  // friction band Tc Ra/(Ks Kp) = 7e-4
}

TEST(MotorController, PidPositionWithWrapTakesTheShortWayRound) {
  const std::vector<std::pair<std::string, std::string>> position = {
      {"mode='pidspeed' kp='kp' ki='ki' kd='kd' kf='kf'", "mode='pidposition' kp='8' kd='0.3'"}};
  auto edits = position;
  const fs::path wrap = bench_with(edits);
  edits.push_back({"<axis x='0' y='0' z='1'/>", "<axis x='0' y='0' z='1' wrap='0'/>"});
  const fs::path nowrap = bench_with(edits);
  for (const auto& [dir, wraps] : {std::pair{wrap, true}, std::pair{nowrap, false}}) {
    auto sim = Simulation::load(dir, bench_options());
    const auto pos = sim->signal_index(axis("pos"));
    sim->set_input(axis("controller_active"), 1);
    sim->set_input(axis("ref_pos"), 1.5 * kPi);  // −π/2 the short way
    double lo = 0, hi = 0;
    while (sim->time_s() < 3.0) {
      sim->step();
      lo = std::min(lo, sim->signal(pos));
      hi = std::max(hi, sim->signal(pos));
    }
    const double q = sim->signal(pos);
    std::printf("  wrap %d: final %.5f rad, range [%.4f, %.4f]\n", wraps, q, lo, hi);
    if (wraps) {
      EXPECT_NEAR(q, -0.5 * kPi, 0.01);
      EXPECT_GT(lo, -0.5 * kPi - 0.2);
      EXPECT_LT(hi, 1e-3);
    } else {
      EXPECT_NEAR(q, 1.5 * kPi, 0.01);
      EXPECT_GT(lo, -1e-3);
    }
  }
}

TEST(Encoder, ReadsNTimesPprAfterNTurnsAndNeverDrifts) {
  // Spinning at 9 V for 5 s: at every sample the count is floor(ppr·θ/2π) of the θ sampled.
  auto sim = load_bench();
  const auto pos = sim->signal_index(axis("pos"));
  const auto count = sim->signal_index(axis("encoder"));
  const std::int64_t period = 40;  // the control period, 40 ms at 1 ms
  sim->set_input(axis("ref_voltage"), 9);
  double q = 0;
  while (sim->time_s() < 5.0) {
    const bool sample = sim->tick() % period == 0;
    if (sample) q = sim->signal(pos);
    sim->step();
    if (sample) {
      ASSERT_EQ(sim->signal(count), std::floor(360 * q / (2 * kPi))) << sim->time_s();
    }
  }
  std::printf("  after %.2f turns: %.0f ticks\n", q / (2 * kPi), sim->signal(count));

  // Five turns under position control, to the middle of tick 5·360.
  auto edited = bench_with(
      {{"mode='pidspeed' kp='kp' ki='ki' kd='kd' kf='kf'", "mode='pidposition' kp='8' kd='0.3'"},
       {"<axis x='0' y='0' z='1'/>", "<axis x='0' y='0' z='1' wrap='0'/>"}});
  auto turns = Simulation::load(edited, bench_options());
  turns->set_input(axis("controller_active"), 1);
  turns->set_input(axis("ref_pos"), 5 * 2 * kPi + kPi / 360);
  turns->run_until(4.0);
  std::printf("  5 turns: pos %.6f rad = %.6f turns, encoder %.0f\n", turns->signal(axis("pos")),
              turns->signal(axis("pos")) / (2 * kPi), turns->signal(axis("encoder")));
  EXPECT_EQ(turns->signal(axis("encoder")), 5 * 360);
}

TEST(Encoder, NoiseIsAppliedPerSampleAndFollowsTheSeed) {
  const fs::path dir = bench_with({{"stdev='-1'", "stdev='2'"}});
  auto a = Simulation::load(dir, bench_options());
  auto b = Simulation::load(dir, bench_options());
  a->set_input(axis("ref_voltage"), 3);
  b->set_input(axis("ref_voltage"), 3);
  a->run_until(4.0);
  b->run_until(4.0);
  EXPECT_EQ(a->signal(axis("encoder")), b->signal(axis("encoder")));
  // 100 samples of N(0, 2 ticks) accumulated: a random walk of 20 ticks' spread.
  const double truth = std::floor(360 * a->signal(axis("pos")) / (2 * kPi));
  const double off = a->signal(axis("encoder")) - truth;
  std::printf("  encoder - truth after 100 noisy samples: %.0f ticks\n", off);
  EXPECT_LT(std::abs(off), 100);
}

TEST(DriveTrain, MotorModelV3AGMRunsUnderItsPidSpeedController) {
  const fs::path scene = fs::path(S2SIM_SHARED_SCENES) / "MotorModel_V3AGM";
  if (!fs::exists(scene / "scene.xml")) GTEST_SKIP() << "no shared scenes at " << scene;
  auto sim = Simulation::load(scene, bench_options());
  const std::string a = "robots/Motor/axes/InertialBoard/";
  sim->set_input(a + "controller_active", 1);
  sim->set_input(a + "ref_speed", 5);
  sim->run_until(2.0);
  const double w = sim->signal(a + "speed"), q = sim->signal(a + "pos");
  std::printf("  InertialBoard after 2 s: speed %.4f rad/s (ref 5), pos %.3f rad, voltage %.3f V\n",
              w, q, sim->signal(a + "voltage"));
  EXPECT_NEAR(w, 5, 0.05 * 5);
  EXPECT_GT(q, 5);
}

TEST(DriveTrain, MissingPluginIsAPluginErrorNamingTheAxisAndTheKind) {
  const fs::path empty = s2sim::test::process_temp_dir() / "s2sim_no_plugins";
  fs::create_directories(empty);
  SimulationOptions o;
  o.plugin_path = {empty};
  o.default_plugin_path = false;  // only the empty folder
  try {
    Simulation::load(kBench, o);
    FAIL() << "loaded without the drive-train plugin";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::plugin);
    EXPECT_THAT(e.what(), HasSubstr("nxt_motor.xml"));
    EXPECT_THAT(e.what(), HasSubstr("robots/bench/axes/motor"));
    EXPECT_THAT(e.what(), HasSubstr("drive_train"));
  }
}

Error bench_error(std::vector<std::pair<std::string, double>> defines,
                  std::vector<std::pair<std::string, std::string>> edits = {}) {
  try {
    if (edits.empty())
      load_bench(std::move(defines));
    else
      Simulation::load(bench_with(edits), bench_options(std::move(defines)));
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "loaded";
  return Error(ErrorKind::runtime, "none");
}

TEST(DriveTrain, BadParametersNameFileElementAttributeAndValue) {
  EXPECT_THAT(bench_error({{"ri", -1}}).what(),
              HasSubstr("nxt_motor.xml: robot/articulations/joint/motor@ri: must be >= 0, got -1"));
  EXPECT_THAT(bench_error({{"ratio", 0}}).what(),
              HasSubstr("nxt_motor.xml: robot/articulations/joint/gear@ratio: must be > 0, got 0"));
  EXPECT_THAT(
      bench_error({{"ppr", 0}}).what(),
      HasSubstr("nxt_motor.xml: robot/articulations/joint/encoder@ppr: must be > 0, got 0"));
  EXPECT_THAT(bench_error({{"imax", -2}}).what(), HasSubstr("motor@imax: must be >= 0, got -2"));
  EXPECT_THAT(bench_error({}, {{"mode='pidspeed'", "mode='pidspede'"}}).what(),
              HasSubstr("controller@mode: unknown controller mode 'pidspede'"));
  EXPECT_THAT(bench_error({}, {{"<motor ", "<motor backemf='ideal' "}}).what(),
              HasSubstr("motor@backemf: must be 'physical' or 'simtwo', got 'ideal'"));
  // The loader hands the elements over as written: the plugin's errors are located as the
  // loader's are (file, element, attribute, value).
  Error e = bench_error({}, {{"active='1'", "active='yes'"}});
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_EQ(e.where().file, "nxt_motor.xml");
  EXPECT_EQ(e.where().element, "robot/articulations/joint/motor");
  EXPECT_EQ(e.where().attribute, "active");
  EXPECT_THAT(e.message(), HasSubstr("'yes'"));
  e = bench_error({}, {{"mode='pidspeed'", "mode='fuzzy'"}});
  EXPECT_EQ(e.where().element, "robot/articulations/joint/controller");
  EXPECT_EQ(e.where().attribute, "mode");
  EXPECT_THAT(e.message(), HasSubstr("unknown controller mode 'fuzzy'"));
  EXPECT_NO_THROW(
      Simulation::load(bench_with({{"mode='pidspeed'", "mode='PIDSpeed' law='SimTwo'"}}),
                       bench_options({})));  // keywords are case-insensitive
  // A value inherited from a <default> is reported where it is written.
  e = bench_error({}, {{"<articulations>", "<articulations><default><spring k='-1'/></default>"}});
  EXPECT_EQ(e.where().element, "robot/articulations/default/spring");
  EXPECT_EQ(e.where().attribute, "k");
  EXPECT_THAT(e.message(), HasSubstr("must be >= 0, got -1"));
}

TEST(DriveTrain, SnapshotAndResetAreExactWithMotorState) {
  auto sim = load_bench();
  sim->set_input(axis("controller_active"), 1);
  sim->set_input(axis("ref_speed"), 7);
  sim->step(123);
  const auto snap = sim->save();
  sim->step(400);
  const double i = sim->signal(axis("current")), e = sim->signal(axis("energy"));
  sim->restore(snap);
  sim->step(400);
  EXPECT_EQ(sim->signal(axis("current")), i);
  EXPECT_EQ(sim->signal(axis("energy")), e);
  sim->reset();
  EXPECT_EQ(sim->input(sim->input_index(axis("controller_active"))), 0.0);
  sim->set_input(axis("controller_active"), 1);
  sim->set_input(axis("ref_speed"), 7);
  sim->step(523);
  EXPECT_EQ(sim->signal(axis("current")), i);
}

TEST(DcMotor, RotorInertiaIsReflectedAsNSquaredJ) {
  // Open circuit (imax 0), no friction: a 0.01 N·m torque accelerates flywheel + N²·J.
  const double ratio = 2, rotor = 1e-4, flywheel = 1e-3;
  auto sim = load_bench({{"imax", 0}, {"fc", 0}, {"bv", 0}, {"ratio", ratio}, {"rotor_j", rotor}});
  sim->set_input(axis("ref_torque"), 0.01);
  sim->run_until(1.0);
  const double expected = 0.01 * (1.0 - 0.0005) / (flywheel + ratio * ratio * rotor);
  std::printf("  w after 1 s = %.6f rad/s, 0.01 N*m / (1e-3 + 2^2 * 1e-4) = %.6f\n",
              sim->signal(axis("speed")), expected);
  EXPECT_NEAR(sim->signal(axis("speed")), expected, 1e-6 * expected);
}

TEST(DcMotor, SimTwoBackEmfSwitchUsesKwOverN) {
  auto physical = load_bench({{"ratio", 4}});
  auto simtwo = Simulation::load(bench_with({{"<motor ", "<motor backemf='simtwo' "}}),
                                 bench_options({{"ratio", 4}}));
  double w[2] = {0, 0}, e[2] = {0, 0};
  int k = 0;
  for (auto* sim : {physical.get(), simtwo.get()}) {
    sim->set_input(axis("ref_voltage"), 3);
    sim->run_until(0.5);
    w[k] = sim->signal(axis("speed"));  // the speed the motor sees in the next tick
    sim->step();
    e[k++] = sim->signal(axis("back_emf"));
  }
  const double w1 = w[0], e1 = e[0], w2 = w[1], e2 = e[1];
  std::printf("  ratio 4 at 3 V: physical w = %.4f rad/s, e = %.4f V; simtwo w = %.4f, e = %.4f\n",
              w1, e1, w2, e2);
  EXPECT_NEAR(e1, kKs * 4 * w1, 1e-12);
  EXPECT_NEAR(e2, kKs * w2 / 4, 1e-12);
}

}  // namespace
}  // namespace s2sim::test
