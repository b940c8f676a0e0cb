// The small-tree fast path's equations (docs/models/multibody.md, "Fast path"): kinematics
// base to tip, the velocity-product accelerations, the loads each subtree needs (recursive
// Newton-Euler), the mass matrix from composite bodies, and a Cholesky factor per tree.
#include "model/tree_dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace s2sim::model {
namespace {

Mat3 rotation_about_z(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Mat3 r;
  r.m[0][0] = c;
  r.m[0][1] = -s;
  r.m[1][0] = s;
  r.m[1][1] = c;
  return r;
}

/// Simbody's body-fixed X then Y rotation (a Universal mobilizer's R_FM): Rx(a)·Ry(b).
Mat3 rotation_x_then_y(double a, double b) {
  const double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b);
  Mat3 r;
  r.m[0][0] = cb;
  r.m[0][1] = 0;
  r.m[0][2] = sb;
  r.m[1][0] = sa * sb;
  r.m[1][1] = ca;
  r.m[1][2] = -sa * cb;
  r.m[2][0] = -ca * sb;
  r.m[2][1] = sa;
  r.m[2][2] = ca * cb;
  return r;
}

/// Simbody's rotation of a quaternion (w, x, y, z), normalised first as its Quaternion does.
Mat3 rotation_of_quaternion(const double* q) {
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
  const double ww = w * w, xx = x * x, yy = y * y, zz = z * z;
  const double wx = w * x, wy = w * y, wz = w * z, xy = x * y, xz = x * z, yz = y * z;
  Mat3 r;
  r.m[0][0] = ww + xx - yy - zz;
  r.m[0][1] = 2 * (xy - wz);
  r.m[0][2] = 2 * (xz + wy);
  r.m[1][0] = 2 * (xy + wz);
  r.m[1][1] = ww - xx + yy - zz;
  r.m[1][2] = 2 * (yz - wx);
  r.m[2][0] = 2 * (xz - wy);
  r.m[2][1] = 2 * (yz + wx);
  r.m[2][2] = ww - xx - yy + zz;
  return r;
}

/// R·I·Rᵀ.
Mat3 rotate_inertia(const Mat3& R, const Mat3& I) {
  return R * I * R.transposed();
}

/// I + m·(|d|²·E − d·dᵀ): an inertia about a point moved by d from the centre of mass.
void add_parallel_axis(Mat3& I, double mass, const Vec3& d) {
  const double dd = dot(d, d);
  const double v[3] = {d.x, d.y, d.z};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      I.m[i][j] += mass * ((i == j ? dd : 0.0) - v[i] * v[j]);
}

Mat3 operator+(const Mat3& a, const Mat3& b) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r.m[i][j] = a.m[i][j] + b.m[i][j];
  return r;
}

int dofs_of(TreeDynamics::Joint joint) {
  switch (joint) {
    case TreeDynamics::Joint::free:
      return 6;
    case TreeDynamics::Joint::pin:
    case TreeDynamics::Joint::slider:
      return 1;
    case TreeDynamics::Joint::universal:
      return 2;
    case TreeDynamics::Joint::ball:
      return 3;
    case TreeDynamics::Joint::weld:
      return 0;
  }
  return 0;
}

}  // namespace

TreeDynamics::TreeDynamics(const std::vector<BodySpec>& bodies, int nq, int nu) : nq_(nq), nu_(nu) {
  bodies_.resize(bodies.size() + 1);  // [0]: Ground, no mass, no parent
  bodies_[0].parent = -1;
  tree_of_body_.assign(bodies_.size(), -1);
  int next_u = 0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Body& b = bodies_[i + 1];
    static_cast<BodySpec&>(b) = bodies[i];
    b.dofs = dofs_of(b.joint);
    b.X_MB = b.X_BM.inverse();
    if (b.parent < 0 || b.parent > static_cast<int>(i))
      throw std::logic_error("TreeDynamics: a body's parent must come before it");
    if (b.dofs > 0 && b.u0 != next_u)
      throw std::logic_error("TreeDynamics: speeds must be numbered body by body");
    next_u += b.dofs;
    const int parent_tree = tree_of_body_[static_cast<std::size_t>(b.parent)];
    if (parent_tree >= 0) {
      tree_of_body_[i + 1] = parent_tree;
      Tree& t = trees_[static_cast<std::size_t>(parent_tree)];
      // A tree's speeds must stay one contiguous range for its block of the mass matrix.
      if (b.dofs > 0 && t.u_end != b.u0)
        throw std::logic_error("TreeDynamics: a tree's speeds must be contiguous");
      t.u_end += b.dofs;
    } else {
      tree_of_body_[i + 1] = static_cast<int>(trees_.size());
      trees_.push_back({b.u0, b.u0 + b.dofs, 0});
    }
  }
  if (next_u != nu || nq < nu) throw std::logic_error("TreeDynamics: state sizes do not match");
  int offset = 0;
  for (Tree& t : trees_) {
    t.matrix = offset;
    offset += (t.u_end - t.u_begin) * (t.u_end - t.u_begin);
  }
  mass_.assign(static_cast<std::size_t>(offset), 0.0);
  rhs_.assign(static_cast<std::size_t>(nu), 0.0);
  last_q_.assign(static_cast<std::size_t>(nq), 0.0);
  last_u_.assign(static_cast<std::size_t>(nu), 0.0);
  speed_parent_.assign(static_cast<std::size_t>(nu), -1);
  for (std::size_t i = 1; i < bodies_.size(); ++i) {
    const Body& b = bodies_[i];
    if (b.dofs == 0) continue;
    const Tree& t = trees_[static_cast<std::size_t>(tree_of_body_[i])];
    int a = b.parent;  // a weld has no speeds
    while (a > 0 && bodies_[static_cast<std::size_t>(a)].dofs == 0)
      a = bodies_[static_cast<std::size_t>(a)].parent;
    const Body& above = bodies_[static_cast<std::size_t>(a)];
    speed_parent_[static_cast<std::size_t>(b.u0)] =
        a > 0 ? above.u0 + above.dofs - 1 - t.u_begin : -1;
    for (int c = 1; c < b.dofs; ++c)
      speed_parent_[static_cast<std::size_t>(b.u0 + c)] = b.u0 + c - 1 - t.u_begin;
  }
  const std::size_t n = bodies_.size();
  pose_.assign(n, Pose{});
  twist_.assign(n, Twist{});
  joint_origin_.assign(n, Vec3{});
  frame_rotation_.assign(n, Mat3{});
  relative_angular_.assign(n, Vec3{});
  relative_linear_.assign(n, Vec3{});
  relative_bias_.assign(n, Vec3{});
  bias_increment_.assign(n, Twist{});
  acceleration_.assign(n, Twist{});
  reaction_load_.assign(n, Wrench{});
  column_.assign(static_cast<std::size_t>(nu), Twist{});
  bias_acceleration_.assign(n, Twist{});
  subtree_load_.assign(n, Wrench{});
  composite_.assign(n, Composite{});
}

void TreeDynamics::set_mass(int body, double mass_kg, const Vec3& com_B,
                            const Mat3& central_inertia_B) {
  Body& b = bodies_.at(static_cast<std::size_t>(body));
  b.mass_kg = mass_kg;
  b.com_B = com_B;
  b.central_inertia_B = central_inertia_B;
}

void TreeDynamics::kinematics(const double* q, const double* u) {
  const bool same_q = kinematics_valid_ && std::equal(q, q + nq_, last_q_.begin());
  if (same_q && std::equal(u, u + nu_, last_u_.begin())) return;
  if (!same_q) {
    std::copy(q, q + nq_, last_q_.begin());
    positions(q);
    ++configuration_;
  }
  std::copy(u, u + nu_, last_u_.begin());
  kinematics_valid_ = true;
  velocities(u);
}

void TreeDynamics::positions(const double* q) {
  for (std::size_t i = 1; i < bodies_.size(); ++i) {
    const Body& b = bodies_[i];
    const auto p = static_cast<std::size_t>(b.parent);
    const Pose X_GF = pose_[p] * b.X_PF;
    Pose X_FM;
    const double* qb = q + b.q0;
    switch (b.joint) {
      case Joint::free:
        X_FM = {{qb[4], qb[5], qb[6]}, rotation_of_quaternion(qb)};
        break;
      case Joint::pin:
        X_FM.rotation = rotation_about_z(qb[0]);
        break;
      case Joint::slider:
        X_FM.position = {qb[0], 0, 0};
        break;
      case Joint::universal:
        X_FM.rotation = rotation_x_then_y(qb[0], qb[1]);
        break;
      case Joint::ball:
        X_FM.rotation = rotation_of_quaternion(qb);
        break;
      case Joint::weld:
        break;
    }
    const Pose X_GM = X_GF * X_FM;
    pose_[i] = X_GM * b.X_MB;
    joint_origin_[i] = X_GM.position;
    const Mat3& R_GF = X_GF.rotation;
    frame_rotation_[i] = R_GF;
    const Vec3 d = pose_[i].position - X_GM.position;  // M origin to body origin
    // Columns: the body's velocity per unit speed, its parent held.
    Twist* col = &column_[static_cast<std::size_t>(b.u0)];
    switch (b.joint) {
      case Joint::free:
        for (int k = 0; k < 3; ++k) {
          const Vec3 e = R_GF.column(k);
          col[k] = {e, cross(e, d)};
          col[3 + k] = {Vec3{}, e};
        }
        break;
      case Joint::pin: {
        const Vec3 z = R_GF.column(2);
        col[0] = {z, cross(z, d)};
        break;
      }
      case Joint::slider:
        col[0] = {Vec3{}, R_GF.column(0)};
        break;
      case Joint::ball:
        for (int k = 0; k < 3; ++k) {
          const Vec3 e = R_GF.column(k);
          col[k] = {e, cross(e, d)};
        }
        break;
      case Joint::universal: {
        // F's X, then the new Y: F's Y turned about X by q0.
        const Vec3 x = R_GF.column(0);
        const Vec3 y = R_GF * Vec3{0, std::cos(qb[0]), std::sin(qb[0])};
        col[0] = {x, cross(x, d)};
        col[1] = {y, cross(y, d)};
        break;
      }
      case Joint::weld:
        break;
    }
  }
}

void TreeDynamics::velocities(const double* u) {
  for (std::size_t i = 1; i < bodies_.size(); ++i) {
    const Body& b = bodies_[i];
    const auto p = static_cast<std::size_t>(b.parent);
    Vec3 w_FM, v_FM;  // in F
    const double* ub = u + b.u0;
    switch (b.joint) {
      case Joint::free:
        w_FM = {ub[0], ub[1], ub[2]};
        v_FM = {ub[3], ub[4], ub[5]};
        break;
      case Joint::ball:
        w_FM = {ub[0], ub[1], ub[2]};
        break;
      case Joint::pin:
        w_FM = {0, 0, ub[0]};
        break;
      case Joint::slider:
        v_FM = {ub[0], 0, 0};
        break;
      case Joint::universal:
      case Joint::weld:
        break;
    }
    const Mat3& R_GF = frame_rotation_[i];
    Vec3 w_rel = R_GF * w_FM;
    const Vec3 v_rel = R_GF * v_FM;
    relative_bias_[i] = Vec3{};
    if (b.joint == Joint::universal) {  // its columns' axes, the second turning with the first
      const Vec3 w_1 = column_[static_cast<std::size_t>(b.u0)].angular_rad_s * ub[0];
      const Vec3 w_2 = column_[static_cast<std::size_t>(b.u0) + 1].angular_rad_s * ub[1];
      w_rel = w_1 + w_2;
      relative_bias_[i] = cross(w_1, w_2);
    }
    relative_angular_[i] = w_rel;
    relative_linear_[i] = v_rel;
    const Twist& V_P = twist_[p];
    const Vec3 r = pose_[i].position - pose_[p].position;  // parent origin to body origin
    const Vec3 d = pose_[i].position - joint_origin_[i];   // M origin to body origin
    twist_[i] = {V_P.angular_rad_s + w_rel,
                 V_P.linear_m_s + cross(V_P.angular_rad_s, r) + v_rel + cross(w_rel, d)};
  }
}

void TreeDynamics::accelerations(const double* body_loads, const double* mobility_forces,
                                 double* udot) {
  bias_accelerations();
  subtree_loads(body_loads);
  mass_matrix_and_right_side(mobility_forces);
  for (const Tree& t : trees_) {
    factor(t);
    substitute(t, &rhs_[static_cast<std::size_t>(t.u_begin)], udot + t.u_begin);
  }
}

void TreeDynamics::bias_accelerations() {
  const std::size_t n = bodies_.size();
  // Velocity-product accelerations, base to tip (u' = 0): the time derivative of
  // V_B = shift(V_P) + V_rel, the mobilizer's axes turning with the parent and the arm d from
  // M's origin to B's with the body.
  for (std::size_t i = 1; i < n; ++i) {
    const auto p = static_cast<std::size_t>(bodies_[i].parent);
    const Vec3& w_P = twist_[p].angular_rad_s;
    const Vec3& w_rel = relative_angular_[i];
    const Twist& A_P = bias_acceleration_[p];
    const Vec3 r = pose_[i].position - pose_[p].position;
    const Vec3 d = pose_[i].position - joint_origin_[i];
    // The relative ω's change at u' = 0: its axes turning with the parent, and a Universal's
    // second axis with its first.
    const Vec3 w_rel_rate = cross(w_P, w_rel) + relative_bias_[i];
    const Vec3 c1 = cross(w_P, twist_[i].linear_m_s - twist_[p].linear_m_s);
    const Vec3 c2 = cross(w_P, relative_linear_[i]), c3 = cross(w_rel_rate, d);
    const Vec3 c4 = cross(w_rel, cross(twist_[i].angular_rad_s, d));
    bias_acceleration_[i] = {A_P.angular_rad_s + w_rel_rate,
                             A_P.linear_m_s + cross(A_P.angular_rad_s, r) + c1 + c2 + c3 + c4};
    bias_increment_[i] = {w_rel_rate, c1 + c2 + c3 + c4};  // for reactions()
  }
}

const Wrench& TreeDynamics::add_own_load(std::size_t i, const Twist& A, const double* body_loads,
                                         Wrench& load, Vec3& c, Mat3& I) const {
  const Body& b = bodies_[i];
  const Mat3& R = pose_[i].rotation;
  c = R * b.com_B;
  const Vec3& w = twist_[i].angular_rad_s;
  const Vec3 a_com = A.linear_m_s + cross(A.angular_rad_s, c) + cross(w, cross(w, c));
  I = rotate_inertia(R, b.central_inertia_B);
  const Vec3 momentum_rate = a_com * b.mass_kg;
  const double* applied = body_loads + 6 * i;
  load.force_N += momentum_rate - Vec3{applied[3], applied[4], applied[5]};
  load.torque_Nm += I * A.angular_rad_s + cross(w, I * w) + cross(c, momentum_rate) -
                    Vec3{applied[0], applied[1], applied[2]};
  return load;
}

Vec3 TreeDynamics::frame_origin(int body) const {
  const Body& b = bodies_[static_cast<std::size_t>(body)];
  return (pose_[static_cast<std::size_t>(b.parent)] * b.X_PF).position;  // as positions() has it
}

void TreeDynamics::reactions(const double* body_loads, const double* udot, Wrench* at_M) {
  const std::size_t n = bodies_.size();
  // Each body's acceleration for udot, base to tip: the parent's carried over, the velocity
  // products of its own mobilizer (bias_increment_) and its own speeds' columns.
  for (std::size_t i = 1; i < n; ++i) {
    const Body& b = bodies_[i];
    const auto p = static_cast<std::size_t>(b.parent);
    const Twist& A_P = acceleration_[p];
    const Vec3 r = pose_[i].position - pose_[p].position;
    Twist A{A_P.angular_rad_s + bias_increment_[i].angular_rad_s,
            A_P.linear_m_s + cross(A_P.angular_rad_s, r) + bias_increment_[i].linear_m_s};
    for (int k = b.u0; k < b.u0 + b.dofs; ++k) {
      const Twist& h = column_[static_cast<std::size_t>(k)];
      A.angular_rad_s += h.angular_rad_s * udot[k];
      A.linear_m_s += h.linear_m_s * udot[k];
    }
    acceleration_[i] = A;
    reaction_load_[i] = Wrench{};
  }
  // Tip to base: what each subtree needs for them less what is applied to it (Newton–Euler
  // about each centre of mass, moved to the body's origin, summed into the parent's): what the
  // parent gives it through the mobilizer, here moved to M's origin.
  for (std::size_t i = n - 1; i >= 1; --i) {
    const Body& b = bodies_[i];
    Vec3 c;
    Mat3 I;
    const Wrench& load = add_own_load(i, acceleration_[i], body_loads, reaction_load_[i], c, I);
    at_M[i] = {load.torque_Nm + cross(pose_[i].position - joint_origin_[i], load.force_N),
               load.force_N};
    const auto p = static_cast<std::size_t>(b.parent);
    if (p == 0) continue;
    reaction_load_[p].force_N += load.force_N;
    reaction_load_[p].torque_Nm +=
        load.torque_Nm + cross(pose_[i].position - pose_[p].position, load.force_N);
  }
}

void TreeDynamics::subtree_loads(const double* body_loads) {
  const std::size_t n = bodies_.size();
  for (std::size_t i = 1; i < n; ++i) {
    subtree_load_[i] = Wrench{};
    composite_[i] = Composite{0.0, Vec3{}, Mat3{{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}}};
  }
  // Tip to base: the load each body needs for those accelerations less what is applied
  // (Newton-Euler about its centre of mass, moved to its origin), and its mass, first and
  // second moments about its origin, each subtree's summed into its parent's.
  for (std::size_t i = n - 1; i >= 1; --i) {
    const Body& b = bodies_[i];
    Vec3 c;
    Mat3 I;
    const Wrench& load = add_own_load(i, bias_acceleration_[i], body_loads, subtree_load_[i], c, I);
    Composite& comp = composite_[i];
    comp.mass_kg += b.mass_kg;
    comp.first_moment += c * b.mass_kg;
    comp.second_moment = comp.second_moment + I;
    add_parallel_axis(comp.second_moment, b.mass_kg, c);
    const auto p = static_cast<std::size_t>(b.parent);
    if (p == 0) continue;
    const Vec3 delta = pose_[i].position - pose_[p].position;
    subtree_load_[p].force_N += load.force_N;
    subtree_load_[p].torque_Nm += load.torque_Nm + cross(delta, load.force_N);
    Composite& parent = composite_[p];
    parent.mass_kg += comp.mass_kg;
    parent.first_moment += comp.first_moment + delta * comp.mass_kg;
    // J about the parent's origin: J + 2(S·δ)E − (S·δᵀ + δ·Sᵀ) + M(|δ|²E − δ·δᵀ).
    Mat3 J = comp.second_moment;
    add_parallel_axis(J, comp.mass_kg, delta);
    const double s_dot_d = dot(comp.first_moment, delta);
    const double S[3] = {comp.first_moment.x, comp.first_moment.y, comp.first_moment.z};
    const double D[3] = {delta.x, delta.y, delta.z};
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k)
        J.m[r][k] += (r == k ? 2 * s_dot_d : 0.0) - (S[r] * D[k] + D[r] * S[k]);
    parent.second_moment = parent.second_moment + J;
  }
}

void TreeDynamics::mass_matrix_and_right_side(const double* mobility_forces) {
  const std::size_t n = bodies_.size();
  // Only a speed's and its ancestors' entries are written: the others are zero in M and in its
  // factor, which never reads them.
  auto ancestor_origin = [&](int a) { return pose_[static_cast<std::size_t>(a)].position; };
  // The mass matrix, lower triangle: M_kj = h_kᵀ·(the composite of j's body moved by h_j),
  // for k of j's body or an ancestor (the only non-zeros of row j). Right side: τ − bias.
  for (std::size_t i = 1; i < n; ++i) {
    const Body& b = bodies_[i];
    if (b.dofs == 0) continue;
    const Tree& t = trees_[static_cast<std::size_t>(tree_of_body_[i])];
    const int size = t.u_end - t.u_begin;
    double* block = &mass_[static_cast<std::size_t>(t.matrix)];
    const Composite& comp = composite_[i];
    for (int c = 0; c < b.dofs; ++c) {
      const int j = b.u0 + c;
      const Twist& h = column_[static_cast<std::size_t>(j)];
      rhs_[static_cast<std::size_t>(j)] =
          mobility_forces[j] - (dot(h.angular_rad_s, subtree_load_[i].torque_Nm) +
                                dot(h.linear_m_s, subtree_load_[i].force_N));
      const Vec3 L = h.linear_m_s * comp.mass_kg + cross(h.angular_rad_s, comp.first_moment);
      const Vec3 H = cross(comp.first_moment, h.linear_m_s) + comp.second_moment * h.angular_rad_s;
      double* row = block + (j - t.u_begin) * size;  // row[k - t.u_begin]: column k
      for (int k = b.u0; k <= j; ++k)
        row[k - t.u_begin] = dot(column_[static_cast<std::size_t>(k)].angular_rad_s, H) +
                             dot(column_[static_cast<std::size_t>(k)].linear_m_s, L);
      for (int a = b.parent; a > 0; a = bodies_[static_cast<std::size_t>(a)].parent) {
        const Body& ancestor = bodies_[static_cast<std::size_t>(a)];
        const Vec3 H_a = H + cross(pose_[i].position - ancestor_origin(a), L);
        for (int k = ancestor.u0; k < ancestor.u0 + ancestor.dofs; ++k)
          row[k - t.u_begin] = dot(column_[static_cast<std::size_t>(k)].angular_rad_s, H_a) +
                               dot(column_[static_cast<std::size_t>(k)].linear_m_s, L);
      }
    }
  }
}

void TreeDynamics::factor(const Tree& t) {
  // M = Lᵀ·L, tip to base (RBDA §6.5): row k of L has non-zeros only at k's ancestors, as M
  // does, so nothing fills in between branches. The humanoid's 26 speeds: about a third of a
  // dense Cholesky's products, 12.2 k instructions against its 20.1 k (callgrind).
  const int n = t.u_end - t.u_begin;
  double* M = &mass_[static_cast<std::size_t>(t.matrix)];
  const int* parent = &speed_parent_[static_cast<std::size_t>(t.u_begin)];
  bool positive = true;
  for (int k = n; k-- > 0;) {
    double* row_k = M + k * n;
    positive = positive && row_k[k] > 0;
    const double d = std::sqrt(row_k[k]);
    row_k[k] = d;
    for (int i = parent[k]; i >= 0; i = parent[i])
      row_k[i] /= d;
    for (int i = parent[k]; i >= 0; i = parent[i]) {
      double* row_i = M + i * n;
      const double l_ki = row_k[i];
      for (int j = i; j >= 0; j = parent[j])
        row_i[j] -= l_ki * row_k[j];
    }
  }
  if (!positive) throw std::runtime_error("the mass matrix is not positive definite");
}

void TreeDynamics::substitute(const Tree& t, const double* b, double* x) const {
  const int n = t.u_end - t.u_begin;
  const double* L = &mass_[static_cast<std::size_t>(t.matrix)];
  const int* parent = &speed_parent_[static_cast<std::size_t>(t.u_begin)];
  if (x != b) std::copy(b, b + n, x);
  // Lᵀ·y = b, tip to base: each y_k is final once its descendants gave their shares, and
  // gives its own to its ancestors (a unit b touches only its own path to the base).
  for (int k = n; k-- > 0;) {
    if (x[k] == 0.0) continue;
    const double* row_k = L + k * n;
    const double y = x[k] / row_k[k];
    x[k] = y;
    for (int i = parent[k]; i >= 0; i = parent[i])
      x[i] -= row_k[i] * y;
  }
  // L·x = y, base to tip.
  for (int k = 0; k < n; ++k) {
    const double* row_k = L + k * n;
    double v = x[k];
    for (int i = parent[k]; i >= 0; i = parent[i])
      v -= row_k[i] * x[i];
    x[k] = v / row_k[k];
  }
}

void TreeDynamics::generalized_forces(const double* body_loads, double* f) {
  const std::size_t n = bodies_.size();
  for (std::size_t i = 1; i < n; ++i) {
    const double* l = body_loads + 6 * i;
    subtree_load_[i] = {{l[0], l[1], l[2]}, {l[3], l[4], l[5]}};  // (torque, force)
  }
  // Tip to base: each subtree's load about its body's origin, then each speed's share.
  for (std::size_t i = n - 1; i >= 1; --i) {
    const Body& b = bodies_[i];
    const Wrench& load = subtree_load_[i];
    for (int k = b.u0; k < b.u0 + b.dofs; ++k) {
      const Twist& h = column_[static_cast<std::size_t>(k)];
      f[k] = dot(h.angular_rad_s, load.torque_Nm) + dot(h.linear_m_s, load.force_N);
    }
    const auto p = static_cast<std::size_t>(b.parent);
    if (p == 0) continue;
    subtree_load_[p].force_N += load.force_N;
    subtree_load_[p].torque_Nm +=
        load.torque_Nm + cross(pose_[i].position - pose_[p].position, load.force_N);
  }
}

void TreeDynamics::solve_tree_of(int body, const double* g, double* x, int& u_begin,
                                 int& u_end) const {
  const Tree& t = trees_[static_cast<std::size_t>(tree_of_body_[static_cast<std::size_t>(body)])];
  u_begin = t.u_begin;
  u_end = t.u_end;
  substitute(t, g + t.u_begin, x + t.u_begin);
}

void TreeDynamics::solve(const double* g, double* x) const {
  for (const Tree& t : trees_) {
    bool zero = true;
    for (int i = t.u_begin; zero && i < t.u_end; ++i)
      zero = g[i] == 0.0;
    if (zero) {
      for (int i = t.u_begin; i < t.u_end; ++i)
        x[i] = 0.0;
      continue;
    }
    substitute(t, g + t.u_begin, x + t.u_begin);
  }
}

}  // namespace s2sim::model
