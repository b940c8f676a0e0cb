#pragma once
/// \file
/// The loop joints of the fast path: the constraints that close a loop, in the
/// tree's coordinates, without Simbody: balls, constant angles and points on lines, of which
/// every loop joint is made (ball: a ball; universal: a ball and an angle; hinge: a ball and two
/// angles; fixed: a ball and three angles, Simbody's Weld; slider: three angles and a point on
/// a line, its ConstantOrientation and PointOnLine). Simbody's loop forward dynamics rebuilds
/// G·M⁻¹·Gᵀ column by column through its realize chain every step: nine tenths of a four-bar's step
/// (bench/peers/results/history.md, "Instructions per step": arm_loop 402 k instructions a step on
/// Simbody's loop dynamics, 25.8 k here). Here the same equations run over plain arrays:
///   accelerations  u' = u'_free − M⁻¹·Gᵀ·λ,  (G·M⁻¹·Gᵀ)·λ = G·u'_free + Ġ·u;
///   speeds         u ← u − D·Gᵀ·(G·D·Gᵀ)⁺·G·u, D_kk = max(1, u_k²)   (Simbody's projectU);
///   positions      Δu = −Gᵀ·(G·Gᵀ)⁺·perr, q ← q + N·Δu, repeated (its projectQ, Gauss-Newton);
/// each projection only when the RMS of the errors exceeds the tolerance, as Simbody's.
/// Redundant rows (a planar loop's out-of-plane equations) are solved by a pivoted Cholesky
/// (common/cholesky.hpp). Conventions are TreeDynamics's (body 0 is Ground).

#include "model/tree_dynamics.hpp"

#include <s2sim/math.hpp>

#include <vector>

namespace s2sim::model {

class LoopConstraints {
 public:
  /// A point of body1 held on a point of body2 (three equations): Simbody's Constraint::Ball.
  struct Ball {
    int body1 = 0, body2 = 0;
    Vec3 point1_B1, point2_B2;  // body frames
  };
  /// An axis of `follower` kept at a constant angle to an axis of `base` (one equation):
  /// Simbody's Constraint::ConstantAngle.
  struct Angle {
    int base = 0, follower = 0;
    Vec3 axis_base_B, axis_follower_F;  // unit, body frames
    double cos_angle = 0;
  };

  /// A point of `follower` held on a line fixed in `base` (two equations): Simbody's
  /// Constraint::PointOnLine.
  struct Line {
    int base = 0, follower = 0;
    Vec3 direction_B, point_B;  // the line, base frame (direction unit)
    Vec3 point_F;               // follower frame
  };
  /// Two one-speed coordinates (a Pin's or Slider's, q' = u) held in step (one equation):
  /// q_follower − ratio·q_leader − offset = 0, G's row e_f − ratio·e_l, Ġ·u = 0. Simbody's
  /// CoordinateCoupler with a linear function (a joint coupling).
  struct Coupler {
    int follower_q = 0, follower_u = 0, leader_q = 0, leader_u = 0;
    double ratio = 1, offset = 0;
  };
  struct Spec {
    std::vector<Ball> balls;
    std::vector<Angle> angles;
    std::vector<Line> lines;
    std::vector<Coupler> couplers;
  };

  /// `speeds`: the tree's (TreeDynamics::speeds()).
  LoopConstraints(Spec spec, int speeds);

  /// The RMS of the position errors (m for a ball or a line, the cosine's for an angle, rad or
  /// m for a coupler); after the tree's kinematics().
  double rms_position_error(const TreeDynamics& tree);
  /// Corrects the tree's accelerations `udot` (of its last accelerations(), whose mass matrix
  /// factor it uses) by the constraint forces.
  void constrain_accelerations(TreeDynamics& tree, double* udot);
  /// Projects the speeds `u` (those of the tree's last kinematics()) onto G·u = 0 by the
  /// least change, when the RMS of G·u exceeds `tolerance`; returns whether it did.
  bool project_speeds(const TreeDynamics& tree, double* u, double tolerance);
  /// When the RMS of the position errors exceeds `tolerance`: the least speed change `du`
  /// whose first-order effect removes them (the caller moves q by N·du), and true.
  bool position_correction(const TreeDynamics& tree, double tolerance, double* du);

 private:
  struct RowPoint {  // a ball: the two points in Ground
    Vec3 p1, p2;
  };
  struct LinePlace {  // a line: its point, the follower's point and two normals in Ground
    Vec3 p, s, n[2];
  };
  std::vector<Ball> balls_;
  std::vector<Angle> angles_;
  std::vector<Line> lines_;
  std::vector<Coupler> couplers_;
  std::vector<Vec3> line_normals_;  // two per line, base frame
  std::vector<LinePlace> line_places_;
  int rows_ = 0, nu_ = 0;
  // Scratch, sized at construction.
  std::vector<RowPoint> points_;
  std::vector<Vec3> base_axis_, follower_axis_;  // per angle, in Ground
  std::vector<double> error_;                    // rows
  std::vector<double> G_;                        // rows x nu, row-major
  std::vector<double> minv_gt_;                  // rows x nu: row r is M⁻¹·(row r of G)
  std::vector<double> A_, rhs_, x_;              // the rows' system
  std::vector<double> weight_;                   // nu: the speed projection's weights
  std::vector<int> order_;
  std::vector<double> solve_scratch_;  // semidefinite_solve's
  // The configurations (TreeDynamics::configuration()) the points and G were computed at.
  long placed_at_ = -1, jacobian_at_ = -1;

  /// The points and axes in Ground and the position errors; after kinematics(). Kept while
  /// the configuration is unchanged, as G is (jacobian()).
  void place(const TreeDynamics& tree);
  /// G at the tree's configuration; after place().
  void jacobian(const TreeDynamics& tree);
  /// Adds `sign` times the velocity of a point of `body` (at p in Ground) along `direction`
  /// per unit speed to row `row` of G, for every speed that moves the body.
  void add_point_row(const TreeDynamics& tree, int row, int body, const Vec3& p,
                     const Vec3& direction, double sign);
  /// Adds `sign` times the body's angular velocity along `direction` per unit speed.
  void add_angular_row(const TreeDynamics& tree, int row, int body, const Vec3& direction,
                       double sign);
  /// Solves (G·D·R)·x = rhs_ into x_: R = Gᵀ (`right` G_) or M⁻¹·Gᵀ (minv_gt_), D the diagonal
  /// `weight` (null: the identity).
  void solve_rows(const std::vector<double>& right, const double* weight);
};

}  // namespace s2sim::model
