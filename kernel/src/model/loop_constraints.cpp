// The loop joints' constraints in the tree's coordinates (loop_constraints.hpp; equations in
// docs/models/multibody.md, "Loops on the fast path").
#include "model/loop_constraints.hpp"

#include "common/cholesky.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace s2sim::model {
namespace {

/// Relative size below which a pivot of the rows' system counts as a redundant row.
constexpr double kRankTolerance = 1e-12;

/// The acceleration of a point of a body at p (Ground) with every u' zero.
Vec3 point_bias(const TreeDynamics& tree, int body, const Vec3& p) {
  const Twist& A = tree.bias_acceleration(body);
  const Vec3& w = tree.twist(body).angular_rad_s;
  const Vec3 r = p - tree.pose(body).position;
  return A.linear_m_s + cross(A.angular_rad_s, r) + cross(w, cross(w, r));
}

Vec3 point_velocity(const TreeDynamics& tree, int body, const Vec3& p) {
  const Twist& V = tree.twist(body);
  return V.linear_m_s + cross(V.angular_rad_s, p - tree.pose(body).position);
}

double rms(const std::vector<double>& e) {
  double sum = 0;
  for (double v : e)
    sum += v * v;
  return e.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(e.size()));
}

}  // namespace

LoopConstraints::LoopConstraints(Spec spec, int speeds)
    : balls_(std::move(spec.balls)),
      angles_(std::move(spec.angles)),
      lines_(std::move(spec.lines)),
      couplers_(std::move(spec.couplers)),
      nu_(speeds) {
  rows_ = 3 * static_cast<int>(balls_.size()) + static_cast<int>(angles_.size()) +
          2 * static_cast<int>(lines_.size()) + static_cast<int>(couplers_.size());
  for (const Line& l : lines_) {
    // Two normals of the line, fixed in its body: any pair spans the same errors.
    const Vec3& d = l.direction_B;
    const Vec3 helper = std::abs(d.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 n1 = cross(d, helper) / norm(cross(d, helper));
    line_normals_.push_back(n1);
    line_normals_.push_back(cross(d, n1));
  }
  line_places_.assign(lines_.size(), LinePlace{});
  const auto rows = static_cast<std::size_t>(rows_);
  const auto nu = static_cast<std::size_t>(nu_);
  points_.assign(balls_.size(), RowPoint{});
  base_axis_.assign(angles_.size(), Vec3{});
  follower_axis_.assign(angles_.size(), Vec3{});
  error_.assign(rows, 0.0);
  G_.assign(rows * nu, 0.0);
  minv_gt_.assign(rows * nu, 0.0);
  A_.assign(rows * rows, 0.0);
  rhs_.assign(rows, 0.0);
  x_.assign(rows, 0.0);
  solve_scratch_.assign(rows * rows + 2 * rows, 0.0);
  weight_.assign(nu, 1.0);
  order_.assign(rows, 0);
}

void LoopConstraints::place(const TreeDynamics& tree) {
  if (placed_at_ == tree.configuration()) return;
  placed_at_ = tree.configuration();
  int row = 0;
  for (std::size_t i = 0; i < balls_.size(); ++i) {
    const Ball& b = balls_[i];
    RowPoint& p = points_[i];
    p.p1 = tree.pose(b.body1) * b.point1_B1;
    p.p2 = tree.pose(b.body2) * b.point2_B2;
    const Vec3 e = p.p2 - p.p1;
    error_[static_cast<std::size_t>(row++)] = e.x;
    error_[static_cast<std::size_t>(row++)] = e.y;
    error_[static_cast<std::size_t>(row++)] = e.z;
  }
  for (std::size_t i = 0; i < angles_.size(); ++i) {
    const Angle& a = angles_[i];
    base_axis_[i] = tree.pose(a.base).rotation * a.axis_base_B;
    follower_axis_[i] = tree.pose(a.follower).rotation * a.axis_follower_F;
    error_[static_cast<std::size_t>(row++)] = dot(base_axis_[i], follower_axis_[i]) - a.cos_angle;
  }
  for (std::size_t i = 0; i < lines_.size(); ++i) {
    const Line& l = lines_[i];
    LinePlace& at = line_places_[i];
    const Pose& X_GB = tree.pose(l.base);
    at.p = X_GB * l.point_B;
    at.s = tree.pose(l.follower) * l.point_F;
    for (int k = 0; k < 2; ++k) {
      at.n[k] = X_GB.rotation * line_normals_[2 * i + static_cast<std::size_t>(k)];
      error_[static_cast<std::size_t>(row++)] = dot(at.s - at.p, at.n[k]);
    }
  }
  const double* q = tree.coordinates();
  for (const Coupler& c : couplers_)
    error_[static_cast<std::size_t>(row++)] = q[c.follower_q] - c.ratio * q[c.leader_q] - c.offset;
}

double LoopConstraints::rms_position_error(const TreeDynamics& tree) {
  place(tree);
  return rms(error_);
}

void LoopConstraints::add_point_row(const TreeDynamics& tree, int row, int body, const Vec3& p,
                                    const Vec3& direction, double sign) {
  double* g = &G_[static_cast<std::size_t>(row * nu_)];
  for (int a = body; a > 0; a = tree.parent(a)) {
    const Vec3 r = p - tree.pose(a).position;
    for (int k = tree.first_speed(a); k < tree.first_speed(a) + tree.speed_count(a); ++k) {
      const Twist& h = tree.column(k);
      g[k] += sign * dot(direction, h.linear_m_s + cross(h.angular_rad_s, r));
    }
  }
}

void LoopConstraints::add_angular_row(const TreeDynamics& tree, int row, int body,
                                      const Vec3& direction, double sign) {
  double* g = &G_[static_cast<std::size_t>(row * nu_)];
  for (int a = body; a > 0; a = tree.parent(a))
    for (int k = tree.first_speed(a); k < tree.first_speed(a) + tree.speed_count(a); ++k)
      g[k] += sign * dot(direction, tree.column(k).angular_rad_s);
}

void LoopConstraints::jacobian(const TreeDynamics& tree) {
  if (jacobian_at_ == tree.configuration()) return;
  jacobian_at_ = tree.configuration();
  std::fill(G_.begin(), G_.end(), 0.0);
  int row = 0;
  const Vec3 unit[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  // A ball: v(p2) − v(C), C the point of body 1 where p2 is now, as Simbody's BallImpl (not
  // p1: the two differ by the error, and so would the position projection's second step).
  for (std::size_t i = 0; i < balls_.size(); ++i, row += 3)
    for (int c = 0; c < 3; ++c) {
      add_point_row(tree, row + c, balls_[i].body2, points_[i].p2, unit[c], 1.0);
      add_point_row(tree, row + c, balls_[i].body1, points_[i].p2, unit[c], -1.0);
    }
  for (std::size_t i = 0; i < angles_.size(); ++i, ++row) {  // (ω_F − ω_B)·(f × b)
    const Vec3 n = cross(follower_axis_[i], base_axis_[i]);
    add_angular_row(tree, row, angles_[i].follower, n, 1.0);
    add_angular_row(tree, row, angles_[i].base, n, -1.0);
  }
  // A line: (v(s) of the follower − v(s) of the base's point at s)·n, n turning with the base.
  for (std::size_t i = 0; i < lines_.size(); ++i)
    for (int k = 0; k < 2; ++k, ++row) {
      const LinePlace& at = line_places_[i];
      add_point_row(tree, row, lines_[i].follower, at.s, at.n[k], 1.0);
      add_point_row(tree, row, lines_[i].base, at.s, at.n[k], -1.0);
    }
  for (const Coupler& c : couplers_) {  // e_f − ratio·e_l (the rows were zeroed above)
    double* g = &G_[static_cast<std::size_t>(row++ * nu_)];
    g[c.follower_u] += 1.0;
    g[c.leader_u] -= c.ratio;
  }
}

void LoopConstraints::solve_rows(const std::vector<double>& right, const double* weight) {
  // The lower triangle of G·D·R (all semidefinite_solve reads).
  for (int r = 0; r < rows_; ++r) {
    const double* gr = &G_[static_cast<std::size_t>(r * nu_)];
    for (int c = 0; c <= r; ++c) {
      const double* wc = &right[static_cast<std::size_t>(c * nu_)];
      double sum = 0;
      if (weight != nullptr) {
        for (int k = 0; k < nu_; ++k)
          sum += gr[k] * weight[k] * wc[k];
      } else {
        for (int k = 0; k < nu_; ++k)
          sum += gr[k] * wc[k];
      }
      A_[static_cast<std::size_t>(r * rows_ + c)] = sum;
    }
  }
  common::semidefinite_solve(A_.data(), rows_, rhs_.data(), x_.data(), order_.data(),
                             solve_scratch_.data(), kRankTolerance);
}

void LoopConstraints::constrain_accelerations(TreeDynamics& tree, double* udot) {
  place(tree);
  jacobian(tree);
  for (int r = 0; r < rows_; ++r)
    tree.solve(&G_[static_cast<std::size_t>(r * nu_)],
               &minv_gt_[static_cast<std::size_t>(r * nu_)]);
  // The right side: G·u'_free plus the constraints' accelerations at u' = 0 (Ġ·u).
  int row = 0;
  for (std::size_t i = 0; i < balls_.size(); ++i) {
    const Vec3 bias = point_bias(tree, balls_[i].body2, points_[i].p2) -
                      point_bias(tree, balls_[i].body1, points_[i].p2);  // at C, as G
    rhs_[static_cast<std::size_t>(row++)] = bias.x;
    rhs_[static_cast<std::size_t>(row++)] = bias.y;
    rhs_[static_cast<std::size_t>(row++)] = bias.z;
  }
  for (std::size_t i = 0; i < angles_.size(); ++i) {
    const Angle& a = angles_[i];
    const Vec3& f = follower_axis_[i];
    const Vec3& b = base_axis_[i];
    const Vec3& w_F = tree.twist(a.follower).angular_rad_s;
    const Vec3& w_B = tree.twist(a.base).angular_rad_s;
    const Vec3 alpha = tree.bias_acceleration(a.follower).angular_rad_s -
                       tree.bias_acceleration(a.base).angular_rad_s;
    const Vec3 n_rate = cross(cross(w_F, f), b) + cross(f, cross(w_B, b));
    rhs_[static_cast<std::size_t>(row++)] = dot(alpha, cross(f, b)) + dot(w_F - w_B, n_rate);
  }
  for (std::size_t i = 0; i < lines_.size(); ++i) {
    // e = (s − p)·n: ë at u' = 0 is (a_S − a_P − α_B × r − ω_B × (v_S − v_P))·n
    // + (v_S − v_P − ω_B × r)·(ω_B × n), r = s − p.
    const Line& l = lines_[i];
    const LinePlace& at = line_places_[i];
    const Vec3& w_B = tree.twist(l.base).angular_rad_s;
    const Vec3 r = at.s - at.p;
    const Vec3 v_S = point_velocity(tree, l.follower, at.s);
    const Vec3 v_P = point_velocity(tree, l.base, at.p);
    const Vec3 a = point_bias(tree, l.follower, at.s) - point_bias(tree, l.base, at.p) -
                   cross(tree.bias_acceleration(l.base).angular_rad_s, r) - cross(w_B, v_S - v_P);
    const Vec3 v = v_S - v_P - cross(w_B, r);
    for (int k = 0; k < 2; ++k)
      rhs_[static_cast<std::size_t>(row++)] = dot(a, at.n[k]) + dot(v, cross(w_B, at.n[k]));
  }
  for (std::size_t i = 0; i < couplers_.size(); ++i)  // a constant G: Ġ·u = 0
    rhs_[static_cast<std::size_t>(row++)] = 0.0;
  for (int r = 0; r < rows_; ++r) {
    const double* g = &G_[static_cast<std::size_t>(r * nu_)];
    double sum = 0;
    for (int k = 0; k < nu_; ++k)
      sum += g[k] * udot[k];
    rhs_[static_cast<std::size_t>(r)] += sum;
  }
  solve_rows(minv_gt_, nullptr);
  for (int r = 0; r < rows_; ++r) {
    const double lambda = x_[static_cast<std::size_t>(r)];
    if (lambda == 0.0) continue;
    const double* y = &minv_gt_[static_cast<std::size_t>(r * nu_)];
    for (int k = 0; k < nu_; ++k)
      udot[k] -= lambda * y[k];
  }
}

bool LoopConstraints::project_speeds(const TreeDynamics& tree, double* u, double tolerance) {
  place(tree);
  jacobian(tree);
  for (int r = 0; r < rows_; ++r) {
    const double* g = &G_[static_cast<std::size_t>(r * nu_)];
    double sum = 0;
    for (int k = 0; k < nu_; ++k)
      sum += g[k] * u[k];
    rhs_[static_cast<std::size_t>(r)] = sum;
  }
  if (!(rms(rhs_) > tolerance)) return false;
  // Simbody's weights on the change (SimbodyMatterSubsystemRep::projectU): a speed above 1
  // may change in proportion to itself, |Eu·du| least with Eu_k = min(1, 1/|u_k|); the step
  // is D·Gᵀ·y with D = Eu⁻².
  for (int k = 0; k < nu_; ++k)
    weight_[static_cast<std::size_t>(k)] = std::max(1.0, u[k] * u[k]);
  solve_rows(G_, weight_.data());
  for (int r = 0; r < rows_; ++r) {
    const double y = x_[static_cast<std::size_t>(r)];
    const double* g = &G_[static_cast<std::size_t>(r * nu_)];
    for (int k = 0; k < nu_; ++k)
      u[k] -= y * weight_[static_cast<std::size_t>(k)] * g[k];
  }
  return true;
}

bool LoopConstraints::position_correction(const TreeDynamics& tree, double tolerance, double* du) {
  place(tree);
  if (!(rms(error_) > tolerance)) return false;
  jacobian(tree);
  std::copy(error_.begin(), error_.end(), rhs_.begin());
  solve_rows(G_, nullptr);
  std::fill(du, du + nu_, 0.0);
  for (int r = 0; r < rows_; ++r) {
    const double y = x_[static_cast<std::size_t>(r)];
    const double* g = &G_[static_cast<std::size_t>(r * nu_)];
    for (int k = 0; k < nu_; ++k)
      du[k] -= y * g[k];
  }
  return true;
}

}  // namespace s2sim::model
