// Joint reactions for the jointforce sensor and plugins: Simbody's mobilizer reaction forces
// turned into the load body2 exerts on body1.
#include "model/multibody_impl.hpp"

namespace s2sim::model {

namespace {

/// Joint j's reaction from its mobilizer's reaction on the child at M (torque about M's origin,
/// then force; Ground): the load on body1 about the anchor carried by body1 (M's origin when the
/// child is body1; F's when it is the parent, `p_FM` from F's origin to M's apart along a
/// slider), and the same in body1's frame (`R_G1` its rotation), which the step carries to
/// body1's pose at its end.
void store_reaction(Multibody::Impl& m, std::size_t j, const Wrench& at_M, const Vec3& p_FM,
                    const Mat3& R_G1) {
  Vec3 force = at_M.force_N, torque = at_M.torque_Nm;
  if (!m.joint_reaction_source[j].child_is_body1) {  // on the parent: the opposite load
    force = -at_M.force_N;
    torque = -at_M.torque_Nm + cross(p_FM, force);
  }
  m.joint_reactions[j] = Wrench{torque, force};
  const Mat3 R_1G = R_G1.transposed();
  m.joint_reactions_in_body1[j] = Wrench{R_1G * torque, R_1G * force};
}

}  // namespace

/// The joint reactions from a state realized to Acceleration: Simbody's mobilizer reactions
/// on the children at M (mobility forces included).
void compute_joint_reactions(Multibody::Impl& m, const SimTK::State& s) {
  m.matter.calcMobilizerReactionForces(s, m.reactions_at_M);
  for (std::size_t j = 0; j < m.joint_reaction_source.size(); ++j) {
    const auto& src = m.joint_reaction_source[j];
    if (!src.mobod.isValid()) continue;  // a loop joint: zeros
    const SimTK::SpatialVec& R = m.reactions_at_M[src.mobod];
    Vec3 p_FM;
    if (!src.child_is_body1) {
      const auto& mob = m.matter.getMobilizedBody(src.mobod);
      const SimTK::Rotation R_GF =
          mob.getParentMobilizedBody().getBodyRotation(s) * mob.getInboardFrame(s).R();
      p_FM = from_simtk(R_GF * mob.getMobilizerTransform(s).p());
    }
    store_reaction(m, j, Wrench{from_simtk(R[0]), from_simtk(R[1])}, p_FM,
                   from_simtk(m.mobod(src.body1).getBodyRotation(s)));
  }
}

void compute_tree_joint_reactions(Multibody::Impl& m) {
  TreeDynamics& tree = *m.tree;
  tree.reactions(&m.tree_body_loads[0][0][0], m.udot.getContiguousScalarData(),
                 m.tree_reactions.data());
  for (std::size_t j = 0; j < m.joint_reaction_source.size(); ++j) {
    const auto& src = m.joint_reaction_source[j];
    if (!src.mobod.isValid()) continue;  // a loop joint: zeros
    const int mobod = src.mobod;
    const Vec3 p_FM =
        src.child_is_body1 ? Vec3{} : tree.joint_origin(mobod) - tree.frame_origin(mobod);
    store_reaction(m, j, m.tree_reactions[static_cast<std::size_t>(mobod)], p_FM,
                   tree.pose(m.mobod_of_body[static_cast<std::size_t>(src.body1)]).rotation);
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
