// Things added and deleted while running (Simulation::add_thing, delete_thing; the spare bodies
// of <s2sim><runtime_things count>): they fall as free fall says, touch and stop touching,
// and snapshots, resets and repeated runs bring them back exactly.
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <thread>

namespace s2sim {
namespace {

namespace fs = std::filesystem;

const fs::path kScene = fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/runtime_things";

std::unique_ptr<Simulation> load(std::optional<int> spare = std::nullopt) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  o.runtime_things = spare;
  return Simulation::load(kScene, o);
}

ThingSpec box_at(double x, double y, double z) {
  ThingSpec spec;
  spec.shape = ThingShape::box;
  spec.size_m = {0.1, 0.1, 0.1};
  spec.mass_kg = 0.5;
  spec.pose.position = {x, y, z};
  return spec;
}

int touching(const Simulation& sim, int body) {
  int n = 0;
  for (std::size_t c = 0; c < sim.contact_count(); ++c) {
    const ContactInfo& info = sim.contact(c);
    if (info.body_a.index == body || info.body_b.index == body) ++n;
  }
  return n;
}

TEST(RuntimeThings, TheSceneSaysHowManySpareBodiesAndEachHasSignals) {
  auto sim = load();
  ASSERT_EQ(sim->scene().runtime_things.size(), 4u);
  EXPECT_EQ(sim->things().size(), 5u);  // the ball, then the four spare bodies
  EXPECT_TRUE(sim->things()[0].present);
  EXPECT_FALSE(sim->things()[1].present);
  EXPECT_NO_THROW(sim->signal_index("runtime_things/3/z"));
  EXPECT_EQ(sim->body_path(sim->things()[4].body), "runtime_things/3");
  EXPECT_EQ(load(0)->scene().runtime_things.size(), 0u) << "the option overrides the scene";
}

TEST(RuntimeThings, ABoxAddedAtOneSecondFallsAsFreeFallSaysAndLandsOnTheFloor) {
  auto sim = load();
  sim->run_until(1.0);
  const double z0 = 1.0;
  const int box = sim->add_thing(box_at(0.5, 0, z0), "crate");
  EXPECT_EQ(sim->body_pose(box).position.z, z0);
  EXPECT_EQ(norm(sim->body_twist(box).linear_m_s), 0.0);
  // Free fall: z = z0 - g t^2 / 2 until it meets the floor (0.05 m, half its edge).
  sim->run_until(1.3);
  const double t = 0.3;
  EXPECT_NEAR(sim->body_pose(box).position.z, z0 - 0.5 * kGravity_m_s2 * t * t, 2e-3);
  EXPECT_EQ(touching(*sim, box), 0);
  sim->run_until(3.0);
  EXPECT_NEAR(sim->body_pose(box).position.z, 0.05, 2e-3) << "it rests on the floor";
  EXPECT_NEAR(sim->body_pose(box).position.x, 0.5, 1e-3);
  EXPECT_GT(touching(*sim, box), 0);
  const double weight = 0.5 * kGravity_m_s2;
  EXPECT_NEAR(sim->signal(sim->signal_index("runtime_things/0/contact_force")), weight,
              0.02 * weight);
}

TEST(RuntimeThings, ADeletedThingLeavesNoContactAndStaysOutOfTheWorld) {
  auto sim = load();
  sim->run_until(0.5);
  const int ball = sim->things()[0].body;
  ASSERT_GT(touching(*sim, ball), 0) << "the ball rests on the floor";
  sim->delete_thing(ball);
  EXPECT_FALSE(sim->things()[0].present);
  sim->run_until(1.5);
  EXPECT_EQ(touching(*sim, ball), 0);
  EXPECT_EQ(sim->contact_count(), 0u);
  EXPECT_LT(sim->body_pose(ball).position.z, -100) << "parked out of the world";
  EXPECT_EQ(norm(sim->body_twist(ball).linear_m_s), 0.0) << "and it does not fall";
  // An added box dropped where the ball was meets only the floor.
  const int box = sim->add_thing(box_at(0, 0, 0.3), "crate");
  sim->run_until(2.5);
  EXPECT_NEAR(sim->body_pose(box).position.z, 0.05, 2e-3);
  // Deleting an added thing frees its spare body for the next one.
  sim->delete_thing(box);
  sim->step(1);  // the contacts listed are the last step's
  EXPECT_EQ(sim->contact_count(), 0u);
  EXPECT_EQ(sim->add_thing(box_at(1, 1, 1), "again"), box);
}

TEST(RuntimeThings, TwoAddedThingsTouchEachOther) {
  auto sim = load();
  const int lower = sim->add_thing(box_at(1, 0, 0.05), "lower");
  ThingSpec ball = box_at(1, 0, 0.3);
  ball.shape = ThingShape::sphere;
  ball.size_m = {0.05, 0.05, 0.05};
  const int upper = sim->add_thing(ball, "upper");
  sim->run_until(1.0);
  EXPECT_NEAR(sim->body_pose(upper).position.z, 0.1 + 0.05, 2e-3) << "the sphere rests on the box";
  bool met = false;
  for (std::size_t c = 0; c < sim->contact_count(); ++c) {
    const ContactInfo& info = sim->contact(c);
    met |= (info.body_a.index == upper && info.body_b.index == lower) ||
           (info.body_a.index == lower && info.body_b.index == upper);
  }
  EXPECT_TRUE(met);
}

TEST(RuntimeThings, ResetRemovesTheAddedAndBringsBackTheDeleted) {
  auto sim = load();
  sim->run_until(0.2);
  const std::vector<double> start = [&] {
    auto fresh = load();
    fresh->run_until(0.2);
    return fresh->signal_values();
  }();
  const int ball = sim->things()[0].body;
  sim->delete_thing(ball);
  sim->add_thing(box_at(0.5, 0, 1), "crate");
  sim->run_until(0.4);
  sim->reset();
  EXPECT_TRUE(sim->things()[0].present);
  for (std::size_t t = 1; t < sim->things().size(); ++t)
    EXPECT_FALSE(sim->things()[t].present);
  sim->run_until(0.2);
  EXPECT_EQ(sim->signal_values(), start) << "the reset run is the fresh run, bit for bit";
}

TEST(RuntimeThings, ASnapshotHoldsTheAddedThingsExactly) {
  auto sim = load();
  sim->run_until(0.3);
  const int box = sim->add_thing(box_at(0.5, 0, 0.6), "crate");
  sim->run_until(0.5);
  const Simulation::Snapshot snap = sim->save();
  sim->run_until(1.5);
  const std::vector<double> after = sim->signal_values();
  const Pose landed = sim->body_pose(box);
  // Changed since: the box deleted, another added elsewhere.
  sim->delete_thing(box);
  ThingSpec ball = box_at(-1, 0, 2);
  ball.shape = ThingShape::sphere;
  sim->add_thing(ball, "ball2");
  sim->restore(snap);
  EXPECT_TRUE(sim->things()[1].present);
  EXPECT_EQ(sim->things()[1].id, "crate");
  EXPECT_FALSE(sim->things()[2].present);
  sim->run_until(1.5);
  EXPECT_EQ(sim->signal_values(), after);
  EXPECT_EQ(sim->body_pose(box).position.z, landed.position.z);
}

TEST(RuntimeThings, TwoRunsGiveTheSameSignalsBitForBit) {
  auto run = [] {
    auto sim = load();
    std::vector<double> log;
    for (int k = 0; k < 1500; ++k) {
      if (k == 200) sim->add_thing(box_at(0.02, 0, 0.4), "crate");  // onto the ball
      if (k == 900) sim->delete_thing(sim->things()[0].body);
      sim->step(1);
      const auto& v = sim->signal_values();
      log.insert(log.end(), v.begin(), v.end());
    }
    return log;
  };
  EXPECT_EQ(run(), run());
}

TEST(RuntimeThings, ADeletedSceneObstacleLetsGoOfWhatLiesOnItAndRaysPassThrough) {
  auto sim = load();
  const int box = sim->add_thing(box_at(3, 0, 0.6), "crate");
  sim->run_until(0.5);
  EXPECT_NEAR(sim->body_pose(box).position.z, 0.55, 2e-3) << "on the platform";
  const RayHit before = sim->cast_ray({3, 0.4, 0.2}, {0, -1, 0}, 2);
  ASSERT_TRUE(before.hit);
  EXPECT_NEAR(before.distance_m, 0.15, 1e-9);
  const Simulation::Snapshot snap = sim->save();
  sim->delete_obstacle(0);
  EXPECT_FALSE(sim->obstacle_present(0));
  EXPECT_FALSE(sim->cast_ray({3, 0.4, 0.2}, {0, -1, 0}, 2).hit);
  sim->run_until(1.5);
  EXPECT_NEAR(sim->body_pose(box).position.z, 0.05, 2e-3) << "fallen to the floor";
  sim->restore(snap);
  EXPECT_TRUE(sim->obstacle_present(0));
  sim->run_until(1.5);
  EXPECT_NEAR(sim->body_pose(box).position.z, 0.55, 2e-3) << "the snapshot's platform holds it";
  EXPECT_THROW(sim->delete_obstacle(1), Error);
}

TEST(RuntimeThings, AFixedThingHoldsWhatFallsOnItAndMovesOnlyWhenPlaced) {
  auto sim = load();
  ThingSpec shelf = box_at(-2, 0, 0.5);
  shelf.size_m = {0.4, 0.4, 0.02};
  shelf.fixed = true;
  const int fixed = sim->add_thing(shelf, "shelf");
  const int box = sim->add_thing(box_at(-2, 0, 0.8), "crate");
  sim->run_until(1.0);
  EXPECT_EQ(sim->body_pose(fixed).position.z, 0.5) << "it does not fall nor yield";
  EXPECT_NEAR(sim->body_pose(box).position.z, 0.51 + 0.05, 2e-3);
  Pose lower = sim->body_pose(fixed);
  lower.position.z = 0.3;
  sim->place_body(fixed, lower);
  sim->run_until(2.0);
  EXPECT_EQ(sim->body_pose(fixed).position.z, 0.3);
  EXPECT_NEAR(sim->body_pose(box).position.z, 0.31 + 0.05, 2e-3);
}

TEST(RuntimeThings, AResizedBodyCollidesWithItsNewSizeItsMassAsLoaded) {
  auto sim = load();
  const int ball = sim->things()[0].body;
  const double mass = 0.2;
  sim->run_until(0.3);
  EXPECT_NEAR(sim->body_pose(ball).position.z, 0.05, 1e-3);
  const Simulation::Snapshot snap = sim->save();
  sim->resize_body(ball, {0.1, 0.1, 0.1});
  EXPECT_EQ(*sim->resized(ball), (Vec3{0.1, 0.1, 0.1}));
  sim->run_until(1.5);
  EXPECT_NEAR(sim->body_pose(ball).position.z, 0.1, 2e-3) << "it rests on its new radius";
  const double weight = mass * kGravity_m_s2;
  EXPECT_NEAR(sim->signal(sim->signal_index("things/ball/contact_force")), weight, 0.02 * weight)
      << "its weight is the loaded mass's";
  const RayHit hit = sim->cast_ray({0, 0, 1}, {0, 0, -1}, 2);
  EXPECT_NEAR(hit.distance_m, 1 - 0.2, 2e-3) << "rays meet the new size";
  sim->restore(snap);
  EXPECT_FALSE(sim->resized(ball));
  sim->run_until(1.5);
  EXPECT_NEAR(sim->body_pose(ball).position.z, 0.05, 1e-3) << "the snapshot's size";
  sim->resize_body(ball, {0.1, 0.1, 0.1});
  sim->reset();
  EXPECT_FALSE(sim->resized(ball));
  EXPECT_THROW(sim->resize_body(ball, {-1, 1, 1}), Error);
  EXPECT_THROW(sim->resize_body(0, {1, 1, 1}), Error);
}

TEST(RuntimeThings, ASurfaceSetWhileRunningLetsABoxSlideDownTheRampItHeldTo) {
  auto sim = load();
  const double angle = 20 * kPi / 180;  // tan = 0.36, below the default 0.95
  ThingSpec ramp = box_at(-3, 0, 0.5);
  ramp.size_m = {1, 0.6, 0.02};
  ramp.fixed = true;
  ramp.pose.rotation = Mat3{
      {{std::cos(angle), 0, std::sin(angle)}, {0, 1, 0}, {-std::sin(angle), 0, std::cos(angle)}}};
  const int fixed = sim->add_thing(ramp, "ramp");
  ThingSpec crate = box_at(-3, 0, 0.6);
  crate.pose.rotation = ramp.pose.rotation;
  const int box = sim->add_thing(crate, "crate");
  sim->run_until(1.0);
  const Vec3 held = sim->body_pose(box).position;
  sim->run_until(1.5);
  EXPECT_LT(norm(sim->body_pose(box).position - held), 2e-3) << "static friction holds it";
  sim->set_body_surface(box, 0.1, -1);
  sim->set_body_surface(fixed, 0.1, -1);
  const double t0 = sim->time_s();
  sim->run_until(t0 + 0.3);
  // Sliding from rest: s = a t^2 / 2 with a = g (sin - mu cos).
  const double a = kGravity_m_s2 * (std::sin(angle) - 0.1 * std::cos(angle));
  EXPECT_NEAR(norm(sim->body_pose(box).position - held), 0.5 * a * 0.09, 0.1 * 0.5 * a * 0.09);
  sim->reset();
  EXPECT_FALSE(sim->things()[1].present);
}

TEST(RuntimeThings, PartsRunningInParallelGiveTheSerialRunBitForBit) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one hardware thread";
  auto run = [](int threads) {
    SimulationOptions o;
    o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
    o.threads = threads;
    o.runtime_things = 4;
    auto sim = Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "bench/peers/scenes/robots_16", o);
    sim->run_until(0.2);
    const int box = sim->add_thing(box_at(0.3, 0, 0.5), "crate");
    ThingSpec ball = box_at(1, 1, 0.3);
    ball.shape = ThingShape::sphere;
    sim->add_thing(ball, "ball");
    sim->run_until(0.6);
    sim->delete_thing(box);
    sim->run_until(1.0);
    return sim->signal_values();
  };
  EXPECT_EQ(run(1), run(2));
}

TEST(RuntimeThings, BadRequestsAreRefusedNamingTheThingAndTheValue) {
  auto sim = load(1);
  auto message = [&](const ThingSpec& spec) {
    try {
      sim->add_thing(spec, "crate");
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::usage);
      return std::string(e.what());
    }
    return std::string("no error");
  };
  ThingSpec s = box_at(0, 0, 1);
  s.mass_kg = 0;
  EXPECT_NE(message(s).find("crate': mass must be positive, got 0"), std::string::npos)
      << message(s);
  s = box_at(0, 0, 1);
  s.size_m.y = -1;
  EXPECT_NE(message(s).find("size must be positive"), std::string::npos) << message(s);
  s = box_at(0, 0, std::nan(""));
  EXPECT_NE(message(s).find("not finite"), std::string::npos) << message(s);
  EXPECT_NO_THROW(sim->add_thing(box_at(0, 0, 1), "first"));
  EXPECT_NE(message(box_at(0, 0, 1)).find("all 1 spare bodies hold things"), std::string::npos)
      << message(box_at(0, 0, 1));
  EXPECT_THROW(sim->delete_thing(0), Error);
  EXPECT_THROW(sim->delete_thing(100000), Error);
}

}  // namespace
}  // namespace s2sim
