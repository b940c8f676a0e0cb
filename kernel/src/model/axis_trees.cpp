// The independent trees of the implicit axis solve (implicit_axes.cpp). Without constraints the
// mass matrix is block diagonal over the trees hanging from Ground: an impulse on one robot's
// axis moves none of another robot's speeds (M^-1 is zero across trees, exactly), so the
// Delassus matrix W is block diagonal too. Solving each tree's rows as their own block, over
// its own range of speeds, costs Σ n_t³ instead of (Σ n_t)³, and gives the same numbers: the
// cross terms it skips are exact zeros. A scene with constraints (loops may join trees) or with
// trees whose coordinates interleave is one block, as before.
#include "model/multibody_impl.hpp"

#include <algorithm>

namespace s2sim::model {

void find_axis_trees(Multibody::Impl& m) {
  const SimTK::State& s = m.initial_state;
  const int nu = s.getNU(), nq = s.getNQ();
  const std::size_t axes = m.axes.size();
  auto one_block = [&] {
    m.axis_tree.assign(axes, 0);
    m.tree_u_begin.assign(1, 0);
    m.tree_u_end.assign(1, nu);
    m.tree_q_begin.assign(1, 0);
    m.tree_q_end.assign(1, nq);
  };
  bool loop_axis = false;
  for (const auto& axis : m.axes)
    loop_axis = loop_axis || axis.loop;
  if (m.has_constraints || loop_axis || axes == 0) {
    one_block();
  } else {
    // Each mobilized body's tree: the index of its ancestor that hangs from Ground.
    const int bodies = m.matter.getNumBodies();
    std::vector<int> root_of(static_cast<std::size_t>(bodies), -1);
    for (SimTK::MobilizedBodyIndex i(1); i < bodies; ++i) {
      const auto& parent = m.matter.getMobilizedBody(i).getParentMobilizedBody();
      root_of[i] =
          parent.isGround() ? static_cast<int>(i) : root_of[parent.getMobilizedBodyIndex()];
    }
    // Trees with axes, numbered in order of their first axis; their speed and coordinate ranges.
    std::vector<int> tree_of_root(static_cast<std::size_t>(bodies), -1);
    m.axis_tree.assign(axes, -1);
    m.tree_u_begin.clear();
    m.tree_u_end.clear();
    m.tree_q_begin.clear();
    m.tree_q_end.clear();
    for (std::size_t a = 0; a < axes; ++a) {
      const int root = root_of[m.axis_impl[a].mobod];
      if (tree_of_root[root] < 0) {
        tree_of_root[root] = static_cast<int>(m.tree_u_begin.size());
        m.tree_u_begin.push_back(nu);
        m.tree_u_end.push_back(0);
        m.tree_q_begin.push_back(nq);
        m.tree_q_end.push_back(0);
      }
      m.axis_tree[a] = tree_of_root[root];
    }
    const std::size_t trees = m.tree_u_begin.size();
    std::vector<int> u_count(trees, 0), q_count(trees, 0);
    for (SimTK::MobilizedBodyIndex i(1); i < bodies; ++i) {
      const int t = tree_of_root[root_of[i]];
      if (t < 0) continue;
      const auto& mob = m.matter.getMobilizedBody(i);
      const int u0 = mob.getFirstUIndex(s), q0 = mob.getFirstQIndex(s);
      const int n_u = mob.getNumU(s), n_q = mob.getNumQ(s);
      const auto k = static_cast<std::size_t>(t);
      m.tree_u_begin[k] = std::min(m.tree_u_begin[k], u0);
      m.tree_u_end[k] = std::max(m.tree_u_end[k], u0 + n_u);
      m.tree_q_begin[k] = std::min(m.tree_q_begin[k], q0);
      m.tree_q_end[k] = std::max(m.tree_q_end[k], q0 + n_q);
      u_count[k] += n_u;
      q_count[k] += n_q;
    }
    // A tree's ranges must hold its own coordinates only (Simbody numbers them body by body,
    // and the builder adds a tree's bodies together): otherwise, one block.
    for (std::size_t t = 0; t < trees; ++t)
      if (m.tree_u_end[t] - m.tree_u_begin[t] != u_count[t] ||
          m.tree_q_end[t] - m.tree_q_begin[t] != q_count[t]) {
        one_block();
        break;
      }
  }
  // Scratch of the solve: axes grouped by tree, and the largest tree's matrices (one row and
  // column per axis: a tree's drive rows are solved per axis, implicit_axes.cpp).
  const std::size_t trees = m.tree_u_begin.size();
  m.tree_cursor.assign(trees, 0);
  m.tree_changed.assign(trees, 0);
  m.tree_sweeps.assign(trees, 0);
  m.tree_solve_start.assign(trees + 1, 0);
  m.solve_order.assign(axes, 0);
  std::vector<std::size_t> axes_in_tree(trees, 0);
  for (std::size_t a = 0; a < axes; ++a)
    ++axes_in_tree[static_cast<std::size_t>(m.axis_tree[a])];
  const std::size_t most_axes =
      axes_in_tree.empty() ? 0 : *std::max_element(axes_in_tree.begin(), axes_in_tree.end());
  m.tree_delassus.assign(most_axes * most_axes, 0.0);
  m.tree_matrix.assign(most_axes * most_axes, 0.0);
  for (auto* v : {&m.tree_rhs, &m.rows_scale, &m.rows_rate, &m.rows_damping, &m.rows_residual,
                  &m.mode_rhs, &m.mode_force, &m.mode_rate, &m.mode_total, &m.mode_friction})
    v->assign(most_axes, 0.0);
  m.rows_axes.assign(most_axes, 0);
  m.mode_unknown.assign(most_axes, 0);
  m.mode_stuck.assign(most_axes, 0);
  m.mode_row_side.assign(m.next_row.size(), 0);
}

void group_solve_list_by_tree(Multibody::Impl& m) {
  auto& start = m.tree_solve_start;
  std::fill(start.begin(), start.end(), 0);
  for (int a : m.solve_list)
    ++start[static_cast<std::size_t>(m.axis_tree[static_cast<std::size_t>(a)]) + 1];
  for (std::size_t t = 0; t + 1 < start.size(); ++t)
    start[t + 1] += start[t];
  std::copy(start.begin(), start.end() - 1, m.tree_cursor.begin());
  for (int a : m.solve_list) {  // stable: a tree's axes keep their order
    const auto t = static_cast<std::size_t>(m.axis_tree[static_cast<std::size_t>(a)]);
    m.solve_order[static_cast<std::size_t>(m.tree_cursor[t]++)] = a;
  }
}

}  // namespace s2sim::model
