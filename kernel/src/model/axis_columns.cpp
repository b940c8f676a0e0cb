// M^-1 columns of the axes: the generalized-speed response to a unit impulse on an axis. The
// implicit axis solve (implicit_axes.cpp: drives and Coulomb friction) works in the axes'
// Delassus matrix W_ab = g_a·M^-1·g_b built from them.
#include "model/dynamics.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::model {
namespace {

/// Columns computed at a configuration within 1e-7 (rad or m) of the current one in every
/// coordinate of their tree that the mass matrix depends on are still valid; otherwise the
/// tree's columns are forgotten (a tree's M^-1 block depends on its own coordinates only).
void check_configuration(Multibody::Impl& m, const SimTK::State& s) {
  const SimTK::Vector& q = s.getQ();
  const double* now = q.hasContiguousData() ? q.getContiguousScalarData() : nullptr;
  bool any = false;
  for (std::size_t t = 0; t < m.tree_q_begin.size(); ++t) {
    bool same = now != nullptr;
    for (int i = m.tree_q_begin[t]; same && i < m.tree_q_end[t]; ++i)
      same = !m.q_shapes_mass[static_cast<std::size_t>(i)] ||
             std::abs(now[i] - m.columns_q[static_cast<std::size_t>(i)]) <= 1e-7;
    m.tree_changed[t] = !same;
    if (same) continue;
    any = true;
    for (int i = m.tree_q_begin[t]; i < m.tree_q_end[t]; ++i)
      m.columns_q[static_cast<std::size_t>(i)] = q[i];
  }
  if (!any) return;
  for (std::size_t a = 0; a < m.column_valid.size(); ++a)
    if (m.tree_changed[static_cast<std::size_t>(m.axis_tree[a])]) m.column_valid[a] = 0;
}

/// A column kept while the robot turned as a whole about its free root: M transforms as
/// T·M·Tᵀ with T = diag(R, R, 1) on the root's ground-frame (ω, v) and the joint rates, and a
/// joint axis's g is unchanged, so its column is T·column: the root's two vectors rotated by
/// R = R_now·R_thenᵀ.
void rotate_with_root(Multibody::Impl& m, const SimTK::State& s, int a) {
  const int root = m.axis_root[a];
  if (root < 0) return;
  const Multibody::Impl::Root& r = m.roots[static_cast<std::size_t>(root)];
  // Raw reads and writes: a Vector's element access is a call (asked for every axis, every
  // substep). A State's q is one contiguous block; the columns are our own Vectors.
  const double* q = s.getQ().getContiguousScalarData() + r.q0;
  double* then = &m.column_root_quat[4 * static_cast<std::size_t>(a)];
  bool same = true;
  for (int k = 0; k < 4; ++k)
    same = same && then[k] == q[k];
  if (same) return;
  const SimTK::Rotation R_now(SimTK::Quaternion(q[0], q[1], q[2], q[3]));
  const SimTK::Rotation R_then(SimTK::Quaternion(then[0], then[1], then[2], then[3]));
  const SimTK::Rotation R = R_now * ~R_then;
  double* column = m.minv_column.of(a);
  for (int part = 0; part < 2; ++part) {
    const int i = r.u0 + 3 * part - m.minv_column.u_begin[a];
    const SimTK::Vec3 v = R * SimTK::Vec3(column[i], column[i + 1], column[i + 2]);
    for (int k = 0; k < 3; ++k)
      column[i + k] = v[k];
  }
  for (int k = 0; k < 4; ++k)
    then[k] = q[k];
}

}  // namespace

void update_columns(Multibody::Impl& m, const SimTK::State& s, const std::vector<int>& axes) {
  if (axes.empty()) return;
  check_configuration(m, s);
  for (int a : axes) {
    if (m.column_valid[a]) {
      rotate_with_root(m, s, a);
      continue;
    }
    if (!m.axes[a].loop) {
      m.dynamics->tree_axis_column(m, s, a);
    } else {
      // g = Jᵀ·(the body loads of a unit axis load), then M^-1·g.
      m.unit_body_forces.setToZero();
      m.unit_force = 0.0;
      apply_axis_load(m, s, static_cast<std::size_t>(a), 1.0, m.unit_body_forces, m.unit_force);
      m.dynamics->loop_axis_column(m, s, a);
    }
    m.axis_mobility[a] =
        axis_dot_column(m, static_cast<std::size_t>(a), static_cast<std::size_t>(a));
    m.column_valid[a] = 1;
    if (m.axis_root[a] >= 0) {
      const double* q =
          s.getQ().getContiguousScalarData() + m.roots[static_cast<std::size_t>(m.axis_root[a])].q0;
      std::copy(q, q + 4, &m.column_root_quat[4 * static_cast<std::size_t>(a)]);
    }
  }
}

double axis_dot(const Multibody::Impl& m, std::size_t a, const SimTK::Vector& x) {
  if (!m.axes[a].loop) {
    // The friction sweeps ask this many times per substep.
    return m.axis_impl[a].sign * element(x, m.axis_u[a]);
  }
  const SimTK::Vector& g = m.loop_unit_force[a];
  double sum = 0;
  if (g.hasContiguousData() && x.hasContiguousData()) {
    const double* pg = g.getContiguousScalarData();
    const double* px = x.getContiguousScalarData();
    for (int i = 0; i < g.size(); ++i)
      sum += pg[i] * px[i];
  } else {
    for (int i = 0; i < g.size(); ++i)
      sum += g[i] * x[i];
  }
  return sum;
}

double axis_dot_column(const Multibody::Impl& m, std::size_t a, std::size_t b) {
  const AxisColumns& columns = m.minv_column;
  if (!m.axes[a].loop) return m.axis_impl[a].sign * columns.at(b, m.axis_u[a]);
  // g·column over the column's speeds: the terms elsewhere are exact zeros.
  const double* pg = contiguous_data(m.loop_unit_force[a]) + columns.u_begin[b];
  const double* pc = columns.of(b);
  double sum = 0;
  for (int i = 0, n = columns.size(b); i < n; ++i)
    sum += pg[i] * pc[i];
  return sum;
}

void keep_column(Multibody::Impl& m, std::size_t a, const double* solved, int u_begin, int u_end) {
  AxisColumns& c = m.minv_column;
  double* column = c.of(a);
  for (int u = c.u_begin[a]; u < c.u_end[a]; ++u)
    column[u - c.u_begin[a]] = u >= u_begin && u < u_end ? solved[u] : 0.0;
}

void allocate_axis_columns(Multibody::Impl& m) {
  const std::size_t axes = m.axes.size();
  AxisColumns& c = m.minv_column;
  c.start.assign(axes, 0);
  c.u_begin.assign(axes, 0);
  c.u_end.assign(axes, 0);
  std::size_t total = 0;
  for (std::size_t a = 0; a < axes; ++a) {
    const auto t = static_cast<std::size_t>(m.axis_tree[a]);
    c.start[a] = total;
    c.u_begin[a] = m.tree_u_begin[t];
    c.u_end[a] = m.tree_u_end[t];
    total += static_cast<std::size_t>(c.size(a));
  }
  c.values.assign(total, 0.0);
  const int nu = m.initial_state.getNU();
  m.column_scratch.assign(static_cast<std::size_t>(nu), 0.0);
  m.column_scratch_vector.resize(nu);
}

bool turning_keeps_mass(const Multibody::Impl& m, SimTK::MobilizedBodyIndex i,
                        const SimTK::State& s) {
  const auto& mob = m.matter.getMobilizedBody(i);
  const SimTK::Transform& X_BM = mob.getOutboardFrame(s);
  const SimTK::Vec3 axis = X_BM.R().z();
  const SimTK::MassProperties& mp = mob.getBodyMassProperties(s);
  const SimTK::Vec3 offset = mp.getMassCenter() - X_BM.p();
  const double scale = 1 + offset.norm();
  if (SimTK::cross(offset, axis).norm() > 1e-12 * scale) return false;
  const SimTK::Mat33 I(mp.calcCentralInertia().asSymMat33());
  const double along = ~axis * (I * axis);
  const double across = 0.5 * (I.trace() - along);
  const SimTK::Mat33 aa = axis * ~axis;
  const SimTK::Mat33 symmetric = along * aa + across * (SimTK::Mat33(1) - aa);
  return (I - symmetric).norm() <= 1e-9 * (1e-300 + std::abs(I.trace()));
}

void find_mass_matrix_coordinates(Multibody::Impl& m) {
  const SimTK::State& s = m.initial_state;
  m.q_shapes_mass.assign(static_cast<std::size_t>(s.getNQ()), 1);
  m.axis_root.assign(m.axes.size(), -1);
  m.column_root_quat.assign(4 * m.axes.size(), 0.0);
  // With loops the loop axes' g depends on every body's pose: keep every coordinate.
  if (m.matter.getNumConstraints() > 0) return;
  std::vector<char> has_children(static_cast<std::size_t>(m.matter.getNumBodies()), 0);
  for (SimTK::MobilizedBodyIndex i(1); i < m.matter.getNumBodies(); ++i)
    has_children[m.matter.getMobilizedBody(i).getParentMobilizedBody().getMobilizedBodyIndex()] = 1;
  for (SimTK::MobilizedBodyIndex i(1); i < m.matter.getNumBodies(); ++i) {
    const auto& mob = m.matter.getMobilizedBody(i);
    const auto q0 = static_cast<std::size_t>(mob.getFirstQIndex(s));
    // A root's translation: M (ground-frame generalized speeds) is translation invariant.
    // Its orientation: the columns of its tree's axes turn with it (rotate_with_root).
    if (SimTK::MobilizedBody::Free::isInstanceOf(mob) && mob.getParentMobilizedBody().isGround()) {
      for (std::size_t k = 0; k < 7; ++k)
        m.q_shapes_mass[q0 + k] = 0;
      m.roots.push_back({static_cast<int>(q0), mob.getFirstUIndex(s)});
      continue;
    }
    // A pin whose child is a leaf with its mass centre on the axis and an inertia symmetric
    // about it (a wheel, a rotor): turning it leaves the mass distribution unchanged.
    if (!SimTK::MobilizedBody::Pin::isInstanceOf(mob) || has_children[i]) continue;
    if (turning_keeps_mass(m, i, s)) m.q_shapes_mass[q0] = 0;
  }
  // Each tree axis's root, when that root is free.
  for (std::size_t a = 0; a < m.axes.size(); ++a) {
    if (m.axes[a].loop) continue;
    SimTK::MobilizedBodyIndex b = m.axis_impl[a].mobod;
    while (!m.matter.getMobilizedBody(b).getParentMobilizedBody().isGround())
      b = m.matter.getMobilizedBody(b).getParentMobilizedBody().getMobilizedBodyIndex();
    const auto& root = m.matter.getMobilizedBody(b);
    if (!SimTK::MobilizedBody::Free::isInstanceOf(root)) continue;
    for (std::size_t r = 0; r < m.roots.size(); ++r)
      if (m.roots[r].q0 == root.getFirstQIndex(s)) m.axis_root[a] = static_cast<int>(r);
  }
}

void clear_columns(Multibody::Impl& m) {
  std::fill(m.column_valid.begin(), m.column_valid.end(), 0);
  std::fill(m.axis_mobility.begin(), m.axis_mobility.end(), 0.0);
  for (auto& range : m.friction_ranges)
    range.valid = false;
}

}  // namespace s2sim::model
