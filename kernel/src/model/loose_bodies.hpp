#pragma once
/// \file
/// Bodies without any joint (things, one-solid robots) integrated here instead of in Simbody:
/// for a lone free body, Simbody's articulated-body recursion (a 6x6 factorisation per body
/// per step) costs ten times the physics. Same update law as the multibody model (leapfrog:
/// kick the velocities, then drift the positions with the new velocities), Newton–Euler about
/// the centre of mass with the gyroscopic term, the orientation as a unit quaternion updated
/// like Simbody's Free mobilizer (q += h·½·ω⊗q, then normalised).

#include <s2sim/kernel/scene.hpp>
#include <s2sim/math.hpp>

#include <string>
#include <vector>

namespace s2sim::common {
class StateLayout;
}

namespace s2sim::model {

class LooseBodies {
 public:
  /// Adds scene body `body` as kernel body `kernel_index`.
  void add(int kernel_index, const scene::Body& body);
  std::size_t size() const { return model_.size(); }
  bool empty() const { return model_.empty(); }
  /// Mass of kernel body `kernel_index`, 0 if it is not one of these (at load, not per step).
  double mass_kg(int kernel_index) const {
    for (const Model& m : model_)
      if (m.kernel_index == kernel_index) return m.mass_kg;
    return 0.0;
  }

  /// Back to the load poses, at rest.
  void reset();
  /// Velocities += kick_s · accelerations from gravity and the two wrench arrays (per kernel
  /// body, about each body origin, world frame; `extra` may be null).
  void kick(const Wrench* wrenches, const Wrench* extra, double kick_s);
  /// Positions += step_s · velocities.
  void drift(double step_s);
  /// Poses and twists (body origin) into the kernel's per-body arrays.
  void read(Pose* poses, Twist* twists) const;

  double kinetic_energy_J() const;
  double potential_energy_J() const;
  /// Sum of every state number (a NaN check).
  double checksum() const;

  /// Puts kernel body `kernel_index` at `pose` (body origin, world frame), at rest. Returns
  /// false when that body is not one of these.
  bool place(int kernel_index, const Pose& pose);
  /// Puts kernel body `kernel_index` at `pose`, its velocities kept; false if not loose.
  bool move(int kernel_index, const Pose& pose);
  /// Gives body `kernel_index` new mass properties (a thing added while running): mass, centre
  /// of mass (body frame; the body origin stays where it is), inertia about it (body axes),
  /// whether gravity pulls it and whether it is held where it is (no load moves it, and it is
  /// at rest). False if not loose.
  bool set_mass_properties(int kernel_index, double mass_kg, const Vec3& com_m, const Mat3& inertia,
                           bool gravity, bool fixed);
  /// Sets body `kernel_index`'s velocity (its origin's, world frame); false if not loose.
  bool set_velocity(int kernel_index, const Twist& twist);

  /// Registers the state segments `<prefix>/position` (per body its centre of mass and
  /// orientation quaternion w, x, y, z: 7 numbers) and `<prefix>/velocity` (its centre of
  /// mass's velocity and its angular velocity: 6 numbers), in the order the bodies were added.
  void declare_state(common::StateLayout& layout, const std::string& prefix);

 private:
  struct Model {
    int kernel_index;
    double mass_kg;
    Vec3 com_body_m;
    Mat3 inertia_body, inverse_inertia_body;  // about the COM, body axes
    bool gravity;
    bool fixed = false;  // held where it is placed (an obstacle added while running)
    Vec3 com0_m;
    Quat q0;
  };
  struct State {
    Vec3 com_m, com_velocity_m_s, angular_velocity_rad_s;
    Quat q;
  };
  /// rotation_[i] = to_matrix(state_[i].q), refreshed wherever q changes: kick and read
  /// both need it, and the quaternion changes once per step (drift).
  void refresh_rotations();

  std::vector<Model> model_;    // built at load
  std::vector<State> state_;    // what a snapshot holds
  std::vector<Mat3> rotation_;  // derived from state_, per body
};

}  // namespace s2sim::model
