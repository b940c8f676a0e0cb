// The touch sensor against a hand-made contact list (a fake ConfigureContext and WorldView
// drive the component directly), then on a box resting on the floor (the contact layer).
#include "kinds.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace s2sim::sensors {
namespace {

class FakeParams : public Params {
 public:
  bool region = false;
  bool has(std::string_view) const override { return false; }
  bool has_element(std::string_view p) const override { return region && p == "region"; }
  double number(std::string_view, Range) const override { return 0; }
  double number(std::string_view p, double fallback, Range) const override {
    return p == "threshold.value" ? 5.0 : fallback;
  }
  std::int64_t integer(std::string_view) const override { return 0; }
  std::int64_t integer(std::string_view, std::int64_t f) const override { return f; }
  bool boolean(std::string_view, bool f) const override { return f; }
  std::string text(std::string_view) const override { return {}; }
  std::string text(std::string_view, std::string_view f) const override { return std::string(f); }
  Vec3 vec3(std::string_view, Vec3) const override { return {0.1, 0.1, 0.1}; }
  std::string location() const override { return "robot.xml: robot/sensors/touch"; }
  std::string choice(std::string_view, std::initializer_list<std::string_view>,
                     std::string_view f) const override {
    return std::string(f);
  }
};

class FakeConfigure : public ConfigureContext {
 public:
  FakeParams params_;
  SensorSpec spec_;
  int signals = 0;
  const Params& params() const override { return params_; }
  std::string_view id() const override { return "bumper"; }
  std::string_view signal_prefix() const override { return "robots/r/sensors/bumper"; }
  std::string_view robot() const override { return "r"; }
  double tick_s() const override { return 0.001; }
  BodyHandle body(std::string_view) override { return {1}; }
  double body_mass_kg(BodyHandle) const override { return 1; }
  AxisHandle axis(std::string_view) override { return {}; }
  bool axis_is_linear(AxisHandle) const override { return false; }
  std::string axis_prefix(AxisHandle) const override { return {}; }
  SignalHandle declare_signal(std::string_view, std::string_view) override { return {signals++}; }
  SignalHandle declare_signal_at(std::string_view, std::string_view) override {
    return {signals++};
  }
  InputHandle declare_input(std::string_view, std::string_view, double, const Range&) override {
    return {0};
  }
  InputHandle declare_input_at(std::string_view, std::string_view, double, const Range&) override {
    return {0};
  }
  StateHandle declare_state(std::string_view, int count, double) override { return {0, count}; }
  void set_schedule(Stage, double, double) override {}
  const SensorSpec* sensor_spec() const override { return &spec_; }
  std::vector<FloorPolygon> floor_polygons() const override { return {}; }
  int body_count() const override { return 3; }
  std::string body_id(BodyHandle) const override { return {}; }
  SignalHandle published_signal(std::string_view) const override { return {}; }
  JointHandle joint(std::string_view) override { return {}; }
  BodyHandle joint_body(JointHandle, int) const override { return {}; }
  void add_axis_inertia(AxisHandle, double) override {}
  void warn(std::string_view) override {}
  std::vector<NamedUnit> signal_names(std::string_view) const override { return {}; }
  std::vector<NamedUnit> input_names(std::string_view) const override { return {}; }
  InputHandle input(std::string_view) override { return {}; }
  SignalReader signal_reader(std::string_view) const override { return {}; }
  ImageHandle declare_image(std::string_view, int, int, PixelFormat) override { return {}; }
  ImageHandle image(std::string_view) const override { return {}; }
};

struct World {
  std::vector<Pose> poses = std::vector<Pose>(3);
  std::vector<Twist> twists = std::vector<Twist>(3);
  std::vector<double> signals = std::vector<double>(4, -9);
  std::vector<std::uint64_t> random = std::vector<std::uint64_t>(4, 1);
  std::vector<ContactInfo> contacts;
  std::int32_t count = 0;
  detail::WorldView view;
  World() {
    view.body_count = static_cast<std::int32_t>(poses.size());
    view.body_pose = poses.data();
    view.body_twist = twists.data();
    view.signal_count = static_cast<std::int32_t>(signals.size());
    view.signals = signals.data();
    view.random_state = random.data();
    view.tick_s = 0.001;
  }
  void set(std::vector<ContactInfo> c) {
    contacts = std::move(c);
    count = static_cast<std::int32_t>(contacts.size());
    view.contacts = contacts.data();
    view.contact_count = &count;
  }
};

ContactInfo contact(int a, int b, Vec3 point, Vec3 force) {
  ContactInfo c;
  c.body_a = {a};
  c.body_b = {b};
  c.point_m = point;
  c.force_N = force;
  return c;
}

TEST(Touch, SumsTheContactForcesOnItsBodyAgainstItsThreshold) {
  FakeConfigure cfg;
  cfg.spec_.body = {1};
  Touch touch;
  touch.configure(cfg);
  World w;
  w.poses[1].position = {1, 0, 0};
  StepContext ctx(&w.view, 0, 10);
  w.set({});
  touch.update(ctx);
  EXPECT_EQ(w.signals[0], 0.0);  // value
  EXPECT_EQ(w.signals[1], 0.0);  // force
  // A contact between two other bodies does not count; one on body 1 (either side) does.
  w.set({contact(2, 0, {5, 0, 0}, {0, 0, 50}), contact(1, 0, {1, 0, 0}, {0, 0, 3})});
  touch.update(ctx);
  EXPECT_EQ(w.signals[1], 3.0);
  EXPECT_EQ(w.signals[0], 0.0);  // under the 5 N threshold
  w.set({contact(1, 0, {1, 0, 0}, {0, 0, 3}), contact(2, 1, {1.2, 0, 0}, {0, 4, 0})});
  touch.update(ctx);
  EXPECT_EQ(w.signals[1], 7.0);
  EXPECT_EQ(w.signals[0], 1.0);
}

TEST(Touch, ARegionKeepsOnlyTheContactsNearTheSensor) {
  FakeConfigure cfg;
  cfg.spec_.body = {1};
  cfg.spec_.pose.position = {0.2, 0, 0};  // sensor at the front of the body
  cfg.params_.region = true;              // a 0.1 m cube around it
  Touch touch;
  touch.configure(cfg);
  World w;
  w.poses[1].position = {1, 0, 0};
  StepContext ctx(&w.view, 0, 10);
  w.set({contact(1, 0, {1.22, 0.03, 0}, {6, 0, 0}), contact(1, 0, {0.8, 0, 0}, {0, 0, 9})});
  touch.update(ctx);
  EXPECT_EQ(w.signals[1], 6.0);  // the rear contact is outside the region
  EXPECT_EQ(w.signals[0], 1.0);
}

TEST(Touch, MustBeAttachedToABody) {
  FakeConfigure cfg;
  cfg.spec_.body = {0};
  Touch touch;
  EXPECT_THROW(touch.configure(cfg), Error);
}

}  // namespace
}  // namespace s2sim::sensors

#include <s2sim/kernel/simulation.hpp>

#include <filesystem>

namespace s2sim::sensors {
namespace {

// With the contact layer: a box at rest on the floor presses with its weight on the sensor
// under it; the one on top feels nothing.
TEST(Touch, ABoxOnTheFloorFeelsItsWeightUnderneathAndNothingOnTop) {
  SimulationOptions o;
  o.plugin_path = {std::filesystem::path(S2SIM_PLUGIN_DIR)};
  auto sim = Simulation::load(
      std::filesystem::path(S2SIM_SOURCE_DIR) / "tests/plugins/sensors/fixtures/touch_floor", o);
  sim->run_until(1.0);
  EXPECT_EQ(sim->signal("robots/box/sensors/under/value"), 1.0);
  EXPECT_NEAR(sim->signal("robots/box/sensors/under/force"), 2 * kGravity_m_s2,
              0.01 * 2 * kGravity_m_s2);
  EXPECT_EQ(sim->signal("robots/box/sensors/top/value"), 0.0);
  EXPECT_EQ(sim->signal("robots/box/sensors/top/force"), 0.0);
}

}  // namespace
}  // namespace s2sim::sensors
