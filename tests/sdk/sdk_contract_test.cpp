// What the SDK promises a plugin, checked without a kernel: every StepContext accessor checks
// its handle, state comes as a span with its size, and the sensor rules and defaults are the
// ones the scene loader uses.
#include <s2sim/kernel/scene.hpp>
#include <s2sim/sdk.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <type_traits>
#include <vector>

namespace s2sim {
namespace {

using ::testing::HasSubstr;

// Two bodies (the world and one), one axis, one joint, one input, one signal, three doubles
// of state.
struct World {
  std::vector<Pose> poses = std::vector<Pose>(2);
  std::vector<Twist> twists = std::vector<Twist>(2);
  std::vector<Wrench> wrenches = std::vector<Wrench>(2);
  std::vector<double> axis_values = std::vector<double>(1, 0.5);
  std::vector<double> axis_forces = std::vector<double>(1);
  std::vector<Wrench> reactions = std::vector<Wrench>(1);
  std::vector<double> inputs = std::vector<double>(1, 2.0);
  std::vector<double> signals = std::vector<double>(1, 3.0);
  std::vector<double> state = {4.0, 5.0, 6.0};
  std::vector<std::uint64_t> random = std::vector<std::uint64_t>(4, 1);
  std::int32_t contact_count = 0;
  detail::WorldView view;
  World() {
    view.body_count = 2;
    view.body_pose = poses.data();
    view.body_twist = twists.data();
    view.body_wrench = wrenches.data();
    view.axis_count = 1;
    view.axis_position = axis_values.data();
    view.axis_velocity = axis_values.data();
    view.axis_force = axis_forces.data();
    view.joint_count = 1;
    view.joint_reaction = reactions.data();
    view.input_count = 1;
    view.inputs = inputs.data();
    view.signal_count = 1;
    view.signals = signals.data();
    view.state_count = 3;
    view.state = state.data();
    view.random_state = random.data();
    view.contact_count = &contact_count;
  }
};

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::runtime);
    return e.message();
  }
  ADD_FAILURE() << "nothing was thrown";
  return {};
}

TEST(StepContextHandles, ValidHandlesReadTheKernelsArrays) {
  World w;
  StepContext ctx(&w.view, 0, 1);
  EXPECT_EQ(&ctx.body_pose(BodyHandle{1}), &w.poses[1]);
  EXPECT_EQ(ctx.axis_position(AxisHandle{0}), 0.5);
  EXPECT_EQ(ctx.input(InputHandle{0}), 2.0);
  EXPECT_EQ(ctx.signal(SignalHandle{0}), 3.0);
  ctx.apply_axis_force(AxisHandle{0}, 1.5);
  EXPECT_EQ(w.axis_forces[0], 1.5);
}

TEST(StepContextHandles, AnInvalidHandleThrowsNamingTheAccessorTheKindAndTheIndex) {
  World w;
  StepContext ctx(&w.view, 0, 1);
  EXPECT_THAT(error_of([&] { ctx.body_pose(BodyHandle{}); }),
              HasSubstr("StepContext::body_pose: invalid body handle (index -1, valid 0 to 1)"));
  EXPECT_THAT(error_of([&] { ctx.body_twist(BodyHandle{2}); }),
              HasSubstr("StepContext::body_twist: invalid body handle (index 2, valid 0 to 1)"));
  EXPECT_THAT(error_of([&] { ctx.apply_torque(BodyHandle{}, Vec3{}); }),
              HasSubstr("apply_torque: invalid body handle"));
  EXPECT_THAT(error_of([&] { ctx.axis_velocity(AxisHandle{1}); }),
              HasSubstr("axis_velocity: invalid axis handle (index 1, valid 0 to 0)"));
  EXPECT_THAT(error_of([&] { ctx.apply_axis_drive(AxisHandle{}, 1, 0); }),
              HasSubstr("apply_axis_drive: invalid axis handle"));
  EXPECT_THAT(error_of([&] { ctx.joint_reaction(JointHandle{}); }),
              HasSubstr("joint_reaction: invalid joint handle"));
  EXPECT_THAT(error_of([&] { ctx.input(InputHandle{}); }),
              HasSubstr("input: invalid input handle"));
  EXPECT_THAT(error_of([&] { ctx.publish(SignalHandle{5}, 1); }),
              HasSubstr("publish: invalid signal handle (index 5"));
  EXPECT_THAT(error_of([&] { ctx.signal(SignalReader{}); }),
              HasSubstr("signal: invalid signal reader handle"));
  EXPECT_THAT(error_of([&] { ctx.contact(0); }),
              HasSubstr("contact: invalid contact handle (index 0, none exist)"));
  EXPECT_THAT(error_of([&] {
                ctx.state(StateHandle{2, 2});
              }),
              HasSubstr("state: invalid state handle (index 2, valid 0 to 2)"));
  EXPECT_THAT(error_of([&] { ctx.state(StateHandle{}); }), HasSubstr("state: invalid state"));
}

TEST(StepContextState, ComesAsASpanWithItsSize) {
  World w;
  StepContext ctx(&w.view, 0, 1);
  const Span<double> s = ctx.state(StateHandle{1, 2});
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.data(), w.state.data() + 1);
  EXPECT_EQ(s[0], 5.0);
  s[1] = 7.0;
  EXPECT_EQ(w.state[2], 7.0);
  double sum = 0;
  for (double v : s)
    sum += v;
  EXPECT_EQ(sum, 12.0);
}

TEST(SensorRules, TheLoaderAndThePluginsShareOneBeamNoiseAndPeriod) {
  static_assert(std::is_same_v<scene::Beam, SensorBeam>);
  static_assert(std::is_same_v<scene::Noise, SensorNoise>);
  static_assert(std::is_same_v<scene::SolenoidForce, SolenoidForce>);
  EXPECT_EQ(scene::Sensor{}.period_s, SensorSpec{}.period_s);
  EXPECT_EQ(SensorBeam{}.angle_rad, 0.5235987755982988);  // 30 degrees, to the last bit
}

TEST(SensorRules, NameTheAttributeThatBreaksOne) {
  EXPECT_FALSE(check_beam(SensorBeam{}));
  SensorBeam b;
  b.length_m = -0.3;
  EXPECT_STREQ(check_beam(b).attribute, "length");
  EXPECT_EQ(check_beam(b).message, "must be > 0 m, got -0.3");
  b = SensorBeam{};
  b.angle_rad = 400 * kPi / 180;
  EXPECT_STREQ(check_beam(b).attribute, "angle");
  b = SensorBeam{};
  b.rays = kMaxBeamRays + 1;
  EXPECT_EQ(check_beam(b).message, "must be an integer from 1 to 100000, got 100001");
  SensorNoise n;
  n.stdev = -1;
  EXPECT_FALSE(check_noise(n));  // no <noise> element: not read
  n.present = true;
  EXPECT_STREQ(check_noise(n).attribute, "stdev");
  EXPECT_STREQ(check_sensor_period(0).attribute, "value");
  EXPECT_FALSE(check_sensor_period(kDefaultSensorPeriod_s));
}

}  // namespace
}  // namespace s2sim
