// The axis loads solved at the end of the kick (docs/models/multibody.md): the drives and the
// Coulomb friction of the joint axes.
//
// A drive is a force on an axis that falls with the axis velocity v within bounds,
//   f(v) = clamp(F − c·(v − v0), lo, hi),
// as a motor's back-EMF (bounded by its current limit), a viscous friction, or the loop axes'
// regularised Coulomb friction. Applied at the velocity of the substep's start, such a force
// rings on a light axis once h·c/inertia > 1 and diverges past 2. Here, after the explicit
// kick Δu* = κ·M^-1·f, the axis forces are re-solved at the kick's end velocity:
//   f⁺ = clamp(F − c·(v⁺ − v0)),   v⁺ = v* + κ·W·(f⁺ − f),   W_ij = g_i·M^-1·g_j,
// that is linearly implicit Euler, (M + κ·C)·Δu = κ·f, within the bounds. Coulomb friction on a
// tree axis joins as the set-valued law f ∈ −F·Sign(v) (a velocity-level brake: true stick).
//  1. The drives without their bounds: one symmetric positive definite solve with a row per
//     axis (an axis's unbounded drives add up to one law), (I + κ·S·W·S)·z = S^-1·r,
//     S = diag(√Σc), d = S·z: exact for any number of coupled axes.
//  2. Where a bound binds or an axis has friction: block Gauss-Seidel over the axes, each
//     axis's monotone piecewise-linear law solved exactly for its own speed (its breakpoints
//     walked in order), the others held; from the clamped solution of 1. After each sweep the
//     modes it left are solved at once (axis_modes.cpp), which ends the sweeps when it holds.
// An axis alone: its speed change is the explicit one divided by 1 + κ·c·w, never
// overshooting, whatever c·κ/inertia; a motor stronger than its friction turns, a weaker one
// sticks.
#include "common/cholesky.hpp"
#include "model/multibody_impl.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::model {
namespace {

/// The axis's rate for the current generalized speeds; `state` realized to Velocity for a
/// loop axis.
double current_rate(const Multibody::Impl& m, const SimTK::State& s, std::size_t a) {
  if (!m.axes[a].loop) return m.axis_impl[a].sign * element(s.getU(), m.axis_u[a]);
  return axis_rate(m, s, a);
}

}  // namespace

/// Which axes with friction slide so fast that friction cannot stop them within a step (ten
/// times the speed change the bound can make): they get Coulomb's law as a plain force and
/// skip the solve. (M^-1)_aa is remembered from the last solve.
void classify_sliding(Multibody::Impl& m, const SimTK::State& s, double h) {
  const SimTK::Vector& u = s.getU();
  for (std::size_t a = 0; a < m.axis_friction.size(); ++a) {
    m.sliding[a] = 0;
    if (!(m.axis_friction[a] > 0.0) || m.axes[a].loop || !(m.axis_mobility[a] > 0)) continue;
    const double threshold = 10 * m.axis_friction[a] * h * m.axis_mobility[a];
    m.sliding[a] = std::abs(element(u, m.axis_u[a])) > threshold;
  }
}

void prepare_drives(Multibody::Impl& m, const SimTK::State& s) {
  m.rows.clear();
  std::fill(m.explicit_drive.begin(), m.explicit_drive.end(), 0.0);
  std::fill(m.friction_applied.begin(), m.friction_applied.end(), 0.0);
  bool realized = false;
  auto rate = [&](std::size_t a) {
    // A loop axis's rate comes from its bodies (realize_velocity: none on the fast path).
    if (m.axes[a].loop && !realized) {
      realize_velocity(m, s);
      realized = true;
    }
    return current_rate(m, s, a);
  };
  // The components read the axis velocities of the tick's start: their drives are laws about
  // those (on later substeps, the law followed to the substep's velocity).
  if (m.substep == 0)
    for (std::int32_t d = 0; d < m.drive_count; ++d) {
      const auto a = static_cast<std::size_t>(m.drives[static_cast<std::size_t>(d)].axis);
      m.rate0[a] = rate(a);
    }
  for (std::int32_t d = 0; d < m.drive_count; ++d) {
    const AxisDrive& drive = m.drives[static_cast<std::size_t>(d)];
    const auto a = static_cast<std::size_t>(drive.axis);
    if (!(drive.damping > 0)) {  // no velocity dependence: a plain (clamped) force
      m.explicit_drive[a] += std::clamp(drive.force, drive.min_force, drive.max_force);
      continue;
    }
    Multibody::Impl::DriveRow row{drive.axis,      drive.force,     drive.damping, m.rate0[a],
                                  drive.min_force, drive.max_force, 0.0,           true};
    row.applied = drive_law(row, rate(a));
    m.rows.push_back(row);
  }
  // A loop axis has no velocity-level brake: its Coulomb friction is regularised over
  // loop_friction_speed(), a drive of slope F/v_s within ±F.
  for (std::size_t a = 0; a < m.axes.size(); ++a) {
    if (!m.axes[a].loop || !(m.axis_friction[a] > 0.0)) continue;
    const double bound = m.axis_friction[a];
    Multibody::Impl::DriveRow row{
        static_cast<int>(a), 0.0, bound / loop_friction_speed(), 0.0, -bound, bound, 0.0, false};
    row.applied = drive_law(row, rate(a));
    m.rows.push_back(row);
  }
  for (std::size_t a = 0; a < m.explicit_drive.size(); ++a)
    m.drive_sum[a] += m.explicit_drive[a];
}

namespace {

/// The root of an increasing, continuous function f that is linear between the sorted
/// `points` (and beyond them): the piece holding it found, then solved exactly.
template <class F>
double root_of_piecewise_linear(const F& f, const double* points, int count) {
  if (count == 0) {  // one line: through f(0) and f(1)
    const double f0 = f(0.0);
    return -f0 / (f(1.0) - f0);
  }
  int j = 0;
  double f_j = f(points[0]);
  // Beyond the breakpoints f is one line: its slope from a second point a step away that
  // stays distinct from the first in floating point.
  auto away = [](double x) { return std::max(1.0, std::abs(x)); };
  if (f_j >= 0) {  // left of every breakpoint
    const double left = points[0] - away(points[0]);
    return points[0] - f_j * (points[0] - left) / (f_j - f(left));
  }
  for (j = 1; j < count; ++j) {
    const double f_next = f(points[j]);
    if (f_next >= 0) {
      const double span = points[j] - points[j - 1];
      return span > 0 ? points[j - 1] - f_j * span / (f_next - f_j) : points[j];
    }
    f_j = f_next;
  }
  const double last = points[count - 1];  // right of every breakpoint
  const double right = last + away(last);
  return last - f_j * (right - last) / (f(right) - f_j);
}

/// The drives' law summed on one axis, Σ clamp(F − c·(v − v0)), over its rows.
double axis_law(const Multibody::Impl& m, int axis, double v) {
  double sum = 0;
  for (int i = m.first_row[axis]; i >= 0; i = m.next_row[i])
    sum += drive_law(m.rows[i], v);
  return sum;
}

/// Solves one axis exactly, the others held: the speed v and the total force G of its drives
/// and friction such that v = v_now + κ·w·(G − G_now). With q(v) = v − v_now −
/// κ·w·(D(v) − G_now), D the drives' law (non-increasing, so q increases with slope >= 1):
/// q(v) = κ·w·φ, φ ∈ −F·Sign(v). Returns the change of G.
double solve_one_axis(Multibody::Impl& m, int a, double v_now, double w, double kick_s) {
  const double k = kick_s * w;
  double g_now = m.friction_applied[a];
  for (int i = m.first_row[a]; i >= 0; i = m.next_row[i])
    g_now += m.rows[i].applied;
  auto q = [&](double v) { return v - v_now - k * (axis_law(m, a, v) - g_now); };
  const double F = m.friction_bound[a];
  double target = 0;  // the friction's share of q at the solution
  double v = 0;
  const double q0 = q(0.0);
  m.axis_stuck[a] = F > 0 && std::abs(q0) <= k * F;
  if (m.axis_stuck[a]) {  // sticks
    m.friction_applied[a] = q0 / k;
    v = 0;
  } else {
    if (F > 0) target = q0 > 0 ? k * F : -k * F;  // slides against the bound
    m.friction_applied[a] = F > 0 ? target / k : 0.0;
    // q is piecewise linear between the drives' breakpoints: walk them in order.
    int count = 0;
    double* points = m.breakpoints.data();
    for (int i = m.first_row[a]; i >= 0; i = m.next_row[i]) {
      const auto& r = m.rows[i];
      for (double bound : {r.low, r.high})
        if (std::isfinite(bound)) points[count++] = r.rate0 + (r.force - bound) / r.damping;
    }
    std::sort(points, points + count);
    v = root_of_piecewise_linear([&](double x) { return q(x) - target; }, points, count);
  }
  double g_new = m.friction_applied[a];
  for (int i = m.first_row[a]; i >= 0; i = m.next_row[i]) {
    m.rows[i].applied = drive_law(m.rows[i], v);
    g_new += m.rows[i].applied;
  }
  return g_new - g_now;
}

/// The Delassus matrix of one tree's axes solve_order[begin, end), W_pq = g_p·M^-1·g_q, into
/// tree_delassus (row-major).
void build_tree_delassus(Multibody::Impl& m, int begin, int end) {
  const int n = end - begin;
  const int* axis = m.solve_order.data() + begin;
  double* W = m.tree_delassus.data();
  for (int q = 0; q < n; ++q) {
    const auto b = static_cast<std::size_t>(axis[q]);
    // (The tree's axes share its speeds, those of the column.)
    const double* column = m.minv_column.of(b);
    const int first = m.minv_column.u_begin[b];
    double* out = W + q;  // W's column q, row by row
    for (int p = 0; p < n; ++p, out += n) {
      const auto a = static_cast<std::size_t>(axis[p]);
      // axis_dot_column(a, b), read raw for a tree axis: it is asked n² times.
      *out = m.axes[a].loop ? axis_dot_column(m, a, b)
                            : m.axis_impl[a].sign * column[m.axis_u[a] - first];
    }
  }
}

/// Step 1 for tree t (solve_axes): the drive rows without their bounds, all at once. Unbounded,
/// an axis's rows add up to one law, G_p(v) = Σ F_i − Σ c_i·(v − v0_i), so the system is one
/// row per axis in W of the tree's `axes` solved axes (build_tree_delassus):
///   (I + κ·S·W·S)·z = S^-1·R,  ΔG = S·z,  S = diag(√C),  C = Σc,  R = Σ R_i,
/// R_i = F_i − c_i·(v − v0_i) − applied_i, the rows' residuals now. A row's change is its law's
/// at the axis's new speed, Δ_i = R_i − c_i·Δv with C·Δv = R − ΔG, written as
/// (c_i/C)·ΔG + (R_i − c_i·R/C): not through the new speed, whose rounding a stiff drive
/// (κ·c·W in the thousands) would amplify; a lone row's change is ΔG itself. Then each row
/// within its bounds.
void solve_tree_rows(Multibody::Impl& m, SimTK::Vector& u, std::size_t t, int axes, double kick_s) {
  const double* W = m.tree_delassus.data();
  double* A = m.tree_matrix.data();
  double* b = m.tree_rhs.data();
  double* scale = m.rows_scale.data();  // √C (0: no row)
  double* rate = m.rows_rate.data();
  double* damping_sum = m.rows_damping.data();
  double* residual_sum = m.rows_residual.data();
  int* with_rows = m.rows_axes.data();
  const int* axis = m.solve_order.data() + m.tree_solve_start[t];
  int n = 0;
  for (int p = 0; p < axes; ++p) {
    const auto a = static_cast<std::size_t>(axis[p]);
    rate[p] = axis_dot(m, a, u);
    double damping = 0, residual = 0;
    for (int j = m.first_row[a]; j >= 0; j = m.next_row[j]) {
      const auto& row = m.rows[static_cast<std::size_t>(j)];
      damping += row.damping;
      residual += row.force - row.damping * (rate[p] - row.rate0) - row.applied;
    }
    damping_sum[p] = damping;
    residual_sum[p] = residual;
    scale[p] = std::sqrt(damping);
    if (damping > 0) {
      b[n] = residual / scale[p];
      with_rows[n++] = p;
    }
  }
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k)
      A[i * n + k] = (i == k ? 1.0 : 0.0) + kick_s * scale[with_rows[i]] *
                                                W[with_rows[i] * axes + with_rows[k]] *
                                                scale[with_rows[k]];
  if (n == 0) return;
  common::cholesky_factor(A, n);  // SPD: I + κ·S·W·S
  common::cholesky_substitute(A, n, b, b);
  for (int i = 0; i < n; ++i) {
    const int p = with_rows[i];
    const auto a = static_cast<std::size_t>(axis[p]);
    const double total_change = b[i] * scale[p];  // ΔG
    const bool lone = m.next_row[m.first_row[a]] < 0;
    double change = 0;
    for (int j = m.first_row[a]; j >= 0; j = m.next_row[j]) {
      auto& row = m.rows[static_cast<std::size_t>(j)];
      const double own = row.force - row.damping * (rate[p] - row.rate0) - row.applied;
      const double share = row.damping / damping_sum[p];
      const double wanted =
          row.applied +
          (lone ? total_change : share * total_change + (own - share * residual_sum[p]));
      const double f = std::clamp(wanted, row.low, row.high);
      if (f != wanted) m.tree_sweeps[t] = 1;
      change += f - row.applied;
      row.applied = f;
    }
    if (change != 0.0) add_column(u, kick_s * change, m.minv_column, a);
  }
}

/// Step 2 for tree t (solve_axes): each of its axes solve_order[begin, end) exactly for itself,
/// in turn, until nothing moves, and after each sweep the modes it left solved exactly
/// (axis_modes.cpp).
void sweep_tree(Multibody::Impl& m, SimTK::State& s, std::size_t tree, int begin, int end,
                double kick_s) {
  SimTK::Vector& u = s.updU();
  const int sweeps = end - begin == 1 ? 1 : 16;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    bool changed = false;
    for (int i = begin; i < end; ++i) {
      const int a = m.solve_order[static_cast<std::size_t>(i)];
      const auto axis = static_cast<std::size_t>(a);
      const double w = m.axis_mobility[a];  // g·M^-1·g, kept with its column
      if (!(w > 0)) continue;
      const double delta = solve_one_axis(m, a, axis_dot(m, axis, u), w, kick_s);
      if (delta == 0.0) continue;
      add_column(u, kick_s * delta, m.minv_column, a);
      // A tree axis that sticks stands exactly still (no creep from rounding).
      if (m.friction_bound[a] > 0 && !m.axes[axis].loop && m.axis_stuck[axis])
        u.updContiguousScalarData()[m.axis_u[axis]] = 0.0;  // (a State's u is contiguous)
      // Converged when no axis's speed moves by more than 1e-9 of itself (or 1e-9 rad/s).
      changed =
          changed || std::abs(delta) * kick_s * w > 1e-9 * (1 + std::abs(axis_dot(m, axis, u)));
    }
    if (!changed) break;
    // The modes the sweep left, solved exactly: coupled axes converge slowly by sweeps.
    if (solve_tree_in_modes(m, s, static_cast<int>(tree), begin, end, kick_s)) break;
  }
}

}  // namespace

namespace {

/// Contact friction's sweeps (friction_sweeps.cpp) at most per group and substep, over all
/// its rounds, and the largest speed change at a point (m/s) below which they have converged.
constexpr int kMaxFrictionSweeps = 64;
/// Rounds of the points' sweeps and the tree's axis solve at most (solve_friction_group).
constexpr int kMaxFrictionRounds = 8;
constexpr double kSlipTolerance_m_s = 1e-9;
/// ... plus this fraction of the largest slip a sweep met: points that slide (a body dragged
/// over the floor on several corners) converge slowly, and a change of 1e-6 of their speed
/// is none.
constexpr double kRelativeSlipTolerance = 1e-6;

/// Folds into friction group `group`'s columns the implicit response of tree t's drives that
/// answer linearly now (every row within its bounds, no Coulomb friction on the axis): with h
/// the point's rates of those axes per unit impulse and A = I + κ·C·W over them (W the tree's
/// Delassus matrix, C their damping), a friction impulse changes the drives by −A⁻¹·C·h, so
/// its column becomes c − κ·M⁻¹·Gᵀ·A⁻¹·C·h and its W the Schur complement. Solved as
/// A⁻¹·C = S·B⁻¹·S, B = I + κ·S·W·S, S = √C. Returns how many axes were folded in. `built`:
/// how many the group's columns were last built with in this substep (-1: none); the columns
/// depend on nothing else within it, so the same axes keep them.
int couple_friction_to_drives(Multibody::Impl& m, const SimTK::Vector& u, int group, int begin,
                              int end, double kick_s, int& built) {
  const int n = end - begin;
  const int* axis = m.solve_order.data() + begin;
  const double* W = m.tree_delassus.data();  // the tree's, built by solve_axes
  int* linear = m.friction_linear.data();
  double* scale = m.friction_scale.data();
  int count = 0;
  for (int p = 0; p < n; ++p) {
    const auto a = static_cast<std::size_t>(axis[p]);
    if (m.first_row[a] < 0 || m.friction_bound[a] > 0 || m.axes[a].loop) continue;
    const double rate = axis_dot(m, a, u);
    double damping = 0;
    bool inside = true;
    for (int j = m.first_row[a]; j >= 0; j = m.next_row[j]) {
      const auto& row = m.rows[static_cast<std::size_t>(j)];
      const double f = row.force - row.damping * (rate - row.rate0);
      damping += row.damping;
      inside = inside && f > row.low && f < row.high;
    }
    if (!inside || !(damping > 0)) continue;
    linear[count] = p;
    scale[count++] = std::sqrt(damping);
  }
  int* built_linear = m.friction_built_linear.data();
  if (built == count && std::equal(linear, linear + count, built_linear)) return count;
  built = count;
  std::copy_n(linear, count, built_linear);
  if (count == 0) {
    uncoupled_friction(m, group);
    return 0;
  }
  copy_raw_friction(m, group);
  double* B = m.friction_coupling.data();
  for (int i = 0; i < count; ++i)
    for (int k = 0; k < count; ++k)
      B[i * count + k] =
          (i == k ? 1.0 : 0.0) + kick_s * scale[i] * W[linear[i] * n + linear[k]] * scale[k];
  common::cholesky_factor(B, count);
  const auto stride = static_cast<std::size_t>(m.friction_stride);
  double* y = m.friction_rhs.data();
  for (int q = m.friction_group_start[static_cast<std::size_t>(group)];
       q < m.friction_group_start[static_cast<std::size_t>(group) + 1]; ++q) {
    const auto i = static_cast<std::size_t>(m.friction_order[static_cast<std::size_t>(q)]);
    const auto body = static_cast<std::size_t>(m.friction.points[i].body);
    const int u_begin = m.friction_u_begin[body], span = m.friction_u_end[body] - u_begin;
    for (std::size_t j = 0; j < 2; ++j) {
      const double* c = m.friction_column.data() + (2 * i + j) * stride;
      double* effective = m.friction_effective_column.data() + (2 * i + j) * stride;
      for (int l = 0; l < count; ++l) {  // S·h
        const auto a = static_cast<std::size_t>(axis[linear[l]]);
        y[l] = scale[l] * m.axis_impl[a].sign * c[m.axis_u[a] - u_begin];
      }
      common::cholesky_substitute(B, count, y, y);
      for (int l = 0; l < count; ++l) {
        // Over the column's speeds within the point's range (the same speeds: its tree's).
        const auto a = static_cast<std::size_t>(axis[linear[l]]);
        const int from = std::max(u_begin, m.minv_column.u_begin[a]);
        const int to = std::min(u_begin + span, m.minv_column.u_end[a]);
        const double* column = m.minv_column.of(a) + (from - m.minv_column.u_begin[a]);
        double* out = effective + (from - u_begin);
        const double k = kick_s * scale[l] * y[l];
        for (int e = 0; e < to - from; ++e)
          out[e] -= k * column[e];
      }
    }
    const double* g = m.friction_g.data() + 2 * i * stride;
    const double* c = m.friction_effective_column.data() + 2 * i * stride;
    friction_pair_w(g, g + stride, c, c + stride, span, &m.friction_effective_w[4 * i]);
  }
  build_friction_blocks(m, group);
  return count;
}

/// Friction group `group` solved with tree t's axes solve_order[begin, end) (none: begin ==
/// end, or t < 0). The points' sweeps run with the linear drives' response folded in
/// (couple_friction_to_drives), those drives then take their law at the new speeds (the speeds
/// already carry their change), and the axis solve settles bounds and the axes' friction; until
/// a first sweep after it moves no point.
void solve_friction_group(Multibody::Impl& m, SimTK::State& s, int group, int t, int begin, int end,
                          double kick_s) {
  SimTK::Vector& u = s.updU();
  const bool with_axes = t >= 0 && begin != end;
  int sweeps_left = kMaxFrictionSweeps;  // over all rounds: a bounded cost per substep
  int built = -1;
  for (int round = 0; round < kMaxFrictionRounds && sweeps_left > 0; ++round) {
    const int coupled =
        with_axes ? couple_friction_to_drives(m, u, group, begin, end, kick_s, built) : 0;
    if (!with_axes) uncoupled_friction(m, group);
    bool moved = false;
    while (sweeps_left-- > 0) {
      const double change = sweep_contact_friction(m, u, group, kick_s);
      if (change <= kSlipTolerance_m_s + kRelativeSlipTolerance * m.friction_sweep_slip) break;
      moved = true;
    }
    if (!with_axes || (!moved && round > 0)) return;
    // The folded-in drives at their law for the new speeds, unclamped: the speeds carry the
    // linear change, and the axis solve below clamps what left its bounds.
    bool within = coupled == end - begin;  // every solved axis answered linearly
    for (int l = 0; l < coupled; ++l) {
      const auto a = static_cast<std::size_t>(
          m.solve_order[static_cast<std::size_t>(begin + m.friction_linear[l])]);
      const double rate = axis_dot(m, a, u);
      for (int j = m.first_row[a]; j >= 0; j = m.next_row[j]) {
        auto& row = m.rows[static_cast<std::size_t>(j)];
        row.applied = row.force - row.damping * (rate - row.rate0);
        within = within && row.applied > row.low && row.applied < row.high;
      }
    }
    // Still within their bounds, the drives are solved with the points: nothing for the axis
    // solve to change.
    if (within) return;
    const auto tree = static_cast<std::size_t>(t);
    if (!m.rows.empty()) solve_tree_rows(m, u, tree, end - begin, kick_s);
    if (m.tree_sweeps[tree]) sweep_tree(m, s, tree, begin, end, kick_s);
  }
}

}  // namespace

void solve_axes(Multibody::Impl& m, SimTK::State& s, double kick_s) {
  const bool friction = prepare_contact_friction(m, s);
  // The axes to solve: those with drive rows, and the tree axes whose friction may stop them.
  m.solve_list.clear();
  std::fill(m.first_row.begin(), m.first_row.end(), -1);
  std::fill(m.friction_bound.begin(), m.friction_bound.end(), 0.0);
  for (int i = static_cast<int>(m.rows.size()); i-- > 0;) {
    const int a = m.rows[i].axis;
    if (m.first_row[a] < 0) m.solve_list.push_back(a);
    m.next_row[i] = m.first_row[a];
    m.first_row[a] = i;
  }
  // Which trees sweep in step 2 below, each for itself: whether another tree's axis has friction
  // or hit a bound must not change this tree's numbers (a part of the parallel islands holds
  // only some trees; the last bits once differed from the whole system's).
  std::fill(m.tree_sweeps.begin(), m.tree_sweeps.end(), 0);
  for (std::size_t a = 0; a < m.axes.size(); ++a)
    if (m.axis_friction[a] > 0.0 && !m.axes[a].loop && !m.sliding[a]) {
      m.friction_bound[a] = m.axis_friction[a];
      m.tree_sweeps[static_cast<std::size_t>(m.axis_tree[a])] = 1;
      if (m.first_row[a] < 0) m.solve_list.push_back(static_cast<int>(a));
    }
  if (m.solve_list.empty() && !friction) return;
  update_columns(m, s, m.solve_list);
  SimTK::Vector& u = s.updU();
  // Tree by tree (axis_trees.cpp): 1. the drive rows without bounds, all at once; 2. where a
  // bound binds or an axis has friction, the sweeps. Each tree until its own axes converge, so
  // that a robot's numbers do not depend on another's (the parallel islands' parts must match
  // the serial run).
  group_solve_list_by_tree(m);
  // The friction groups are ordered by key (prepare_contact_friction): the axis trees' in tree
  // order, then those without axes. A cursor walks them with the trees.
  int group = 0;
  for (std::size_t t = 0; t + 1 < m.tree_solve_start.size(); ++t) {
    const int begin = m.tree_solve_start[t], end = m.tree_solve_start[t + 1];
    if (begin != end) {  // (a row's axis is in the solve list)
      build_tree_delassus(m, begin, end);
      if (!m.rows.empty()) solve_tree_rows(m, u, t, end - begin, kick_s);
      if (m.tree_sweeps[t]) sweep_tree(m, s, t, begin, end, kick_s);
    }
    // The contact friction on the tree's bodies, with its axes.
    for (; friction && group < m.friction_groups &&
           friction_group_tree(m, group) == static_cast<int>(t);
         ++group)
      solve_friction_group(m, s, group, static_cast<int>(t), begin, end, kick_s);
  }
  // The friction on trees without axes.
  for (int g = group; friction && g < m.friction_groups; ++g)
    if (friction_group_tree(m, g) < 0) solve_friction_group(m, s, g, -1, 0, 0, kick_s);
  if (friction) finish_contact_friction(m, kick_s);
  for (const auto& row : m.rows)
    if (row.component) m.drive_sum[row.axis] += row.applied;
}

}  // namespace s2sim::model
