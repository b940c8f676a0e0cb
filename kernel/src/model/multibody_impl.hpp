#pragma once
/// \file
/// Multibody's Simbody objects and the helpers shared by model/'s translation units. Only
/// kernel/src/model/ includes this header (it pulls in Simbody: C++17, see kernel/CMakeLists).

#include "model/loose_bodies.hpp"
#include "model/multibody.hpp"

#include <Simbody.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace s2sim::model {

inline SimTK::Vec3 to_simtk(const Vec3& v) {
  return {v.x, v.y, v.z};
}
inline Vec3 from_simtk(const SimTK::Vec3& v) {
  return {v[0], v[1], v[2]};
}

inline SimTK::Rotation to_simtk(const Mat3& m) {
  SimTK::Mat33 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r(i, j) = m.m[i][j];
  return SimTK::Rotation(r);  // re-orthonormalised: scene rotations carry rounding
}
inline Mat3 from_simtk(const SimTK::Rotation& r) {
  Mat3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      m.m[i][j] = r.asMat33()(i, j);
  return m;
}
inline SimTK::Transform to_simtk(const Pose& p) {
  return SimTK::Transform(to_simtk(p.rotation), to_simtk(p.position));
}

/// Standard gravity, m/s², along −Z.
constexpr double kGravity = 9.81;

/// How an axis's value is realised.
/// How an axis's value is realised.
struct AxisImpl {
  // Tree joint: a mobilizer coordinate.
  SimTK::MobilizedBodyIndex mobod;
  int coordinate = 0;  // which q/u of the mobilizer
  double sign = 1;     // axis value = sign * q (ODE convention: body1 relative to body2)
  // Loop joint: measured from the two bodies.
  int body1 = -1, body2 = -1;     // kernel body indices (0 = world)
  SimTK::UnitVec3 axis_in_body2;  // rotation axis or slide direction, body2 frame
  SimTK::Rotation relative0;      // initial body1 orientation in body2 frame
  SimTK::Vec3 offset0_in_body2;   // initial body1 origin in body2 frame
  SimTK::Vec3 anchor_in_body1;    // slider force application point
};

struct Multibody::Impl {
  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter{system};
  SimTK::GeneralForceSubsystem forces{system};
  // Gravity is applied by AppliedLoads, not by a Force::Gravity: Simbody's costs a tenth of
  // a small robot's step in cache bookkeeping for three multiplications per body.
  struct Weight {
    SimTK::MobilizedBodyIndex mobod;
    double mass_kg;
    SimTK::Vec3 com_m;  // body frame
  };
  std::vector<Weight> weights;
  std::vector<SimTK::MobilizedBodyIndex> mobod_of_body;  // kernel body -> mobod (invalid: loose)
  LooseBodies loose;               // bodies with no joint, integrated outside Simbody
  std::vector<Pose> initial_pose;  // kernel body -> pose at load
  std::vector<AxisInfo> axes;
  std::vector<AxisImpl> axis_impl;
  std::vector<std::string> warnings;
  /// A joint stop: a linear spring-damper on one axis outside [low, high], never pulling.
  struct Stop {
    int axis;
    double low, high;
    double stiffness = 0, damping = 0;
  };
  std::vector<Stop> stops;
  std::vector<Wrench> wrenches;
  std::vector<double> axis_forces;
  std::vector<double> axis_friction;
  // Velocity-level Coulomb friction on tree axes (preallocated: stepping must not allocate).
  std::vector<int> braked;                 // axes with a bound this substep
  std::vector<SimTK::Vector> minv_column;  // per braked axis: M^-1 * e_axis
  std::vector<double> delassus, impulse;   // braked x braked, braked
  std::vector<int> axis_u;                 // per tree axis, its index in u (-1: loop axis)
  std::vector<double> axis_mobility;       // per axis, (M^-1)_aa at its last solve (0: none)
  std::vector<char> sliding;               // per axis: Coulomb friction as a plain force
  // M^-1 columns of the braked axes are reused while the configuration stays put (a robot at
  // rest): M depends on q only.
  std::vector<int> columns_for;   // the braked axes the columns belong to
  std::vector<double> columns_q;  // the q they were computed at
  bool bodies_fresh = false;      // substep_poses/twists hold the current state
  SimTK::Vector unit_force;
  bool contact_wrenches_used = false;  // substep_wrenches are written every substep (contact)
  std::vector<Pose> substep_poses;
  std::vector<Twist> substep_twists;
  std::vector<Wrench> substep_wrenches;
  // Joint reactions (request_joint_reactions): per scene joint, the mobilizer realising it
  // (invalid for a loop-closing joint) and whether its child is body1.
  struct JointReaction {
    SimTK::MobilizedBodyIndex mobod;
    bool child_is_body1 = true;
    int body1 = 0;  // kernel index
  };
  std::vector<JointReaction> joint_reaction_source;
  std::vector<Wrench> joint_reactions;               // world frame, at the current state
  std::vector<Wrench> joint_reactions_in_body1;      // body1's frame, as computed
  SimTK::Vector_<SimTK::SpatialVec> reactions_at_M;  // preallocated, one per mobilized body
  bool reactions_wanted = false;
  SimTK::State initial_state;
  SimTK::State current;
  SimTK::Vector udot, qdot;  // preallocated: stepping must not allocate
  bool half_kick_pending = true;
  double last_kick_s = 0;  // the kick of the current substep (the brakes bound their impulse by it)
  std::vector<int> quaternion_q;  // first q index of each quaternion (Free and Ball mobilizers)
  // q' = N(q)·u by hand when every mobilizer is Free or has q' = u: Simbody's multiplyByN goes
  // through its state digest for what is a copy plus one quaternion rate per free body.
  struct FreeCoordinates {
    int q, u;  // first indices: quaternion then position; angular then linear velocity
  };
  std::vector<FreeCoordinates> free_coordinates;
  std::vector<std::pair<int, int>> direct_coordinates;  // (q, u) of mobilizers with q' = u
  bool own_n = true;
  bool has_constraints = false;
  double tick_s = 1e-3;
  int substeps = 1;
  std::int64_t ticks = 0;

  const SimTK::State& state() const { return current; }
  const SimTK::MobilizedBody& mobod(int body) const {
    return matter.getMobilizedBody(mobod_of_body[body]);
  }
  SimTK::MobilizedBody& upd_mobod(int body) { return matter.updMobilizedBody(mobod_of_body[body]); }
};

/// An axis's value (rad or m), ODE convention; `state` realized to Position.
double axis_value(const Multibody::Impl& m, const SimTK::State& s, std::size_t a);
/// An axis's rate (rad/s or m/s); `state` realized to Velocity.
double axis_rate(const Multibody::Impl& m, const SimTK::State& s, std::size_t a);
/// Body poses and velocities (kernel indices); `state` realized to Velocity.
void read_bodies(const Multibody::Impl& m, const SimTK::State& s, Pose* poses, Twist* twists);
/// v += a·x, through raw storage where it is contiguous (element access goes through a
/// non-inline helper, and Vector expressions allocate).
void add_scaled(SimTK::Vector& v, double a, const SimTK::Vector& x);
/// Registers the kernel's loads (gravity, wrenches, axis forces, stops) as a Simbody force.
void add_applied_loads(Multibody::Impl& m);

/// Axis Coulomb friction (axis_friction.cpp): marks the axes that slide clearly, which get a
/// plain force, before the accelerations are computed.
void classify_sliding(Multibody::Impl& m, const SimTK::State& s, double h);
/// The velocity-level brake of the other axes with friction, after the kick.
void brake_axes(Multibody::Impl& m, SimTK::State& s, double kick_s);

/// Joint reactions (joint_reactions.cpp) from a state realized to Acceleration.
void compute_joint_reactions(Multibody::Impl& m, const SimTK::State& s);
/// The reactions carried with body1 to its pose at the step's end.
void carry_joint_reactions(Multibody::Impl& m, const Pose* poses);

}  // namespace s2sim::model
