// Joint reactions for the jointforce sensor and plugins: Simbody's mobilizer reaction forces
// turned into the load body2 exerts on body1.
#include "model/multibody_impl.hpp"

namespace s2sim::model {

/// The joint reactions from a state realized to Acceleration: Simbody's mobilizer reaction
/// on the child at M (mobility forces included), turned into the load on body1 about the
/// anchor carried by body1 (M's origin when the child is body1, F's when it is the parent).
void compute_joint_reactions(Multibody::Impl& m, const SimTK::State& s) {
  m.matter.calcMobilizerReactionForces(s, m.reactions_at_M);
  for (std::size_t j = 0; j < m.joint_reaction_source.size(); ++j) {
    const auto& src = m.joint_reaction_source[j];
    if (!src.mobod.isValid()) continue;  // a loop joint: zeros
    const SimTK::SpatialVec& R = m.reactions_at_M[src.mobod];
    SimTK::Vec3 force = R[1], torque = R[0];
    if (!src.child_is_body1) {
      // On the parent: the opposite load, moved from Mo to Fo (they part along a slider).
      const auto& mob = m.matter.getMobilizedBody(src.mobod);
      const SimTK::Rotation R_GF =
          mob.getParentMobilizedBody().getBodyRotation(s) * mob.getInboardFrame(s).R();
      const SimTK::Vec3 p_FM_G = R_GF * mob.getMobilizerTransform(s).p();
      force = -R[1];
      torque = -R[0] + SimTK::cross(p_FM_G, force);
    }
    m.joint_reactions[j] = Wrench{from_simtk(torque), from_simtk(force)};
    // Also in body1's frame: the step carries it to body1's pose at the step's end.
    const SimTK::Rotation& R_G1 = m.mobod(src.body1).getBodyRotation(s);
    m.joint_reactions_in_body1[j] = Wrench{from_simtk(~R_G1 * torque), from_simtk(~R_G1 * force)};
  }
}

void compute_tree_joint_reactions(Multibody::Impl& m) {
  const TreeDynamics& tree = *m.tree;
  m.tree->reactions(&m.tree_body_loads[0][0][0], m.udot.getContiguousScalarData(),
                    m.tree_reactions.data());
  for (std::size_t j = 0; j < m.joint_reaction_source.size(); ++j) {
    const auto& src = m.joint_reaction_source[j];
    if (!src.mobod.isValid()) continue;  // a loop joint: zeros
    const int mobod = src.mobod;
    const Wrench& R = m.tree_reactions[static_cast<std::size_t>(mobod)];
    Vec3 force = R.force_N, torque = R.torque_Nm;
    if (!src.child_is_body1) {  // on the parent, moved from Mo to Fo, as above
      const Vec3 p_FM = tree.joint_origin(mobod) - tree.frame_origin(mobod);
      force = -R.force_N;
      torque = -R.torque_Nm + cross(p_FM, force);
    }
    m.joint_reactions[j] = Wrench{torque, force};
    const Mat3 R_1G =
        tree.pose(m.mobod_of_body[static_cast<std::size_t>(src.body1)]).rotation.transposed();
    m.joint_reactions_in_body1[j] = Wrench{R_1G * torque, R_1G * force};
  }
}

/// The reactions computed in the step, carried with body1 to its pose at the step's end: the
/// reaction is taken at the last substep's start, the sensors read it with the poses after the
/// drift (a steadily spinning joint would otherwise read a tangential ω·h fraction of its
/// centripetal force). `poses` are the step-end body poses.
void carry_joint_reactions(Multibody::Impl& m, const Pose* poses) {
  for (std::size_t j = 0; j < m.joint_reaction_source.size(); ++j) {
    const auto& src = m.joint_reaction_source[j];
    if (!src.mobod.isValid()) continue;
    const Mat3& R = poses[src.body1].rotation;
    const Wrench& local = m.joint_reactions_in_body1[j];
    m.joint_reactions[j] = Wrench{R * local.torque_Nm, R * local.force_N};
  }
}

}  // namespace s2sim::model
