// The `sensors` plugin from scenes: every acceptance point of docs/models/sensors.md.
#include <s2sim/kernel/simulation.hpp>

#include <gmock/gmock.h>
#include "common/edited_copy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kFixtures = fs::path(S2SIM_SOURCE_DIR) / "tests/plugins/sensors/fixtures";

SimulationOptions options(std::uint64_t seed = 1,
                          std::vector<std::pair<std::string, double>> constants = {}) {
  SimulationOptions o;
  o.seed = seed;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  o.constants = std::move(constants);
  return o;
}

std::unique_ptr<Simulation> load(const std::string& fixture, SimulationOptions o = options()) {
  return Simulation::load(kFixtures / fixture, o);
}

/// A copy of a fixture with one file's text replaced, for error cases.
fs::path fixture_with(const std::string& fixture, const std::string& file, const std::string& from,
                      const std::string& to) {
  return test::edited_copy(kFixtures / fixture, file, from, to);
}

struct Stats {
  double mean = 0, stdev = 0;
};
Stats stats(const std::vector<double>& v) {
  Stats s;
  for (double x : v)
    s.mean += x;
  s.mean /= static_cast<double>(v.size());
  for (double x : v)
    s.stdev += (x - s.mean) * (x - s.mean);
  s.stdev = std::sqrt(s.stdev / static_cast<double>(v.size() - 1));
  return s;
}

/// Samples a signal after each of `n` ticks.
std::vector<double> sample(Simulation& sim, const std::string& signal, int n) {
  const auto k = sim.signal_index(signal);
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    sim.step(1);
    out.push_back(sim.signal(k));
  }
  return out;
}

// --- IRSharp ---------------------------------------------------------------------------------

TEST(IRSharp, ReadsTheWallDistanceWithin1mmWithoutNoise) {
  for (int k = 2; k <= 16; ++k) {
    const double d = k / 20.0;
    auto sim = load("ir_wall", options(1, {{"D", d}}));
    sim->step(1);
    EXPECT_NEAR(sim->signal("sensors/clean/value"), d, 1e-3) << d;
    EXPECT_NEAR(sim->signal("sensors/clean/value"), d, 1e-9) << d;  // in fact exact
    EXPECT_EQ(sim->signal("sensors/clean/valid"), 1.0);
  }
}

TEST(IRSharp, PastTheBeamLengthReportsNoMeasurement) {
  auto sim = load("ir_wall", options(1, {{"D", 0.85}}));
  sim->step(1);
  EXPECT_EQ(sim->signal("sensors/clean/value"), -1.0);
  EXPECT_EQ(sim->signal("sensors/clean/valid"), 0.0);
  EXPECT_EQ(sim->signal("sensors/noisy/value"), -1.0);  // no noise on "no measurement"
}

/// σ_d(d) of simtwo-format.md §12.3, written out independently of the plugin.
double sigma_d(double d) {
  const double gain = 1.2, offset = 0.05, var_k = 0.002, var_d = 0.01;
  const double u = 1 / (gain * d + offset);
  return std::sqrt(var_d * d + var_k) / std::abs(gain * u * u);
}

TEST(IRSharp, NoiseStandardDeviationMatchesSigmaDWithin5PercentOver10000Samples) {
  for (double d : {0.15, 0.4, 0.75}) {
    auto sim = load("ir_wall", options(7, {{"D", d}}));
    const auto v = sample(*sim, "sensors/noisy/value", 10000);
    const Stats s = stats(v);
    EXPECT_NEAR(s.stdev / sigma_d(d), 1.0, 0.05) << "d = " << d << " stdev " << s.stdev;
    EXPECT_NEAR(s.mean, d, 4 * sigma_d(d) / std::sqrt(10000.0)) << d;  // unbiased
    std::printf("IRSharp d=%.2f m: sigma_d=%.5f m, measured %.5f m (%+.2f %%)\n", d, sigma_d(d),
                s.stdev, 100 * (s.stdev / sigma_d(d) - 1));
  }
}

TEST(IRSharp, SameSeedSameNoiseOtherSeedOtherNoise) {
  auto a = load("ir_wall", options(11));
  auto b = load("ir_wall", options(11));
  auto c = load("ir_wall", options(12));
  const auto va = sample(*a, "sensors/noisy/value", 200);
  EXPECT_EQ(va, sample(*b, "sensors/noisy/value", 200));
  const auto vc = sample(*c, "sensors/noisy/value", 200);
  int same = 0;
  for (std::size_t i = 0; i < va.size(); ++i)
    same += va[i] == vc[i];
  EXPECT_EQ(same, 0);
  // And reset() replays the same noise.
  a->reset();
  EXPECT_EQ(va, sample(*a, "sensors/noisy/value", 200));
}

TEST(IRSharp, SampleAndHoldAtItsPeriod) {
  auto sim = load("ir_wall");
  const auto v = sample(*sim, "sensors/slow/value", 100);  // period 10 ms = 10 ticks
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i % 10 == 0)
      EXPECT_NE(v[i], i > 0 ? v[i - 1] : -2.0) << i;  // a new noisy sample on the period
    else
      EXPECT_EQ(v[i], v[i - 1]) << i;  // held in between
  }
}

// --- one-ray presence sensors, sonar ---------------------------------------------------------

TEST(Proximity, InductiveSeesMetalCapacitiveSeesAnything) {
  auto sim = load("ir_wall", options(1, {{"D", 0.5}}));
  sim->step(1);
  EXPECT_EQ(sim->signal("sensors/ind_metal/value"), 1.0);
  EXPECT_EQ(sim->signal("sensors/ind_plastic/value"), 0.0);
  EXPECT_EQ(sim->signal("sensors/cap/value"), 1.0);
  auto far = load("ir_wall", options(1, {{"D", 0.9}}));
  far->step(1);
  EXPECT_EQ(far->signal("sensors/ind_metal/value"), 0.0);
  EXPECT_EQ(far->signal("sensors/cap/value"), 0.0);
}

TEST(Sonar, NearestEchoInItsCone) {
  auto sim = load("ir_wall", options(1, {{"D", 0.6}}));
  sim->step(1);
  EXPECT_NEAR(sim->signal("sensors/sonar/value"), 0.6, 1e-9);
}

TEST(Proximity, RfidReadsTheTagIdAndTheSolenoidPullsIron) {
  auto sim = load("proximity");
  sim->step(1);
  EXPECT_EQ(sim->signal("sensors/reader/value"), 42.0);
  EXPECT_EQ(sim->signal("sensors/reader_iron/value"), 0.0);  // iron carries no RFID tag
  EXPECT_EQ(sim->signal("sensors/magnet/value"), 1.0);       // ferromagnetic
  EXPECT_EQ(sim->signal("sensors/magnet/force"), 0.0);       // Vin = 0
  sim->step(100);
  EXPECT_EQ(sim->signal("things/iron/vx"), 0.0);
  sim->set_input("sensors/magnet/vin", 1.0);
  sim->step(1);
  // f = ½·Vin·fmax/(1 + k2·d)², d = 0.45 m.
  const double f = 0.5 * 1 * 2 / std::pow(1 + 4 * 0.45, 2);
  EXPECT_NEAR(sim->signal("sensors/magnet/force"), f, 1e-9);
  sim->step(99);
  EXPECT_LT(sim->signal("things/iron/vx"), 0.0);  // pulled toward the magnet at x = 0
  EXPECT_NEAR(sim->signal("things/iron/vx"), -f / 0.2 * 0.1, 0.02 * f / 0.2 * 0.1 + 1e-3);
}

TEST(Proximity, PenTipTouchesTheCanvasAndTheBeaconSaysWhereItIs) {
  auto sim = load("proximity");
  sim->step(1);
  EXPECT_EQ(sim->signal("sensors/pen_touch/value"), 1.0);
  EXPECT_NEAR(sim->signal("sensors/pen_touch/x"), 3.0, 1e-12);
  EXPECT_EQ(sim->signal("sensors/pen_up/value"), 0.0);
  EXPECT_EQ(sim->signal("sensors/lighthouse/x"), 2.0);
  EXPECT_EQ(sim->signal("sensors/lighthouse/y"), -3.0);
  EXPECT_EQ(sim->signal("sensors/lighthouse/z"), 1.0);
}

// --- floorline -------------------------------------------------------------------------------

TEST(FloorLine, OneOverTheLineZeroBesideItHalfOverItsEdge) {
  auto sim = load("floorline");
  sim->step(1);
  EXPECT_EQ(sim->signal("sensors/on/value"), 1.0);
  EXPECT_EQ(sim->signal("sensors/beside/value"), 0.0);
  EXPECT_NEAR(sim->signal("sensors/half/value"), 0.5, 1e-12);
  EXPECT_EQ(sim->signal("sensors/short/value"), 0.0);      // the beam does not reach the floor
  EXPECT_EQ(sim->signal("sensors/other_tag/value"), 0.0);  // over a line of another tag
  EXPECT_EQ(sim->signal("sensors/no_tag/value"), 0.0);     // no tag never sees anything
}

// SimTwo accepts a tag no track polygon carries (a shipped SimTwo project was once refused
// for it): a warning naming file, element and value, and the sensor reads 0 for that tag.
TEST(FloorLine, AnUnknownTagIsAWarningNamingFileElementAndValueAndReadsZero) {
  const fs::path dir =
      fixture_with("floorline", "sensors.xml", "<tag value='black'/>", "<tag value='blak'/>");
  auto sim = Simulation::load(dir, options());
  std::string warning;
  for (const auto& w : sim->warnings())
    if (w.find("blak") != std::string::npos) warning = w;
  EXPECT_THAT(warning, HasSubstr("sensors.xml"));
  EXPECT_THAT(warning, HasSubstr("floorline"));
  EXPECT_THAT(warning, HasSubstr("'blak'"));
  EXPECT_THAT(warning, HasSubstr("'black', 'white'"));
  sim->step(1);
  EXPECT_EQ(sim->signal("sensors/on/value"), 0.0);  // over the black line, looking for 'blak'
}

// --- ranger2d --------------------------------------------------------------------------------

/// Distance from the centre of the 2 m room to its walls along heading phi.
double room_distance(double phi) {
  return 1 / std::max(std::abs(std::cos(phi)), std::abs(std::sin(phi)));
}

TEST(Ranger2D, SweepsTheFanOncePerPeriodAndSeesTheRoom) {
  auto sim = load("ranger");
  const int n = 360;
  std::vector<std::size_t> rays;
  for (int i = 0; i < n; ++i)
    rays.push_back(sim->signal_index("sensors/sweep/ray/" + std::to_string(i)));
  const auto sweeps = sim->signal_index("sensors/sweep/sweeps");
  sim->step(9);  // ticks 0..8: the sweep is not complete
  EXPECT_EQ(sim->signal(sweeps), 0.0);
  EXPECT_EQ(sim->signal(rays[0]), -1.0);
  sim->step(1);  // tick 9 ends the first period
  EXPECT_EQ(sim->signal(sweeps), 1.0);
  const double a = 270 * kPi / 180;
  for (int i = 0; i < n; ++i) {
    const double phi = -a / 2 + a * i / (n - 1);
    ASSERT_NEAR(sim->signal(rays[static_cast<std::size_t>(i)]), room_distance(phi), 1e-9) << i;
  }
  sim->step(90);
  EXPECT_EQ(sim->signal(sweeps), 10.0);  // one sweep per 10 ms period
}

TEST(Ranger2D, InstantModeCastsEveryRayAtItsPeriod) {
  auto sim = load("ranger");
  sim->step(1);
  const double a = 2 * kPi;
  for (int i = 0; i < 8; ++i) {
    const double phi = -a / 2 + a * i / 7;
    const double expect = room_distance(phi) <= 1.2 ? room_distance(phi) : -1.0;
    EXPECT_NEAR(sim->signal("sensors/instant/ray/" + std::to_string(i)), expect, 1e-9) << i;
  }
  sim->step(39);
  EXPECT_EQ(sim->signal("sensors/instant/sweeps"), 2.0);  // ticks 0 and 20
}

TEST(Ranger2D, NoiseHasItsStandardDeviationOnHitsOnly) {
  auto sim = load("ranger");
  std::vector<double> err;
  const double a = 270 * kPi / 180;
  for (int sweep = 0; sweep < 30; ++sweep) {
    sim->step(1);
    for (int i = 0; i < 360; ++i) {
      const double phi = -a / 2 + a * i / 359;
      const RayHit h = sim->cast_ray({0.1, -0.2, 0.5}, {std::cos(phi), std::sin(phi), 0}, 4);
      ASSERT_TRUE(h.hit);
      err.push_back(sim->signal("sensors/noisy/ray/" + std::to_string(i)) - h.distance_m);
    }
  }
  const Stats s = stats(err);
  EXPECT_NEAR(s.stdev / 0.01, 1.0, 0.05);
  EXPECT_NEAR(s.mean, 0.0, 4 * 0.01 / std::sqrt(10800.0));
}

TEST(Ranger2D, DefaultScenesRangerReturnsTheSurroundingGeometry) {
  const fs::path scene = fs::path(S2SIM_SHARED_SCENES) / "default";
  if (!fs::exists(scene / "scene.xml")) GTEST_SKIP() << "no " << scene;
  auto sim = Simulation::load(scene, options());
  const int n = 768;
  ASSERT_TRUE(sim->find_signal("sensors/ranger2d/ray/767"));
  EXPECT_FALSE(sim->find_signal("sensors/ranger2d/ray/768"));
  // Expected: the ray of the fan from (1, 0, 0.5), pitched down (rot_deg y = 90): the ray of
  // yaw offset phi points along (0, sin phi, -cos phi). Swept: tick j of the 10-tick period
  // casts rays [round(768 j / 10), round(768 (j + 1) / 10)) from the state at its start.
  const double a = 270 * kPi / 180;
  std::vector<double> expected(n);
  for (int j = 0; j < 10; ++j) {
    for (int i = (n * j + 5) / 10; i < (n * (j + 1) + 5) / 10; ++i) {
      const double phi = -a / 2 + a * i / (n - 1);
      const RayHit h = sim->cast_ray({1, 0, 0.5}, {0, std::sin(phi), -std::cos(phi)}, 1.0);
      expected[static_cast<std::size_t>(i)] = h.hit ? h.distance_m : -1;
    }
    sim->step(1);
  }
  EXPECT_EQ(sim->signal("sensors/ranger2d/sweeps"), 1.0);
  int hits = 0, ground = 0;
  for (int i = 0; i < n; ++i) {
    const double phi = -a / 2 + a * i / (n - 1);
    const double v = sim->signal("sensors/ranger2d/ray/" + std::to_string(i));
    const double e = expected[static_cast<std::size_t>(i)];
    if (e < 0) {
      EXPECT_EQ(v, -1.0) << i;
      continue;
    }
    ++hits;
    EXPECT_NEAR(v, e, 0.01) << i;  // noise stdev 0.002 m
    if (std::abs(e - 0.5 / std::cos(phi)) < 1e-9) ++ground;
  }
  std::printf("default ranger2d: %d of %d rays hit, %d on the floor\n", hits, n, ground);
  EXPECT_GT(ground, 300);  // |phi| < 60 degrees reaches the floor within 1 m
  sim->step(90);
  EXPECT_EQ(sim->signal("sensors/ranger2d/sweeps"), 10.0);
}

// --- IMU and pose ----------------------------------------------------------------------------

TEST(Imu, AtRestTheAccelerometerReadsGUpInTheSensorFrame) {
  auto sim = load("imu");
  sim->step(25);
  // rot_deg x = 90: the sensor's +Y is the world's up.
  EXPECT_NEAR(sim->signal("robots/rig/sensors/rest/acc_x"), 0.0, 1e-9);
  EXPECT_NEAR(sim->signal("robots/rig/sensors/rest/acc_y"), kGravity_m_s2, 1e-9);
  EXPECT_NEAR(sim->signal("robots/rig/sensors/rest/acc_z"), 0.0, 1e-9);
  EXPECT_NEAR(sim->signal("robots/rig/sensors/rest/gyro_z"), 0.0, 1e-12);
}

TEST(Imu, AtRestWithNoiseReadsGWithinItsBiasAndItsWhiteNoise) {
  auto sim = load("imu", options(3));
  const auto v = sample(*sim, "robots/rig/sensors/rest_noisy/acc_z", 5000);
  const Stats s = stats(v);
  EXPECT_NEAR(s.mean, kGravity_m_s2, 4 * 0.05);  // bias drawn N(0, 0.05) at reset
  EXPECT_NEAR(s.stdev / 0.02, 1.0, 0.05);        // white noise 0.02 m/s²
  // Another seed draws other biases (all three axes compared).
  auto other = load("imu", options(4));
  sim->reset();
  double diff = 0;
  for (const char* axis : {"acc_x", "acc_y", "acc_z"}) {
    const std::string name = std::string("robots/rig/sensors/rest_noisy/") + axis;
    diff += std::abs(stats(sample(*sim, name, 2000)).mean - stats(sample(*other, name, 2000)).mean);
  }
  EXPECT_GT(diff, 0.01);
}

TEST(Imu, TheBiasRandomWalkHasIncrementsOfBiasWalkTimesRootT) {
  auto sim = load("imu", options(9));
  const auto v = sample(*sim, "robots/rig/sensors/walk/gyro_x", 5001);
  std::vector<double> steps;
  for (std::size_t i = 1; i < v.size(); ++i)
    steps.push_back(v[i] - v[i - 1]);
  const Stats s = stats(steps);
  const double sigma = 0.01 * std::sqrt(0.001);  // bias_walk * sqrt(period)
  EXPECT_NEAR(s.stdev / sigma, 1.0, 0.05);
  EXPECT_NEAR(s.mean, 0.0, 4 * sigma / std::sqrt(5000.0));
  // The other instrument's axes do not walk.
  EXPECT_NEAR(sim->signal("robots/rig/sensors/walk/acc_z"), kGravity_m_s2, 1e-9);
}

TEST(Imu, ASpinningBodyReadsItsRateAndTheCentripetalAcceleration) {
  auto sim = load("imu");
  sim->set_input("robots/rig/axes/spin/ref_torque", 0.5);
  sim->run_until(0.5);
  sim->set_input("robots/rig/axes/spin/ref_torque", 0.0);
  // The IMU (period 10 ms) samples on tick 700 the state that ticks up to 699 made: read the
  // arm's rate from that same state, and one period earlier for its angular acceleration.
  sim->run_until(0.69);
  const double w_before = sim->signal("robots/rig/solids/arm/wz");
  sim->run_until(0.70);
  const double w = sim->signal("robots/rig/solids/arm/wz");
  const double alpha = (w - w_before) / 0.01;
  sim->step(1);  // tick 700: the IMU samples
  ASSERT_GT(std::abs(w), 3.0);
  const double gyro = sim->signal("robots/rig/sensors/tip/gyro_z");
  EXPECT_NEAR(gyro / w, 1.0, 1e-9);
  // The IMU is r = 0.5 m from the axis, its +X radial outward, +Y along the motion: a = -w² r
  // along +X (centripetal), alpha r along +Y (zero for a free hinge).
  const double r = 0.5;
  const double ax = sim->signal("robots/rig/sensors/tip/acc_x");
  EXPECT_NEAR(-ax / (w * w * r), 1.0, 0.01);
  EXPECT_NEAR(sim->signal("robots/rig/sensors/tip/acc_y"), alpha * r, 0.01 * w * w * r);
  EXPECT_NEAR(sim->signal("robots/rig/sensors/tip/acc_z"), kGravity_m_s2, 1e-3);
  std::printf("IMU on the arm: w = %.4f rad/s, gyro %.4f, -acc_x = %.4f, w^2 r = %.4f (%+.3f %%)\n",
              w, gyro, -ax, w * w * r, 100 * (-ax / (w * w * r) - 1));
}

TEST(PoseSensor, NoisyGroundTruth) {
  auto sim = load("imu", options(5));
  sim->step(1);
  EXPECT_NEAR(sim->signal("robots/rig/sensors/truth/x"), 0.6, 1e-12);
  EXPECT_NEAR(sim->signal("robots/rig/sensors/truth/z"), 1.0, 1e-12);
  const auto x = sample(*sim, "robots/rig/sensors/gps/x", 5000);
  const Stats s = stats(x);
  EXPECT_NEAR(s.mean, 0.6, 4 * 0.01 / std::sqrt(5000.0));
  EXPECT_NEAR(s.stdev / 0.01, 1.0, 0.05);
  sim->reset();
  const Stats yaw = stats(sample(*sim, "robots/rig/sensors/gps/yaw", 5000));
  EXPECT_NEAR(yaw.stdev / 0.02, 1.0, 0.05);
}

// --- sensors without an <ID> ------------------------------------------------------------------

TEST(UnnamedSensors, ThreeOfOneKindAreNamedByTheirIndexInTheRobotsList) {
  auto sim = load("unnamed");
  std::vector<std::string> names;
  for (std::size_t i = 0; i < sim->signal_count(); ++i)
    if (sim->signal_info(i).name.find("sensors/") != std::string::npos)
      names.push_back(sim->signal_info(i).name);
  EXPECT_THAT(names,
              ::testing::ElementsAre("robots/bot/sensors/0/value", "robots/bot/sensors/0/valid",
                                     "robots/bot/sensors/1/value", "robots/bot/sensors/1/valid",
                                     "robots/bot/sensors/2/value", "robots/bot/sensors/2/valid",
                                     "sensors/3/value", "sensors/3/valid"));
  EXPECT_FALSE(sim->find_signal("robots/bot/sensors//value").has_value());
  sim->step(1);
  // In file order: each 0.1 m nearer the wall than the one before.
  EXPECT_NEAR(sim->signal("robots/bot/sensors/0/value"), 1.0, 1e-9);
  EXPECT_NEAR(sim->signal("robots/bot/sensors/1/value"), 0.9, 1e-9);
  EXPECT_NEAR(sim->signal("robots/bot/sensors/2/value"), 0.8, 1e-9);
  // World-fixed: the fourth of the world's list (GetGlobalSensorVal(3)).
  EXPECT_NEAR(sim->signal("sensors/3/value"), 0.5, 1e-9);
}

TEST(UnnamedSensors, AnIdEqualToAnIndexNameIsALocatedError) {
  // The first sensor takes the ID '1': the second, ID-less, would be named '1' too.
  const fs::path before = fixture_with("unnamed", "bot.xml", "<IRSharp>\n      <pos x='0' ",
                                       "<IRSharp>\n      <ID value='1'/>\n      <pos x='0' ");
  EXPECT_THAT([&] { Simulation::load(before, options()); },
              ::testing::ThrowsMessage<Error>(::testing::AllOf(
                  HasSubstr("bot.xml: robot/sensors/IRSharp[2]"), HasSubstr("index '1'"),
                  HasSubstr("robot/sensors/IRSharp[1] has as its ID"))));
  // The third sensor takes the ID '0', the index name of the first.
  const fs::path after = fixture_with("unnamed", "bot.xml", "<IRSharp>\n      <pos x='0.2' ",
                                      "<IRSharp>\n      <ID value='0'/>\n      <pos x='0.2' ");
  EXPECT_THAT([&] { Simulation::load(after, options()); },
              ::testing::ThrowsMessage<Error>(::testing::AllOf(
                  HasSubstr("bot.xml: robot/sensors/IRSharp[3]"),
                  HasSubstr("the ID '0' is the index name of the ID-less sensor at bot.xml: "
                            "robot/sensors/IRSharp[1]"))));
}

// --- errors ----------------------------------------------------------------------------------

TEST(SensorErrors, NegativeBeamLengthNamesFileElementAttributeAndValue) {
  const fs::path dir =
      fixture_with("ir_wall", "sensors.xml", "<beam length='0.8'/>", "<beam length='-0.3'/>");
  try {
    Simulation::load(dir, options());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("sensors.xml"));
    EXPECT_THAT(e.what(), HasSubstr("sensors/IRSharp"));
    EXPECT_THAT(e.what(), HasSubstr("beam@length"));
    EXPECT_THAT(e.what(), HasSubstr("-0.3"));
  }
}

TEST(SensorErrors, ZeroRaysAndABadScanModeAreErrors) {
  const fs::path rays = fixture_with("ranger", "sensors.xml", "rays='8'", "rays='0'");
  EXPECT_THAT([&] { Simulation::load(rays, options()); },
              ::testing::ThrowsMessage<Error>(
                  HasSubstr("beam@rays: must be an integer from 1 to 100000, got 0")));
  const fs::path mode = fixture_with("ranger", "sensors.xml", "mode='instant'", "mode='fast'");
  EXPECT_THAT([&] { Simulation::load(mode, options()); },
              ::testing::ThrowsMessage<Error>(
                  HasSubstr("scan@mode: must be 'sweep' or 'instant', got 'fast'")));
}

}  // namespace
}  // namespace s2sim

namespace s2sim {
namespace {

// --- robot sensors and readings in controllers -----------------------------------------------

SimulationOptions with_reader() {
  SimulationOptions o = options();
  o.plugin_path.push_back(fs::path(S2SIM_TEST_PLUGIN_DIR) / "sensor-reader");
  return o;
}

TEST(RobotSensors, SkipTheirOwnBodyButSeeTheRobotsOtherSolids) {
  auto sim = Simulation::load(kFixtures / "controller", with_reader());
  sim->step(10);
  EXPECT_NEAR(sim->signal("robots/bot/sensors/front/value"), 1.0, 1e-9);  // the wall
  EXPECT_NEAR(sim->signal("robots/bot/sensors/low/value"), 0.29, 1e-9);   // the bumper solid
  // absolute_coords: the pose in the robot frame at load; the same place as `front`.
  EXPECT_NEAR(sim->signal("robots/bot/sensors/front_abs/value"), 1.0, 1e-9);
  // solid id: on the bumper, looking back at the robot's main body.
  EXPECT_NEAR(sim->signal("robots/bot/sensors/on_bumper/value"), 0.1, 1e-9);
  // A kind placed with <plugin> reads the same children from its parameters.
  EXPECT_NEAR(sim->signal("robots/bot/sensors/psonar/value"), 1.0, 1e-9);
}

TEST(Readings, AControllerReadsTheSensorThroughTheSdkInTheSameTick) {
  auto sim = Simulation::load(kFixtures / "controller", with_reader());
  sim->step(1);
  EXPECT_EQ(sim->signal("controllers/reader/seen"), sim->signal("robots/bot/sensors/front/value"));
  EXPECT_NEAR(sim->signal("controllers/reader/seen"), 1.0, 1e-9);
  const fs::path dir =
      fixture_with("controller", "scene.xml", "sensors/front/value", "sensors/frnt/value");
  EXPECT_THAT([&] { Simulation::load(dir, with_reader()); },
              ::testing::ThrowsMessage<Error>(HasSubstr("robots/bot/sensors/frnt/value")));
}

}  // namespace
}  // namespace s2sim
