// Joint couplings (URDF <mimic>, MJCF's linear joint equality) held exactly: a gripper's
// fingers follow their leader on both dynamics paths, coupled pendulums swing with the period
// of one, a flywheel geared 2:1 adds 4·I2; located errors (docs/models/import.md,
// docs/models/multibody.md "Coupled joints").

#include <s2sim/kernel/simulation.hpp>

#include "common/edited_copy.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

const fs::path kCoupled = fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/scene/fixtures/import/coupled";

SimulationOptions options(bool simbody) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  o.simbody_dynamics_only = simbody;
  return o;
}

std::unique_ptr<Simulation> load(const fs::path& file, bool simbody) {
  auto sim = Simulation::load(file, options(simbody));
  EXPECT_EQ(sim->dynamics(), simbody ? "simbody" : "tree") << file.filename();
  return sim;
}

std::string all_warnings(const Simulation& sim) {
  std::string text;
  for (const std::string& w : sim.warnings())
    text += w + "\n";
  return text;
}

TEST(JointCoupling, GripperFingersFollowTheirLeaderExactlyOnBothDynamicsPaths) {
  // The left finger pushed by 4 mN for 1 s, then pulled by 8 mN for 1 s: the three fingers
  // (0.05 + 0.08 + 0.03 kg) move as one mass along the leader's coordinate.
  constexpr double mass_kg = 0.16, push_n = 0.004, pull_n = -0.008, offset_m = 0.01;
  for (const bool simbody : {false, true}) {
    auto sim = load(kCoupled / "gripper.urdf", simbody);
    EXPECT_THAT(all_warnings(*sim), Not(HasSubstr("mimic")));
    const std::string axes = "robots/gripper/axes/";
    const std::size_t left = sim->signal_index(axes + "left_finger_joint/pos");
    const std::size_t right = sim->signal_index(axes + "right_finger_joint/pos");
    const std::size_t thumb = sim->signal_index(axes + "thumb_joint/pos");
    EXPECT_FALSE(sim->find_signal(axes + "right_finger_joint/effort_applied").has_value());
    EXPECT_NEAR(sim->signal(thumb), offset_m, 1e-12) << "the thumb starts at its offset";
    double worst = 0, at_1s = 0;
    for (int tick = 0; tick < 2000; ++tick) {
      sim->set_input(axes + "left_finger_joint/effort", tick < 1000 ? push_n : pull_n);
      sim->step(1);
      const double l = sim->signal(left);
      worst = std::max(
          {worst, std::abs(sim->signal(right) + l), std::abs(sim->signal(thumb) + l - offset_m)});
      if (tick == 999) at_1s = l;
    }
    // Leapfrog is exact under the constant push (the pull's switch falls between half steps).
    const double expected_1s = 0.5 * push_n / mass_kg;
    std::printf(
        "%s: followers off their leader by at most %.3g m over 2 s; leader at 1 s %.12f "
        "m (m = 0.16 kg: %.12f)\n",
        simbody ? "simbody" : "tree", worst, at_1s, expected_1s);
    EXPECT_LT(worst, 1e-9) << (simbody ? "simbody" : "tree");
    EXPECT_NEAR(at_1s, expected_1s, 1e-6 * expected_1s);
    EXPECT_LT(sim->signal(left), at_1s + 0.025) << "the pull did not slow the fingers";
  }
}

/// The hinge's value every tick for `seconds`, and the largest |follower − leader|.
std::vector<double> swing(const fs::path& file, const std::string& robot, bool simbody,
                          double seconds, double* worst_follower) {
  auto sim = load(file, simbody);
  const std::size_t first = sim->signal_index("robots/" + robot + "/axes/first_hinge/pos");
  const auto second = sim->find_signal("robots/" + robot + "/axes/second_hinge/pos");
  std::vector<double> out;
  const auto ticks = static_cast<int>(std::lround(seconds / sim->tick_s()));
  for (int t = 0; t < ticks; ++t) {
    sim->step(1);
    out.push_back(sim->signal(first));
    if (second && worst_follower)
      *worst_follower = std::max(*worst_follower, std::abs(sim->signal(*second) - out.back()));
  }
  return out;
}

/// The mean period of a swing about `mid`, from its first to its last upward crossing (linear
/// interpolation between ticks of `h` seconds).
double period_s(const std::vector<double>& theta, double mid, double h) {
  std::vector<double> crossings;
  for (std::size_t k = 1; k < theta.size(); ++k)
    if (theta[k - 1] < mid && theta[k] >= mid)
      crossings.push_back(
          h * (static_cast<double>(k) + (mid - theta[k - 1]) / (theta[k] - theta[k - 1])));
  if (crossings.size() < 2) return 0;
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

TEST(JointCoupling, TwoPendulumsCoupledOneToOneSwingWithThePeriodOfOne) {
  // The coupling adds both inertias and both gravity torques: I θ'' = −m g d sin θ for each,
  // so the pair swings as one pendulum does, T = 4·√(I/(m g d))·K(sin(θ₀/2)), θ₀ = 0.6 rad.
  constexpr double h = 1e-3, seconds = 4.0, theta0 = 0.6;
  const double I = 0.021041666666666667 + 0.25 * 0.25, mgd = 9.81 * 0.25;
  double a = 1, b = std::sqrt(1 - std::pow(std::sin(theta0 / 2), 2));  // K by the AGM
  for (int k = 0; k < 8; ++k) {
    const double next = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = next;
  }
  const double analytic = 4 * std::sqrt(I / mgd) * (kPi / (2 * a));
  for (const bool simbody : {false, true}) {
    double worst_follower = 0;
    const auto lone = swing(kCoupled / "lone_pendulum.urdf", "lone", simbody, seconds, nullptr);
    const auto twins =
        swing(kCoupled / "twin_pendulums.urdf", "twins", simbody, seconds, &worst_follower);
    ASSERT_EQ(lone.size(), twins.size());
    double worst = 0;
    for (std::size_t k = 0; k < lone.size(); ++k)
      worst = std::max(worst, std::abs(lone[k] - twins[k]));
    const double mid = -theta0;  // the axis starts at 0, tilted 0.6 rad: it swings about −0.6
    ASSERT_LT(*std::min_element(twins.begin(), twins.end()), mid) << "it never swung through";
    const double T_lone = period_s(lone, mid, h), T_twins = period_s(twins, mid, h);
    std::printf(
        "%s: period coupled %.9f s, alone %.9f s, analytic %.9f s; largest angle "
        "difference %.3g rad, follower off its leader by %.3g rad\n",
        simbody ? "simbody" : "tree", T_twins, T_lone, analytic, worst, worst_follower);
    EXPECT_NEAR(T_twins, T_lone, 1e-6 * T_lone);
    EXPECT_NEAR(T_twins, analytic, 1e-5 * analytic);
    EXPECT_LT(worst, 1e-6);
    EXPECT_LT(worst_follower, 1e-9);
  }
}

TEST(JointCoupling, AFlywheelTurningTwiceAsFastAddsFourTimesItsInertia) {
  // τ = 0.02 N·m on the disk: θ = ½·τ/(I1 + 4·I2)·t² = 1 rad at 2 s (leapfrog is exact under
  // a constant acceleration); without the 4 (I1 + I2 = 0.025) it would be 1.6 rad. At 3 s the
  // disk is at 2.25 rad and the flywheel, coupled through its unwrapped angle, at 4.5 rad (a
  // tree hinge's pos signal is that angle, not wrapped).
  constexpr double torque = 0.02, inertia = 0.02 + 4 * 0.005;
  const double expected_2s = 0.5 * torque / inertia * 4, expected_3s = 0.5 * torque / inertia * 9;
  for (const bool simbody : {false, true}) {
    auto sim = load(kCoupled / "flywheel.urdf", simbody);
    const std::size_t disk = sim->signal_index("robots/flywheel/axes/disk_hinge/pos");
    const std::size_t wheel = sim->signal_index("robots/flywheel/axes/wheel_hinge/pos");
    sim->set_input("robots/flywheel/axes/disk_hinge/effort", torque);
    double worst = 0, at_2s = 0;
    for (int tick = 0; tick < 3000; ++tick) {
      sim->step(1);
      worst = std::max(worst, std::abs(sim->signal(wheel) - 2 * sim->signal(disk)));
      if (tick == 1999) at_2s = sim->signal(disk);
    }
    std::printf(
        "%s: disk at 2 s %.12f rad (I1 + 4 I2: %.12f), at 3 s %.12f (%.12f); flywheel "
        "at %.12f rad, off 2x the disk by %.3g rad\n",
        simbody ? "simbody" : "tree", at_2s, expected_2s, sim->signal(disk), expected_3s,
        sim->signal(wheel), worst);
    EXPECT_NEAR(at_2s, expected_2s, 1e-6 * expected_2s);
    EXPECT_NEAR(sim->signal(disk), expected_3s, 1e-6 * expected_3s);
    EXPECT_NEAR(sim->signal(wheel), 2 * expected_3s, 1e-6) << "not the unwrapped angle";
    EXPECT_LT(worst, 1e-9);
  }
}

TEST(JointCoupling, ALinearMjcfJointEqualityIsHeldExactly) {
  // 2 mN·m on the leader (0.002 + 1·0.1² kg·m² about its hinge) turning the follower (0.001 +
  // 0.5·0.1²) at half its rate: θ = ½·τ/(I_l + 0.25·I_f)·t².
  constexpr double torque = 0.002, inertia = 0.012 + 0.25 * 0.006;
  const double expected = 0.5 * torque / inertia;  // at 1 s
  for (const bool simbody : {false, true}) {
    auto sim = load(kCoupled / "linear_equality_mjcf.xml", simbody);
    EXPECT_THAT(all_warnings(*sim), Not(HasSubstr("equality")));
    ASSERT_EQ(sim->scene().couplings.size(), 1u);
    const std::string axes = "robots/coupled_hinges/axes/";
    const std::size_t leader = sim->signal_index(axes + "leader/pos");
    const std::size_t follower = sim->signal_index(axes + "follower/pos");
    EXPECT_NEAR(sim->signal(follower), 0.1, 1e-12);
    sim->set_input(axes + "leader/effort", torque);
    double worst = 0;
    for (int tick = 0; tick < 1000; ++tick) {
      sim->step(1);
      worst = std::max(worst, std::abs(sim->signal(follower) - (0.1 - 0.5 * sim->signal(leader))));
    }
    std::printf(
        "%s: leader at 1 s %.12f rad (%.12f), follower off 0.1 - 0.5 leader by %.3g "
        "rad\n",
        simbody ? "simbody" : "tree", sim->signal(leader), expected, worst);
    EXPECT_NEAR(sim->signal(leader), expected, 1e-6 * expected);
    EXPECT_LT(worst, 1e-9);
  }
}

TEST(JointCoupling, ANonlinearMjcfJointEqualityIsWarnedAndNotApplied) {
  const fs::path file =
      test::edited_copy(kCoupled, "linear_equality_mjcf.xml", R"(polycoef="0.1 -0.5 0 0 0")",
                        R"(polycoef="0.1 -0.5 0.2 0 0")") /
      "linear_equality_mjcf.xml";
  auto sim = Simulation::load(file, options(false));
  EXPECT_TRUE(sim->scene().couplings.empty());
  EXPECT_THAT(all_warnings(*sim),
              HasSubstr("equality 'couple' on joint 'follower' is not applied (a polycoef beyond "
                        "the linear term)"));
}

/// The error `file` raises when loaded.
Error load_error(const fs::path& file) {
  try {
    Simulation::load(file, options(false));
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << file << " loaded";
  return Error(ErrorKind::runtime, Location{}, "none");
}

fs::path edited(const std::string& file, const std::string& from, const std::string& to) {
  return test::edited_copy(kCoupled, file, from, to) / file;
}

TEST(JointCoupling, ATransmissionOnAMimicJointIsWarnedAndGivesNoInput) {
  const fs::path file = edited("gripper.urdf", R"(</transmission>)", R"(</transmission>
  <transmission name="thumb_transmission">
    <joint name="thumb_joint"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
  </transmission>)");
  auto sim = Simulation::load(file, options(false));
  EXPECT_THAT(all_warnings(*sim),
              HasSubstr("robot/joint[4]: joint 'thumb_joint' mimics 'left_finger_joint': its "
                        "transmission is not applied"));
  EXPECT_FALSE(sim->find_signal("robots/gripper/axes/thumb_joint/effort_applied").has_value());
  EXPECT_TRUE(sim->find_signal("robots/gripper/axes/left_finger_joint/effort_applied").has_value());
}

TEST(JointCoupling, AMimicOfAMissingJointIsALocatedError) {
  const Error e =
      load_error(edited("gripper.urdf", R"(<mimic joint="left_finger_joint" multiplier="-1"/>)",
                        R"(<mimic joint="index_finger_joint" multiplier="-1"/>)"));
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_EQ(e.where().file, "gripper.urdf");
  EXPECT_EQ(e.where().element, "robot/joint[3]/mimic");
  EXPECT_EQ(e.where().attribute, "joint");
  EXPECT_THAT(e.message(), HasSubstr("joint 'right_finger_joint' follows 'index_finger_joint': "
                                     "joint 'index_finger_joint' is not in the model"));
}

TEST(JointCoupling, AFollowerCoupledTwiceIsALocatedError) {
  const Error e = load_error(
      edited("linear_equality_mjcf.xml", R"(</equality>)",
             R"(<joint name="again" joint1="follower" joint2="leader" polycoef="0 2 0 0 0"/>
  </equality>)"));
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_EQ(e.where().file, "linear_equality_mjcf.xml");
  EXPECT_EQ(e.where().element, "equality 'again'");
  EXPECT_EQ(e.where().attribute, "polycoef");
  EXPECT_THAT(e.message(),
              HasSubstr("joint 'follower' already follows 'leader'; it cannot also follow"));
}

TEST(JointCoupling, ACycleOfMimicsIsALocatedError) {
  const Error e = load_error(edited("gripper.urdf",
                                    R"(<limit lower="-0.05" upper="0.05" effort="5" velocity="1"/>
  </joint>
  <joint name="right_finger_joint")",
                                    R"(<limit lower="-0.05" upper="0.05" effort="5" velocity="1"/>
    <mimic joint="thumb_joint"/>
  </joint>
  <joint name="right_finger_joint")"));
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_EQ(e.where().element, "robot/joint[2]/mimic");
  EXPECT_THAT(e.message(),
              HasSubstr("joint 'left_finger_joint' follows itself through a cycle of couplings"));
}

TEST(JointCoupling, AMimicOnAFixedJointIsALocatedError) {
  const Error e =
      load_error(edited("gripper.urdf", R"(<origin xyz="0 0 0.5"/>)",
                        R"(<origin xyz="0 0 0.5"/><mimic joint="left_finger_joint"/>)"));
  EXPECT_EQ(e.kind(), ErrorKind::scene);
  EXPECT_EQ(e.where().element, "robot/joint[1]/mimic");
  EXPECT_THAT(e.message(), HasSubstr("joint 'palm_joint'"));
  EXPECT_THAT(e.message(), HasSubstr("only hinges and sliders can be coupled"));
}

}  // namespace
}  // namespace s2sim
