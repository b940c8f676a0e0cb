// The small-tree dynamics built from Simbody's model (TreeDynamics, with LoopConstraints for
// the loop joints): which systems can take it, and the check at load that it gives Simbody's
// accelerations. Stepping on it: tree_path.cpp.
#include "model/dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <new>
#include <sstream>

namespace s2sim::model {
namespace {

Pose pose_of(const SimTK::Transform& X) {
  return {from_simtk(X.p()), from_simtk(X.R())};
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
    } else if (SimTK::MobilizedBody::Universal::isInstanceOf(mob)) {
      b.joint = TreeDynamics::Joint::universal;
    } else if (SimTK::MobilizedBody::Ball::isInstanceOf(mob) && mob.getNumQ(s) == 4) {
      b.joint = TreeDynamics::Joint::ball;
    } else {
      return nullptr;  // another kind (none built now): Simbody's
    }
    b.parent = mob.getParentMobilizedBody().getMobilizedBodyIndex();
    b.X_PF = pose_of(mob.getDefaultInboardFrame());
    b.X_BM = pose_of(mob.getDefaultOutboardFrame());
    b.q0 = mob.getFirstQIndex(s);
    b.u0 = mob.getFirstUIndex(s);
    central_mass_of(mob.getBodyMassProperties(s), b.mass_kg, b.com_B, b.central_inertia_B);
    bodies.push_back(b);
  }
  try {
    return std::make_unique<TreeDynamics>(bodies, s.getNQ(), s.getNU());
  } catch (const std::logic_error&) {  // speeds not contiguous per tree: Simbody's
    return nullptr;
  }
}

/// The three constant angles of Simbody's ConstantOrientation (and of a Weld's rotation): the
/// follower frame's x, y, z axes perpendicular to the base frame's y, z, x.
void add_orientation(std::vector<LoopConstraints::Angle>& angles, int base,
                     const SimTK::Rotation& R_base, int follower,
                     const SimTK::Rotation& R_follower) {
  for (int k = 0; k < 3; ++k)
    angles.push_back({base, follower, from_simtk(SimTK::Vec3(R_base.col((k + 1) % 3))),
                      from_simtk(SimTK::Vec3(R_follower.col(k))), 0.0});
}

/// The loop constraints from Simbody's, or null when one is of a kind they do not know.
std::unique_ptr<LoopConstraints> loops_of(const Multibody::Impl& m) {
  LoopConstraints::Spec spec;
  const SimTK::State& s = m.initial_state;
  for (SimTK::ConstraintIndex c(0); c < m.matter.getNumConstraints(); ++c) {
    const SimTK::Constraint& constraint = m.matter.getConstraint(c);
    if (constraint.isDisabledByDefault()) continue;
    const auto coupler = std::find_if(m.couplers.begin(), m.couplers.end(),
                                      [&](const auto& k) { return k.constraint == c; });
    if (coupler != m.couplers.end()) {  // a joint coupling's CoordinateCoupler
      const SimTK::MobilizedBody& f = m.matter.getMobilizedBody(coupler->follower);
      const SimTK::MobilizedBody& l = m.matter.getMobilizedBody(coupler->leader);
      spec.couplers.push_back({f.getFirstQIndex(s), f.getFirstUIndex(s), l.getFirstQIndex(s),
                               l.getFirstUIndex(s), coupler->ratio, coupler->offset});
    } else if (SimTK::Constraint::Ball::isInstanceOf(constraint)) {
      const auto& ball = SimTK::Constraint::Ball::downcast(constraint);
      spec.balls.push_back({ball.getBody1MobilizedBodyIndex(), ball.getBody2MobilizedBodyIndex(),
                            from_simtk(ball.getDefaultPointOnBody1()),
                            from_simtk(ball.getDefaultPointOnBody2())});
    } else if (SimTK::Constraint::ConstantAngle::isInstanceOf(constraint)) {
      const auto& angle = SimTK::Constraint::ConstantAngle::downcast(constraint);
      spec.angles.push_back({angle.getBaseMobilizedBodyIndex(),
                             angle.getFollowerMobilizedBodyIndex(),
                             from_simtk(SimTK::Vec3(angle.getDefaultBaseAxis())),
                             from_simtk(SimTK::Vec3(angle.getDefaultFollowerAxis())),
                             std::cos(angle.getDefaultAngle())});
    } else if (SimTK::Constraint::ConstantOrientation::isInstanceOf(constraint)) {
      const auto& o = SimTK::Constraint::ConstantOrientation::downcast(constraint);
      add_orientation(spec.angles, o.getBaseMobilizedBodyIndex(), o.getDefaultBaseRotation(),
                      o.getFollowerMobilizedBodyIndex(), o.getDefaultFollowerRotation());
    } else if (SimTK::Constraint::Weld::isInstanceOf(constraint)) {
      // Simbody's Weld: body 2's frame axes perpendicular to body 1's (a ConstantOrientation
      // with body 1 as base), and the two frames' origins held together (a Ball).
      const auto& weld = SimTK::Constraint::Weld::downcast(constraint);
      const SimTK::Transform& X1 = weld.getDefaultFrameOnBody1();
      const SimTK::Transform& X2 = weld.getDefaultFrameOnBody2();
      const int b1 = weld.getBody1MobilizedBodyIndex(), b2 = weld.getBody2MobilizedBodyIndex();
      add_orientation(spec.angles, b1, X1.R(), b2, X2.R());
      spec.balls.push_back({b1, b2, from_simtk(X1.p()), from_simtk(X2.p())});
    } else if (SimTK::Constraint::PointOnLine::isInstanceOf(constraint)) {
      const auto& line = SimTK::Constraint::PointOnLine::downcast(constraint);
      spec.lines.push_back({line.getLineMobilizedBodyIndex(), line.getFollowerMobilizedBodyIndex(),
                            from_simtk(SimTK::Vec3(line.getDefaultLineDirection())),
                            from_simtk(line.getDefaultPointOnLine()),
                            from_simtk(line.getDefaultFollowerPoint())});
    } else {
      return nullptr;
    }
  }
  return std::make_unique<LoopConstraints>(std::move(spec), m.initial_state.getNU());
}

}  // namespace

void build_fast_path(Multibody::Impl& m) {
  if (!m.own_n || !m.has_mobilized_bodies) return;
  std::unique_ptr<TreeDynamics> tree = tree_of(m);
  if (!tree) return;
  std::unique_ptr<LoopConstraints> loops;
  if (m.has_constraints) {
    loops = loops_of(m);
    if (!loops) return;
    m.loop_u.assign(static_cast<std::size_t>(m.initial_state.getNU()), 0.0);
    m.loop_du.assign(static_cast<std::size_t>(m.initial_state.getNU()), 0.0);
    m.loop_dq.assign(static_cast<std::size_t>(m.initial_state.getNQ()), 0.0);
    m.loop_q.assign(static_cast<std::size_t>(m.initial_state.getNQ()), 0.0);
  }
  const int nb = m.matter.getNumBodies(), nu = m.initial_state.getNU();
  m.tree_body_loads.resize(nb);
  m.tree_reactions.assign(static_cast<std::size_t>(nb), Wrench{});
  m.tree_mobility_forces.resize(nu);
  // The check: a probe state with every speed moving (the velocity-product terms count) under
  // gravity, through Simbody and through the tree.
  double scale = 1, worst = 0;
  try {
    m.current = m.initial_state;
    SimTK::Vector& u = m.current.updU();
    for (int i = 0; i < nu; ++i)
      u[i] = std::sin(1.7 * i + 0.3);
    // With loops, a state on the constraints: redundant rows (a planar loop's) then agree.
    if (loops) m.system.project(m.current, kLoopTolerance);
    m.dynamics = &simbody_dynamics();
    realize_accelerations(m);
    const SimTK::Vector simbody = m.current.getUDot();
    m.tree = std::move(tree);
    m.loops = std::move(loops);
    m.dynamics = &tree_dynamics();  // the tree's own kinematics for its loads
    tree_accelerations(m);
    for (int i = 0; i < nu; ++i) {
      scale = std::max(scale, std::abs(simbody[i]));
      worst = std::max(worst, std::abs(simbody[i] - m.udot[i]));
    }
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception&) {
    // A system either side cannot solve at load (a singular mass matrix): Simbody's, which
    // reports it when stepping as it always did.
    m.tree.reset();
    m.loops.reset();
    m.current = m.initial_state;
    m.dynamics = &simbody_dynamics();
    return;
  }
  m.current = m.initial_state;
  m.dynamics = &simbody_dynamics();  // until select_dynamics chooses
  if (!(worst <= kDynamicsAgreement * scale)) {
    m.tree.reset();
    m.loops.reset();
    std::ostringstream out;
    out << "the small-tree fast path disagrees with Simbody by " << worst << " (relative to "
        << scale << "): Simbody computes this scene's dynamics";
    m.warnings.push_back(out.str());
  }
}

}  // namespace s2sim::model
