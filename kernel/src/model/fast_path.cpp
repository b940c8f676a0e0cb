// The small-tree fast path between Simbody's model and TreeDynamics: which systems take it,
// the check at load that it gives Simbody's accelerations, and its use while stepping.
#include "model/multibody_impl.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace s2sim::model {
namespace {

Pose pose_of(const SimTK::Transform& X) {
  return {from_simtk(X.p()), from_simtk(X.R())};
}

const double* data_of(const SimTK::Vector& v) {
  // A State's q and u are contiguous (Simbody allocates them as one block per subsystem).
  if (!v.hasContiguousData()) throw std::logic_error("fast path: a non-contiguous state vector");
  return v.getContiguousScalarData();
}

/// The tree's model from Simbody's, or null when a mobilizer is not one the tree knows.
std::unique_ptr<TreeDynamics> tree_of(const Multibody::Impl& m) {
  const SimTK::State& s = m.initial_state;
  std::vector<TreeDynamics::BodySpec> bodies;
  for (SimTK::MobilizedBodyIndex i(1); i < m.matter.getNumBodies(); ++i) {
    const SimTK::MobilizedBody& mob = m.matter.getMobilizedBody(i);
    TreeDynamics::BodySpec b;
    if (SimTK::MobilizedBody::Free::isInstanceOf(mob) && mob.getNumQ(s) == 7) {
      b.joint = TreeDynamics::Joint::free;
    } else if (SimTK::MobilizedBody::Pin::isInstanceOf(mob)) {
      b.joint = TreeDynamics::Joint::pin;
    } else if (SimTK::MobilizedBody::Slider::isInstanceOf(mob)) {
      b.joint = TreeDynamics::Joint::slider;
    } else if (SimTK::MobilizedBody::Weld::isInstanceOf(mob)) {
      b.joint = TreeDynamics::Joint::weld;
    } else {
      return nullptr;  // Universal, Ball: Simbody's
    }
    b.parent = mob.getParentMobilizedBody().getMobilizedBodyIndex();
    b.X_PF = pose_of(mob.getDefaultInboardFrame());
    b.X_BM = pose_of(mob.getDefaultOutboardFrame());
    b.q0 = mob.getFirstQIndex(s);
    b.u0 = mob.getFirstUIndex(s);
    const SimTK::MassProperties& mp = mob.getBodyMassProperties(s);
    b.mass_kg = mp.getMass();
    b.com_B = from_simtk(mp.getMassCenter());
    const SimTK::Mat33 I = mp.calcCentralInertia().toMat33();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        b.central_inertia_B.m[r][c] = I(r, c);
    bodies.push_back(b);
  }
  try {
    return std::make_unique<TreeDynamics>(bodies, s.getNQ(), s.getNU());
  } catch (const std::logic_error&) {  // speeds not contiguous per tree: Simbody's
    return nullptr;
  }
}

}  // namespace

void update_tree_kinematics(const Multibody::Impl& m) {
  m.tree->kinematics(data_of(m.current.getQ()), data_of(m.current.getU()));
}

SimTK::Vec3 to_ground(const Multibody::Impl& m, const SimTK::State& state,
                      SimTK::MobilizedBodyIndex body, const SimTK::Vec3& v_B) {
  if (m.uses_tree()) return to_simtk(m.tree->pose(body).rotation * from_simtk(v_B));
  return m.matter.getMobilizedBody(body).getBodyRotation(state) * v_B;
}

void tree_accelerations(Multibody::Impl& m) {
  update_tree_kinematics(m);
  m.tree_body_loads.setToZero();
  m.tree_mobility_forces = 0.0;
  add_applied_loads(m, m.current, m.tree_body_loads, m.tree_mobility_forces);
  m.tree->accelerations(&m.tree_body_loads[0][0][0], data_of(m.tree_mobility_forces),
                        m.udot.updContiguousScalarData());
}

void build_fast_path(Multibody::Impl& m) {
  if (m.has_constraints || !m.own_n || !m.has_mobilized_bodies) return;
  std::unique_ptr<TreeDynamics> tree = tree_of(m);
  if (!tree) return;
  const int nb = m.matter.getNumBodies(), nu = m.initial_state.getNU();
  m.tree_body_loads.resize(nb);
  m.tree_mobility_forces.resize(nu);
  // The check: a probe state with every speed moving (the velocity-product terms count) under
  // gravity, through Simbody and through the tree.
  double scale = 1, worst = 0;
  try {
    m.current = m.initial_state;
    SimTK::Vector& u = m.current.updU();
    for (int i = 0; i < nu; ++i)
      u[i] = std::sin(1.7 * i + 0.3);
    realize_accelerations(m);
    const SimTK::Vector simbody = m.current.getUDot();
    m.tree = std::move(tree);
    tree_accelerations(m);
    for (int i = 0; i < nu; ++i) {
      scale = std::max(scale, std::abs(simbody[i]));
      worst = std::max(worst, std::abs(simbody[i] - m.udot[i]));
    }
  } catch (const std::exception&) {
    // A system either side cannot solve at load (a singular mass matrix): Simbody's, which
    // reports it when stepping as it always did.
    m.tree.reset();
    m.current = m.initial_state;
    return;
  }
  m.current = m.initial_state;
  if (!(worst <= 1e-9 * scale)) {
    m.tree.reset();
    std::ostringstream out;
    out << "the small-tree fast path disagrees with Simbody by " << worst << " (relative to "
        << scale << "): Simbody computes this scene's dynamics";
    m.warnings.push_back(out.str());
  }
}

}  // namespace s2sim::model
