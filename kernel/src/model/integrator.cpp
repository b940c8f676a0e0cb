// The leapfrog integrator's operations on the Simbody state, one substep at a time:
// accelerations, kick, drift, projection, and the end-of-tick read-out and finite check. The
// order in which they run is sim/step.cpp's (docs/models/multibody.md).
#include "model/dynamics.hpp"

#include <cmath>

namespace s2sim::model {

void add_scaled(SimTK::Vector& v, double a, const SimTK::Vector& x) {
  const int n = v.size();
  if (v.hasContiguousData() && x.hasContiguousData()) {
    double* pv = v.updContiguousScalarData();
    const double* px = x.getContiguousScalarData();
    for (int i = 0; i < n; ++i)
      pv[i] += a * px[i];
  } else {
    for (int i = 0; i < n; ++i)
      v[i] += a * x[i];
  }
}

void add_column(SimTK::Vector& v, double a, const AxisColumns& columns, std::size_t axis) {
  const int begin = columns.u_begin[axis], n = columns.size(axis);
  const double* px = columns.of(axis);
  if (v.hasContiguousData()) {
    double* pv = v.updContiguousScalarData() + begin;
    for (int i = 0; i < n; ++i)
      pv[i] += a * px[i];
  } else {
    for (int i = 0; i < n; ++i)
      v[begin + i] += a * px[i];
  }
}

/// q' = N(q)·u for Free mobilizers (q = quaternion of R_FM then p_FM, u = ω then v, both in
/// F: q̇_quat = ½·(0, ω)⊗q, ṗ = v) and mobilizers whose q' = u (Pin, Slider, Universal).
namespace {
/// Simbody's quaternion rate for the angular velocity w (in F): q' = ½·(0, w)⊗q.
void quaternion_rate(const double* w, const double* q, double* qdot) {
  const double w0 = w[0], w1 = w[1], w2 = w[2];
  const double a = q[0], b = q[1], c = q[2], d = q[3];
  qdot[0] = -0.5 * (w0 * b + w1 * c + w2 * d);
  qdot[1] = 0.5 * (w0 * a + w1 * d - w2 * c);
  qdot[2] = 0.5 * (-w0 * d + w1 * a + w2 * b);
  qdot[3] = 0.5 * (w0 * c - w1 * b + w2 * a);
}
}  // namespace

void calc_qdot(const Multibody::Impl& m, const double* u, const double* q, double* qdot) {
  for (const auto& [qi, ui] : m.direct_coordinates)
    qdot[qi] = u[ui];
  for (const auto& f : m.free_coordinates) {
    quaternion_rate(u + f.u, q + f.q, qdot + f.q);
    for (int k = 0; k < 3; ++k)
      qdot[f.q + 4 + k] = u[f.u + 3 + k];
  }
  for (const auto& f : m.ball_coordinates)
    quaternion_rate(u + f.u, q + f.q, qdot + f.q);
}

void normalize_quaternions(const Multibody::Impl& m, double* q) {
  for (int first : m.quaternion_q) {
    double n2 = 0;
    for (int c = 0; c < 4; ++c)
      n2 += q[first + c] * q[first + c];
    const double inverse_norm = 1 / std::sqrt(n2);
    for (int c = 0; c < 4; ++c)
      q[first + c] *= inverse_norm;
  }
}

int Multibody::substeps() const {
  return impl_->substeps;
}

double Multibody::substep_s() const {
  return impl_->tick_s / impl_->substeps;
}

void Multibody::current_bodies(const Pose*& poses, const Twist*& twists) {
  Impl& m = *impl_;
  if (!m.bodies_fresh) {
    realize_velocity(m, m.current);
    read_bodies(m, m.current, m.substep_poses.data(), m.substep_twists.data());
  }
  poses = m.substep_poses.data();
  twists = m.substep_twists.data();
}

void Multibody::prepare_axes() {
  Impl& m = *impl_;
  m.bodies_fresh = false;
  if (!m.axis_friction.empty()) classify_sliding(m, m.current, substep_s());
  if (!m.axes.empty()) prepare_drives(m, m.current);
}

void realize_velocity(const Multibody::Impl& m, const SimTK::State& s) {
  m.dynamics->realize_velocity(m, s);
}

void Multibody::accelerations(bool last_substep) {
  Impl& m = *impl_;
  // Only loose bodies (a pile of things): Simbody has nothing to integrate, and its realize
  // chain would still cost its bookkeeping.
  if (!m.has_mobilized_bodies) return;
  m.dynamics->accelerations(m, last_substep);
}

// Semi-explicit Euler, u first (implicit in the declared damping) then q with the new u, started
// with a half step of u (leapfrog): the same single acceleration evaluation per step, but positions
// are second order and exact under constant acceleration (free fall), and the generalized speeds u
// live at the middle of the step (docs/models/multibody.md).
void Multibody::kick() {
  Impl& m = *impl_;
  const double h = substep_s();
  const double kick = m.half_kick_pending ? 0.5 * h : h;
  m.half_kick_pending = false;
  m.last_kick_s = kick;
  if (m.has_mobilized_bodies) add_scaled(m.current.updU(), kick, m.udot);
  m.loose.kick(m.wrenches.data(), m.contact_wrenches_used ? m.substep_wrenches.data() : nullptr,
               kick);
}

void Multibody::solve_axes() {
  Impl& m = *impl_;
  // The axis drives implicitly, (M + κ·C)·Δu = κ·f within their bounds, with the axes'
  // Coulomb friction as a velocity-level brake.
  model::solve_axes(m, m.current, m.last_kick_s);
  // Loops: the speeds the drift integrates satisfy the velocity constraints (the solve above
  // works in the tree's coordinates), so that positions move by h times the speeds reported.
  if (!m.has_constraints || m.rows.empty()) return;
  m.dynamics->project_speeds(m);
}

void Multibody::drift(int substep) {
  Impl& m = *impl_;
  SimTK::State& s = m.current;
  const double h = substep_s();
  m.loose.drift(h);
  // Simbody's time stays at zero (Multibody::Impl::current): advancing it would invalidate
  // and realize the Time stage of every subsystem each substep, for nothing that reads it.
  m.substep = substep + 1;
  if (!m.has_mobilized_bodies) return;  // updQ would invalidate Simbody's empty state
  m.dynamics->qdot(m);
  SimTK::Vector& q = s.updQ();
  add_scaled(q, h, m.qdot);
  normalize_quaternions(m, q.updContiguousScalarData());
}

void Multibody::project() {
  Impl& m = *impl_;
  if (!m.has_constraints) return;
  m.dynamics->project(m);
}

void Multibody::finish_tick() {
  Impl& m = *impl_;
  SimTK::State& s = m.current;
  ++m.ticks;
  m.substep = 0;
  for (std::size_t a = 0; a < m.drive_sum.size(); ++a) {
    m.drive_applied[a] = m.drive_sum[a] / m.substeps;
    m.drive_sum[a] = 0.0;
  }
  realize_velocity(m, s);
  // Read the bodies once here: for read() and for the next substep's contact.
  read_bodies(m, s, m.substep_poses.data(), m.substep_twists.data());
  m.bodies_fresh = true;
  if (m.reactions_wanted) carry_joint_reactions(m, m.substep_poses.data());
  // A NaN anywhere poisons the sums: one cheap check per tick.
  double sum = m.loose.checksum();
  for (const SimTK::Vector* v : {&s.getQ(), &s.getU()}) {
    if (v->hasContiguousData()) {  // element access goes through a non-inline helper
      const double* x = v->getContiguousScalarData();
      for (int i = 0; i < v->size(); ++i)
        sum += x[i];
    } else {
      for (int i = 0; i < v->size(); ++i)
        sum += (*v)[i];
    }
  }
  if (!std::isfinite(sum)) {
    const int body = first_non_finite_body();
    throw Error(ErrorKind::runtime,
                "the simulation state became non-finite at t = " + std::to_string(time_s()) + " s" +
                    (body > 0 ? ", first at body " + body_name(body) : std::string()));
  }
}

int Multibody::first_non_finite_body() const {
  const Impl& m = *impl_;
  const SimTK::State& s = m.current;
  const SimTK::Vector& q = s.getQ();
  const SimTK::Vector& u = s.getU();
  for (std::size_t b = 1; b < m.mobod_of_body.size(); ++b) {
    if (!m.mobod_of_body[b].isValid()) continue;
    const auto& mob = m.matter.getMobilizedBody(m.mobod_of_body[b]);
    for (int k = 0; k < mob.getNumQ(s); ++k)
      if (!std::isfinite(q[mob.getFirstQIndex(s) + k])) return static_cast<int>(b);
    for (int k = 0; k < mob.getNumU(s); ++k)
      if (!std::isfinite(u[mob.getFirstUIndex(s) + k])) return static_cast<int>(b);
  }
  // Loose bodies: their poses and twists as LooseBodies holds them (only on failure).
  std::vector<Pose> poses(m.mobod_of_body.size());
  std::vector<Twist> twists(m.mobod_of_body.size());
  m.loose.read(poses.data(), twists.data());
  for (std::size_t b = 1; b < m.mobod_of_body.size(); ++b) {
    if (m.mobod_of_body[b].isValid()) continue;
    const Pose& p = poses[b];
    const Twist& w = twists[b];
    double sum = p.position.x + p.position.y + p.position.z + w.linear_m_s.x + w.linear_m_s.y +
                 w.linear_m_s.z + w.angular_rad_s.x + w.angular_rad_s.y + w.angular_rad_s.z;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        sum += p.rotation.m[i][j];
    if (!std::isfinite(sum)) return static_cast<int>(b);
  }
  return -1;
}

const std::string& Multibody::body_name(int body) const {
  return impl_->body_names.at(static_cast<std::size_t>(body));
}

}  // namespace s2sim::model
