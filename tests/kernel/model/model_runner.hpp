#pragma once
// Steps a multibody model and reads it back into plain buffers (model and contact tests).

#include "model/multibody.hpp"
#include "sim/step.hpp"

#include <vector>

namespace s2sim::test {

/// One tick of a bare Multibody (no parts, no pool): per substep its contact at the substep's
/// poses, then its stages, as each part of the kernel's tick runs them.
inline void physics_tick(model::Multibody& mb, model::SubstepForces* contact) {
  for (int k = 0; k < mb.substeps(); ++k) {
    if (contact) {
      const Pose* poses = nullptr;
      const Twist* twists = nullptr;
      mb.current_bodies(poses, twists);
      contact->compute(poses, twists, mb.substep_s(), mb.use_contact_wrenches(),
                       mb.contact_friction());
    }
    sim::multibody_substep(mb, k);
    if (contact) contact->end_substep();
  }
}

struct Runner {
  explicit Runner(const scene::Scene& s, double dt = 1e-3, int substeps = 1)
      : mb(s, dt, substeps),
        poses(mb.body_count()),
        twists(mb.body_count()),
        pos(mb.axes().size()),
        vel(mb.axes().size()) {
    read();
  }
  /// With declared axis inertias (Multibody's armature, per axis of the plan).
  Runner(const scene::Scene& s, const std::vector<double>& axis_inertia, double dt = 1e-3,
         int substeps = 1)
      : mb(s, model::plan_topology(s), axis_inertia, dt, substeps),
        poses(mb.body_count()),
        twists(mb.body_count()),
        pos(mb.axes().size()),
        vel(mb.axes().size()) {
    read();
  }
  void read() { mb.read(poses.data(), twists.data(), pos.data(), vel.data()); }
  void step(int n = 1) {
    for (int i = 0; i < n; ++i)
      physics_tick(mb, contact);
    read();
  }
  model::Multibody mb;
  model::SubstepForces* contact = nullptr;  ///< contact forces at every substep, if set
  std::vector<Pose> poses;
  std::vector<Twist> twists;
  std::vector<double> pos, vel;
};

}  // namespace s2sim::test
