#pragma once
// The peer benchmark's scenes as numbers, for the engines that are not given a file: the
// differential robot of scenes/diffbot.xml (ODE), the grid the robots stand on, the
// articulated models' tables and the pile's bodies (read from the files that
// make-peer-scenes.py writes). Keep in step with make-peer-scenes.py.

#include "engine.hpp"

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace peers {

using Vec3d = std::array<double, 3>;

/// scenes/diffbot.xml in the robot frame (the robot's origin on the floor, x forward).
namespace diffbot {
inline constexpr double kBrickMass_kg = 0.31;
inline constexpr Vec3d kBrickSize_m{0.112, 0.072, 0.040};
inline constexpr Vec3d kBrickCentre_m{-0.03, 0.0, 0.07};
inline constexpr double kHousingMass_kg = 0.08;
inline constexpr Vec3d kHousingSize_m{0.100, 0.035, 0.040};
inline constexpr Vec3d kHousingCentre_m{-0.02, 0.0175, 0.03};  ///< left; the right one at −y
inline constexpr double kCasterRadius_m = 0.014;
inline constexpr Vec3d kCasterCentre_m{-0.09, 0.0, 0.014};
inline constexpr double kWheelMass_kg = 0.02;
inline constexpr double kWheelRadius_m = 0.028;
inline constexpr double kWheelWidth_m = 0.026;
inline constexpr double kHalfTrack_m = 0.06;
inline constexpr double kWheelMu = 1.0;
inline constexpr double kMotorRi_ohm = 7.6;
inline constexpr double kMotorKi_Nm_A = 0.4908;
inline constexpr double kMotorImax_A = 2.0;
inline constexpr double kFrictionBv_Nms = 1.92e-3;
inline constexpr double kFrictionFc_Nm = 3.558e-4;
inline constexpr double kRotorJ_kgm2 = 1e-5;
/// The chassis's massive boxes (the brick and the two motor housings; the caster is massless).
struct ChassisPart {
  double mass_kg;
  Vec3d size_m, centre_m;
};
inline constexpr std::array<ChassisPart, 3> kChassisParts = {
    {{kBrickMass_kg, kBrickSize_m, kBrickCentre_m},
     {kHousingMass_kg, kHousingSize_m, kHousingCentre_m},
     {kHousingMass_kg,
      kHousingSize_m,
      {kHousingCentre_m[0], -kHousingCentre_m[1], kHousingCentre_m[2]}}}};
}  // namespace diffbot

/// Robot `index` of `count` stands at (x, y) on a grid 1.5 m apart (make-peer-scenes.py).
std::array<double, 2> grid_position(int index, int count);

/// S2Sim's default friction when neither surface sets one (the pile's).
inline constexpr double kDefaultMu = 0.95;
/// Contacts ring at 0.3 rad per 1 ms step, critically damped (docs/models/contact.md).
inline constexpr double kContactOmega_rad_s = 300.0;

/// A box whose frame is aligned with the world at the start, at its centre of mass.
struct BoxBody {
  std::string name;
  double mass_kg = 0;
  Vec3d size_m{}, centre_m{};
};

/// A hinge with its DC motor (ki = 0: passive), as make-peer-scenes.py writes it.
struct HingeSpec {
  std::string name;
  int child = -1, parent = -1;  ///< body indices, −1 the world
  Vec3d axis{}, anchor_m{};
  double ki_Nm_A = 0, ri_ohm = 1, imax_A = 0, bv_Nms = 0, fc_Nm = 0, rotor_J_kgm2 = 0, volts = 0;
};

struct ArticulatedModel {
  std::vector<BoxBody> bodies;
  std::vector<HingeSpec> hinges;
};

/// Reads a model.txt of make-peer-scenes.py; throws std::runtime_error naming file and line.
ArticulatedModel read_articulated(const std::filesystem::path& table);

/// A spanning tree of a model's hinges, parents before children: a hinge whose child already
/// has its joint closes a loop. Without a hinge to the world, body 0 floats (the humanoid).
struct SpanningTree {
  bool fixed = false;         ///< some hinge joins the world
  std::vector<int> order;     ///< the bodies a tree hinge joins, parents first
  std::vector<int> joint_of;  ///< each body's tree hinge; −1 for the floating body 0
};
/// Throws std::runtime_error, naming `who`, when a body is not jointed to the tree.
SpanningTree spanning_tree(const ArticulatedModel& model, const std::string& who);

/// A free body of the pile: a box (half sizes) or a sphere (radius in half_size_m[0]).
struct PileBody {
  std::string name;
  bool sphere = false;
  double mass_kg = 0;
  Vec3d half_size_m{}, position_m{};
  std::array<double, 4> quat_wxyz{1, 0, 0, 0};
};

/// The bodies of bench/peers/mjcf/pile.xml (one `<body>` a line, as make-peer-scenes.py writes
/// them); throws std::runtime_error naming file and line.
std::vector<PileBody> read_pile(const std::filesystem::path& mjcf);

/// What an engine builds for `scene`, from the files every engine reads: each robot at its
/// place on the grid, each pile body, or the articulated model (humanoid, arm).
template <class AddRobot, class AddPileBody, class AddArticulated>
void add_scene_bodies(const SceneSpec& scene, AddRobot&& add_robot, AddPileBody&& add_pile_body,
                      AddArticulated&& add_articulated) {
  switch (scene.kind) {
    case SceneSpec::Kind::robots:
      for (int i = 0; i < scene.robot_count; ++i)
        add_robot(grid_position(i, scene.robot_count));
      break;
    case SceneSpec::Kind::pile:
      for (const PileBody& b : read_pile(scene.mjcf()))
        add_pile_body(b);
      break;
    case SceneSpec::Kind::humanoid:
    case SceneSpec::Kind::arm_loop:
      add_articulated(read_articulated(scene.ode_table()));
      break;
  }
}

}  // namespace peers
