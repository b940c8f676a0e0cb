// Bodies moved or set moving from outside the integration: the viewer's drag and SimTwo's
// SetRobotPos (place_free_body), SetSolidPos / SetSolidRotationMat (move_body) and
// SetSolidLinearVel / SetSolidAngularVel (set_body_velocity). A jointed body cannot leave its
// joint: it goes as close as the joint allows, its children following (docs/models/multibody.md).
// Axes set from outside (set_axis_state: Python's set_state) write their mobilizer coordinate.
#include "model/multibody_impl.hpp"

#include <cmath>

namespace s2sim::model {
namespace {

bool is_rotational(const SimTK::MobilizedBody& b) {
  return SimTK::MobilizedBody::Pin::isInstanceOf(b) ||
         SimTK::MobilizedBody::Universal::isInstanceOf(b) ||
         SimTK::MobilizedBody::Ball::isInstanceOf(b);
}

bool same_rotation(const SimTK::Rotation& a, const SimTK::Rotation& b) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (std::abs(a.asMat33()(i, j) - b.asMat33()(i, j)) > 1e-12) return false;
  return true;
}

/// x of A·x = b for a small dense system (n ≤ 6), partial pivoting; false when singular.
bool solve_small(double (&A)[6][6], double (&b)[6], int n) {
  for (int c = 0; c < n; ++c) {
    int pivot = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(A[r][c]) > std::abs(A[pivot][c])) pivot = r;
    if (std::abs(A[pivot][c]) < 1e-300) return false;
    for (int k = 0; k < n; ++k)
      std::swap(A[c][k], A[pivot][k]);
    std::swap(b[c], b[pivot]);
    for (int r = c + 1; r < n; ++r) {
      const double f = A[r][c] / A[c][c];
      for (int k = c; k < n; ++k)
        A[r][k] -= f * A[c][k];
      b[r] -= f * b[c];
    }
  }
  for (int c = n - 1; c >= 0; --c) {
    for (int k = c + 1; k < n; ++k)
      b[c] -= A[c][k] * b[k];
    b[c] /= A[c][c];
  }
  return true;
}

double dot6(const SimTK::SpatialVec& a, const SimTK::SpatialVec& b) {
  return SimTK::dot(a[0], b[0]) + SimTK::dot(a[1], b[1]);
}

}  // namespace

bool Multibody::place_free_body(int body, const Pose& pose) {
  Impl& m = *impl_;
  if (body <= 0 || body >= static_cast<int>(m.mobod_of_body.size())) return false;
  m.bodies_fresh = false;  // the cached body poses no longer hold the state
  if (!m.mobod_of_body[body].isValid()) return m.loose.place(body, pose);  // a loose body
  SimTK::MobilizedBody& b = m.upd_mobod(body);
  if (!SimTK::MobilizedBody::Free::isInstanceOf(b) || !b.getParentMobilizedBody().isGround())
    return false;
  SimTK::State& s = m.current;
  b.setQToFitTransform(s, to_simtk(pose));
  b.setUToFitVelocity(s, SimTK::SpatialVec(SimTK::Vec3(0), SimTK::Vec3(0)));
  m.system.realize(s, SimTK::Stage::Velocity);
  return true;
}

bool Multibody::set_loose_mass(int body, double mass_kg, const Vec3& com_m, const Mat3& inertia,
                               bool gravity, bool fixed) {
  Impl& m = *impl_;
  if (body <= 0 || body >= static_cast<int>(m.mobod_of_body.size())) return false;
  if (m.mobod_of_body[body].isValid()) return false;
  m.bodies_fresh = false;
  return m.loose.set_mass_properties(body, mass_kg, com_m, inertia, gravity, fixed);
}

bool Multibody::move_body(int body, const Pose& pose) {
  Impl& m = *impl_;
  if (body <= 0 || body >= static_cast<int>(m.mobod_of_body.size())) return false;
  m.bodies_fresh = false;  // the cached body poses no longer hold the state
  if (!m.mobod_of_body[body].isValid()) return m.loose.move(body, pose);  // a loose body
  SimTK::MobilizedBody& b = m.upd_mobod(body);
  SimTK::State& s = m.current;
  m.system.realize(s, SimTK::Stage::Position);
  SimTK::Transform X_GB = to_simtk(pose);
  const SimTK::Transform& now = b.getBodyTransform(s);
  if (is_rotational(b) && same_rotation(X_GB.R(), now.R())) {
    // A position alone on a hinge, Universal or ball: the joint centre cannot move, so the
    // body turns about it, the shortest way, to bring its origin toward the position.
    const SimTK::Vec3 centre = now * b.getOutboardFrame(s).p();
    const SimTK::Vec3 from = now.p() - centre, to = X_GB.p() - centre;
    const SimTK::Vec3 axis = SimTK::cross(from, to);
    const double sine = axis.norm(), cosine = SimTK::dot(from, to);
    if (sine > 1e-12 * from.norm() * to.norm()) {
      const SimTK::Rotation turn(std::atan2(sine, cosine), SimTK::UnitVec3(axis));
      X_GB = SimTK::Transform(turn * now.R(), centre + turn * from);
    } else {
      X_GB = now;  // along the line through the centre: nothing to turn
    }
  }
  // The mobilizer's coordinates that bring the body closest to X_GB (exact for a Free
  // mobilizer; a hinge keeps only the rotation about its axis): X_FM = X_PF⁻¹·X_GP⁻¹·X_GB·X_BM.
  const SimTK::Transform X_GP = b.getParentMobilizedBody().getBodyTransform(s);
  b.setQToFitTransform(s, ~b.getInboardFrame(s) * ~X_GP * X_GB * b.getOutboardFrame(s));
  m.system.realize(s, SimTK::Stage::Velocity);
  return true;
}

bool Multibody::set_body_velocity(int body, const Twist& twist) {
  Impl& m = *impl_;
  if (body <= 0 || body >= static_cast<int>(m.mobod_of_body.size())) return false;
  m.bodies_fresh = false;
  if (!m.mobod_of_body[body].isValid()) return m.loose.set_velocity(body, twist);
  SimTK::MobilizedBody& b = m.upd_mobod(body);
  SimTK::State& s = m.current;
  // V_GB = V0 + H·u over the mobilizer's own speeds u (the parent's motion in V0). The speeds
  // closest to the requested V in the body's spatial-inertia metric: what a rigid joint's
  // impulse leaves of a velocity given to the body alone (exact when the joint allows it).
  const int nu = b.getNumU(s), first = b.getFirstUIndex(s);
  if (nu <= 0 || nu > 6) return true;  // a weld: its velocity is its parent's
  auto body_velocity_with = [&](int unit) {
    SimTK::Vector& u = s.updU();
    for (int k = 0; k < nu; ++k)
      u[first + k] = k == unit ? 1.0 : 0.0;
    m.system.realize(s, SimTK::Stage::Velocity);
    return b.getBodyVelocity(s);
  };
  const SimTK::SpatialVec v0 = body_velocity_with(-1);
  SimTK::SpatialVec h[6];
  for (int k = 0; k < nu; ++k)
    h[k] = body_velocity_with(k) - v0;
  const SimTK::SpatialMat inertia = b.getBodySpatialInertiaInGround(s).toSpatialMat();
  const SimTK::SpatialVec wanted(to_simtk(twist.angular_rad_s), to_simtk(twist.linear_m_s));
  double A[6][6] = {}, rhs[6] = {};
  for (int i = 0; i < nu; ++i) {
    const SimTK::SpatialVec weighted = inertia * h[i];
    rhs[i] = dot6(weighted, wanted - v0);
    for (int j = 0; j < nu; ++j)
      A[i][j] = dot6(weighted, h[j]);
  }
  if (!solve_small(A, rhs, nu))
    for (double& x : rhs)
      x = 0;
  SimTK::Vector& u = s.updU();
  for (int k = 0; k < nu; ++k)
    u[first + k] = rhs[k];
  m.system.realize(s, SimTK::Stage::Velocity);
  return true;
}

bool Multibody::set_axis_state(std::size_t axis, double position, double velocity) {
  Impl& m = *impl_;
  if (axis >= m.axis_impl.size() || m.axes[axis].loop) return false;
  m.bodies_fresh = false;
  SimTK::State& s = m.current;
  const double sign = m.axis_impl[axis].sign;  // ±1: axis value = sign · q
  s.updQ()[m.axis_q[axis]] = sign * position;
  s.updU()[m.axis_u[axis]] = sign * velocity;
  m.system.realize(s, SimTK::Stage::Velocity);
  return true;
}

}  // namespace s2sim::model
