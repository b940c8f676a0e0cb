// Stepping on the small-tree dynamics (dynamics.hpp): TreeDynamics computes the kinematics,
// the accelerations and M⁻¹ solves, LoopConstraints the loops' projections, without Simbody's
// realize chain.
#include "model/dynamics.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace s2sim::model {

const double* contiguous_data(const SimTK::Vector& v) {
  if (!v.hasContiguousData()) throw std::logic_error("a non-contiguous state vector");
  return v.getContiguousScalarData();
}

void update_tree_kinematics(const Multibody::Impl& m) {
  m.tree->kinematics(contiguous_data(m.current.getQ()), contiguous_data(m.current.getU()));
}

void tree_accelerations(Multibody::Impl& m) {
  update_tree_kinematics(m);
  m.tree_body_loads.setToZero();
  m.tree_mobility_forces = 0.0;
  add_applied_loads(m, m.current, m.tree_body_loads, m.tree_mobility_forces);
  m.tree->accelerations(&m.tree_body_loads[0][0][0], contiguous_data(m.tree_mobility_forces),
                        m.udot.updContiguousScalarData());
  if (m.loops) m.loops->constrain_accelerations(*m.tree, m.udot.updContiguousScalarData());
}

namespace {

/// The loops' projections in place of Simbody's projectU() and project(), at the same
/// accuracy: the speeds; then the positions and the speeds.
void project_loop_speeds(Multibody::Impl& m) {
  update_tree_kinematics(m);
  // u is changed in place only when the errors call for it: updU() would drop what Simbody
  // realized (nothing here, but a state it reads later must stay coherent).
  const SimTK::Vector& u = m.current.getU();
  std::copy(contiguous_data(u), contiguous_data(u) + u.size(), m.loop_u.begin());
  if (m.loops->project_speeds(*m.tree, m.loop_u.data(), kLoopTolerance))
    std::copy(m.loop_u.begin(), m.loop_u.end(), m.current.updU().updContiguousScalarData());
}

void project_loops(Multibody::Impl& m) {
  // Positions first (Gauss-Newton on the errors, in the speeds' least change mapped by N), then
  // the speeds at the new configuration: the order of Simbody's project(). As Simbody's, a
  // projection starts when the errors exceed the tolerance, then aims ten times below it
  // (its overshoot factor) and settles for the tolerance. The iterations work on a copy of q:
  // each updQ() would walk Simbody's cache invalidation.
  const SimTK::Vector& q_now = m.current.getQ();
  const double* u = contiguous_data(m.current.getU());
  double* q = m.loop_q.data();
  std::copy(contiguous_data(q_now), contiguous_data(q_now) + q_now.size(), q);
  double target = kLoopTolerance;
  bool moved = false;
  for (int iteration = 0;; ++iteration) {
    m.tree->kinematics(q, u);
    if (!m.loops->position_correction(*m.tree, target, m.loop_du.data())) break;
    if (iteration == kLoopIterations) {
      const double error = m.loops->rms_position_error(*m.tree);
      if (error <= kLoopTolerance) break;
      std::ostringstream out;
      out << "the loop joints could not be closed to " << kLoopTolerance << " (RMS error " << error
          << " after " << kLoopIterations
          << " corrections): the mechanism cannot be assembled here";
      throw Error(ErrorKind::runtime, out.str());
    }
    target = kLoopTolerance * kLoopOvershoot;
    calc_qdot(m, m.loop_du.data(), q, m.loop_dq.data());
    for (std::size_t i = 0; i < m.loop_q.size(); ++i)
      q[i] += m.loop_dq[i];
    normalize_quaternions(m, q);
    moved = true;
  }
  if (moved)
    std::copy(m.loop_q.begin(), m.loop_q.end(), m.current.updQ().updContiguousScalarData());
  project_loop_speeds(m);
}

class TreePath final : public Dynamics {
 public:
  const char* name() const override { return "tree"; }

  // Bodies come from the tree, axes from q and u: nothing to realize.
  void realize_velocity(const Multibody::Impl&, const SimTK::State&) const override {}

  void read_bodies(const Multibody::Impl& m, const SimTK::State&, Pose* poses,
                   Twist* twists) const override {
    update_tree_kinematics(m);
    for (const auto& [b, mobod] : m.jointed_bodies) {
      poses[b] = m.tree->pose(mobod);
      twists[b] = m.tree->twist(mobod);
    }
  }

  BodyFrame body_frame(const Multibody::Impl& m, const SimTK::State&,
                       SimTK::MobilizedBodyIndex body) const override {
    update_tree_kinematics(m);  // kept while q and u are unchanged
    const Pose& pose = m.tree->pose(body);
    SimTK::Mat33 R;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        R(r, c) = pose.rotation.m[r][c];
    return {SimTK::Rotation(R, true), to_simtk(pose.position)};
  }

  BodyVelocity body_velocity(const Multibody::Impl& m, const SimTK::State&,
                             SimTK::MobilizedBodyIndex body) const override {
    update_tree_kinematics(m);
    const Twist& twist = m.tree->twist(body);
    return {to_simtk(twist.angular_rad_s), to_simtk(twist.linear_m_s)};
  }

  SimTK::Vec3 to_ground(const Multibody::Impl& m, const SimTK::State&,
                        SimTK::MobilizedBodyIndex body, const SimTK::Vec3& v_B) const override {
    return to_simtk(m.tree->pose(body).rotation * from_simtk(v_B));
  }

  void accelerations(Multibody::Impl& m, bool last_substep) const override {
    tree_accelerations(m);
    // The reactions of the tick's last acceleration evaluation (the tree computes them
    // without loops; with loops select_dynamics chose Simbody).
    if (m.reactions_wanted && last_substep) compute_tree_joint_reactions(m);
  }

  void tree_axis_column(Multibody::Impl& m, const SimTK::State&, int a) const override {
    // g: a unit load along the axis; M factored by this substep's accelerations, at this q.
    // Solved in the axis's own tree alone: the column is zero in every other tree, and a
    // solve over every tree, once per axis, grew with the square of the robot count.
    double& g = m.unit_speed[static_cast<std::size_t>(m.axis_u[a])];
    g = m.axis_impl[a].sign;
    int u_begin = 0, u_end = 0;
    m.tree->solve_tree_of(static_cast<int>(m.axis_impl[a].mobod), m.unit_speed.data(),
                          m.column_scratch.data(), u_begin, u_end);
    g = 0.0;
    keep_column(m, static_cast<std::size_t>(a), m.column_scratch.data(), u_begin, u_end);
  }

  void loop_axis_column(Multibody::Impl& m, const SimTK::State&, int a) const override {
    SimTK::Vector& g = m.loop_unit_force[a];
    m.tree->generalized_forces(&m.unit_body_forces[0][0][0], g.updContiguousScalarData());
    m.tree->solve(g.getContiguousScalarData(), m.column_scratch.data());
    keep_column(m, static_cast<std::size_t>(a), m.column_scratch.data(), 0,
                static_cast<int>(m.column_scratch.size()));
  }

  void point_forces(Multibody::Impl& m, const SimTK::State&, SimTK::MobilizedBodyIndex body,
                    const SimTK::Vec3& point, const SimTK::Vec3* directions, int u_begin, int u_end,
                    double* const* g) const override {
    // g_k = d·(the point's velocity per unit speed k), over the body's chain of mobilizers;
    // that velocity once for both directions.
    const TreeDynamics& tree = *m.tree;
    double* g0 = g[0];
    double* g1 = g[1];
    std::fill(g0 + u_begin, g0 + u_end, 0.0);
    std::fill(g1 + u_begin, g1 + u_end, 0.0);
    const Vec3 p{point[0], point[1], point[2]};
    const Vec3 d0{directions[0][0], directions[0][1], directions[0][2]};
    const Vec3 d1{directions[1][0], directions[1][1], directions[1][2]};
    for (int i = body; i > 0; i = tree.parent(i)) {
      const Vec3 arm = p - tree.pose(i).position;
      for (int k = tree.first_speed(i); k < tree.first_speed(i) + tree.speed_count(i); ++k) {
        const Twist& h = tree.column(k);
        const Vec3 velocity = h.linear_m_s + cross(h.angular_rad_s, arm);
        g0[k] = dot(d0, velocity);
        g1[k] = dot(d1, velocity);
      }
    }
  }

  void solve_speeds(Multibody::Impl& m, const SimTK::State&, SimTK::MobilizedBodyIndex body,
                    int u_begin, int u_end, const double* g, double* x) const override {
    // The body's own tree; the rest of the range (every speed, when the axes are one block)
    // is zero, as g is there.
    int begin = 0, end = 0;
    m.tree->solve_tree_of(body, g, x, begin, end);
    std::fill(x + u_begin, x + std::max(u_begin, begin), 0.0);
    std::fill(x + std::min(u_end, end), x + u_end, 0.0);
  }

  void qdot(Multibody::Impl& m) const override {
    const SimTK::State& s = m.current;
    calc_qdot(m, s.getU().getContiguousScalarData(), s.getQ().getContiguousScalarData(),
              m.qdot.updContiguousScalarData());
  }

  void project_speeds(Multibody::Impl& m) const override { project_loop_speeds(m); }
  void project(Multibody::Impl& m) const override { project_loops(m); }
};

}  // namespace

const Dynamics& tree_dynamics() {
  static const TreePath path;
  return path;
}

}  // namespace s2sim::model
