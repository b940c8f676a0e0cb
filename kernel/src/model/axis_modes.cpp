// One tree's axis friction and drive bounds solved exactly in the axes' modes (multibody_impl.hpp:
// solve_tree_in_modes; docs/models/multibody.md, "Axis friction and bounds"). The block
// Gauss-Seidel sweeps of implicit_axes.cpp converge slowly where the axes are strongly coupled:
// a humanoid standing on its 20 braked hinges ran all 16 sweeps at every step and still ended
// short of the law, its joints creeping. A sweep finds the modes, though: which axes
// stick and, for the others, which way they slide and which drive rows sit at a bound. In given
// modes the law is linear, so the exact answer is one linear system:
//   v = v_now + κ·W·x,  x: the change of each axis's total force G (friction + drive rows),
//   stuck axis:   v_a = 0                      (its friction takes whatever holds it),
//   other axis:   G_a + x_a = c0_a − c1_a·v_a  (its friction ±F and its rows' pieces),
// with W the axes' Delassus matrix (W_ab = g_a·M^-1·g_b, symmetric positive definite). An axis
// with c1 > 0 divides its row by c1, one with c1 = 0 has its x known, so the unknowns solve
//   (D + κ·W_UU)·x_U = r_U,   D = diag(0 for a stuck axis, 1/c1 for the others),
// by Cholesky. An answer that leaves a mode (a stuck axis's friction beyond ±F, a sliding one
// moving with its friction, a row off its piece) changes those modes and is solved again, a few
// times at most (an active set); only an answer in its own modes is applied.
#include "common/cholesky.hpp"
#include "model/multibody_impl.hpp"

#include <cmath>

namespace s2sim::model {
namespace {

/// -1: the row's law sits at its low bound at `rate`, +1 at its high bound, 0 on its slope.
signed char side_of(const Multibody::Impl::DriveRow& r, double rate) {
  const double free = r.force - r.damping * (rate - r.rate0);
  return free < r.low ? -1 : (free > r.high ? 1 : 0);
}

/// Mode changes tried before giving the tree back to the sweeps.
constexpr int kModeRounds = 6;

}  // namespace

bool solve_tree_in_modes(Multibody::Impl& m, SimTK::State& s, int tree, int begin, int end,
                         double kick_s) {
  const int n = end - begin;
  if (n < 2) return false;
  const int* axis = m.solve_order.data() + begin;
  SimTK::Vector& u = s.updU();
  double* speeds = u.updContiguousScalarData();
  const double* W = m.tree_delassus.data();  // the tree's Delassus matrix (solve_axes)
  double* x = m.mode_force.data();
  double* v = m.mode_rate.data();       // the speeds now
  double* total = m.mode_total.data();  // G now
  double* r = m.mode_rhs.data();
  double* friction = m.mode_friction.data();  // a sliding axis's friction (±F, or 0)
  char* stuck = m.mode_stuck.data();
  int* unknown = m.mode_unknown.data();

  // The modes the sweep left, the speeds and each axis's total force now.
  for (int i = 0; i < n; ++i) {
    const auto a = static_cast<std::size_t>(axis[i]);
    if (m.axes[a].loop || !(m.axis_mobility[a] > 0)) return false;
    v[i] = m.axis_impl[a].sign * speeds[m.axis_u[a]];
    stuck[i] = m.friction_bound[a] > 0 && m.axis_stuck[a];
    friction[i] = stuck[i] ? 0.0 : m.friction_applied[a];
    total[i] = m.friction_applied[a];
    for (int j = m.first_row[a]; j >= 0; j = m.next_row[j]) {
      const auto& row = m.rows[static_cast<std::size_t>(j)];
      total[i] += row.applied;
      m.mode_row_side[static_cast<std::size_t>(j)] = side_of(row, stuck[i] ? 0.0 : v[i]);
    }
  }
  double* A = m.tree_matrix.data();
  double* y = m.tree_rhs.data();
  for (int round = 0; round < kModeRounds; ++round) {
    // Each axis's equation in its mode: the right side, D's entry, or its known force.
    int count = 0;
    for (int i = 0; i < n; ++i) {
      const auto a = static_cast<std::size_t>(axis[i]);
      double c0 = friction[i], c1 = 0.0;
      for (int j = m.first_row[a]; j >= 0; j = m.next_row[j]) {
        const auto& row = m.rows[static_cast<std::size_t>(j)];
        const signed char side = m.mode_row_side[static_cast<std::size_t>(j)];
        if (side != 0) {
          c0 += side < 0 ? row.low : row.high;
        } else {
          c0 += row.force + row.damping * row.rate0;
          c1 += row.damping;
        }
      }
      if (stuck[i]) {
        unknown[count++] = i;
        r[i] = -v[i];
        x[i] = 0.0;  // D's entry
      } else if (c1 > 0) {
        unknown[count++] = i;
        r[i] = (c0 - total[i]) / c1 - v[i];
        x[i] = 1.0 / c1;
      } else {
        x[i] = c0 - total[i];  // known: its force does not depend on its speed
      }
    }
    // The unknowns' system (the known forces moved to the right side), by Cholesky.
    for (int p = 0; p < count; ++p) {
      const int i = unknown[p];
      double rhs = r[i];
      for (int k = 0, q = 0; k < n; ++k) {
        if (q < count && unknown[q] == k) {
          A[p * count + q] = kick_s * W[i * n + k] + (p == q ? x[i] : 0.0);
          ++q;
        } else {
          rhs -= kick_s * W[i * n + k] * x[k];
        }
      }
      y[p] = rhs;
    }
    if (!common::cholesky_factor(A, count)) return false;
    common::cholesky_substitute(A, count, y, y);
    for (int p = 0; p < count; ++p)
      x[unknown[p]] = y[p];
    // The speeds it gives (into r), and the modes it leaves.
    for (int i = 0; i < n; ++i) {
      double dv = 0;
      for (int k = 0; k < n; ++k)
        dv += W[i * n + k] * x[k];
      r[i] = v[i] + kick_s * dv;
    }
    bool kept = true;
    for (int i = 0; i < n; ++i) {
      const auto a = static_cast<std::size_t>(axis[i]);
      const double rate = stuck[i] ? 0.0 : r[i];
      double drives = 0;
      for (int j = m.first_row[a]; j >= 0; j = m.next_row[j]) {
        const auto& row = m.rows[static_cast<std::size_t>(j)];
        signed char& side = m.mode_row_side[static_cast<std::size_t>(j)];
        const signed char now = side_of(row, rate);
        if (!stuck[i] && now != side) {
          side = now;
          kept = false;
        }
        drives += drive_law(row, rate);
      }
      const double bound = m.friction_bound[a];
      if (stuck[i]) {
        const double held = total[i] + x[i] - drives;  // the friction it takes
        if (!(std::abs(held) <= bound)) {  // it slips, its friction against the way it goes
          stuck[i] = 0;
          friction[i] = held > 0 ? bound : -bound;
          for (int j = m.first_row[a]; j >= 0; j = m.next_row[j])
            m.mode_row_side[static_cast<std::size_t>(j)] =
                side_of(m.rows[static_cast<std::size_t>(j)], 0.0);
          kept = false;
        }
      } else if (friction[i] * rate > 0) {  // it would slide with its friction: it stops
        stuck[i] = 1;
        kept = false;
      }
    }
    if (!kept) continue;

    // In its modes: each axis's forces from its laws at its new speed, and the speeds they give.
    for (int i = 0; i < n; ++i) {
      const auto a = static_cast<std::size_t>(axis[i]);
      const double rate = stuck[i] ? 0.0 : r[i];
      double drives = 0;
      for (int j = m.first_row[a]; j >= 0; j = m.next_row[j]) {
        auto& row = m.rows[static_cast<std::size_t>(j)];
        row.applied = drive_law(row, rate);
        drives += row.applied;
      }
      m.axis_stuck[a] = stuck[i];
      m.friction_applied[a] = stuck[i] ? total[i] + x[i] - drives : friction[i];
      const double change = m.friction_applied[a] + drives - total[i];
      if (change != 0.0) add_column(u, kick_s * change, m.minv_column, a);
    }
    for (int i = 0; i < n; ++i)  // a stuck axis stands exactly still (no creep from rounding)
      if (stuck[i]) speeds[m.axis_u[static_cast<std::size_t>(axis[i])]] = 0.0;
    return true;
  }
  return false;
}

}  // namespace s2sim::model
