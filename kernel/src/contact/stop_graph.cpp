#include "contact/stop_graph.hpp"

#include "common/cholesky.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::contact {

namespace {
constexpr int kMaxSweeps = 16;
/// Held points alone, warm-started: what a few sweeps leave is taken up next step.
constexpr int kMaxSweepsHeldOnly = 4;
/// Sweeps end once no row's separating speed moves by more than this.
constexpr double kConverged_m_s = 1e-5;
/// The exact solve (groups of up to StopGraph::kExactRows rows): its regularisation, of the
/// Delassus matrix's largest diagonal, and how far short of its wanted change an inactive row
/// may be before it joins.
constexpr double kRegularisation = 1e-9;
constexpr double kShort_m_s = 1e-9;
}  // namespace

void StopGraph::reserve(std::size_t bodies, std::size_t rows) {
  rows_.reserve(rows);
  resting_.reserve(rows);
  order_.reserve(rows);
  group_begin_.reserve(rows + 1);
  row_group_.reserve(rows);
  parent_.assign(bodies, -1);
  group_of_root_.assign(bodies, -1);
  reached_.assign(bodies, 0);
  linear_.assign(bodies, Vec3{});
  angular_.assign(bodies, Vec3{});
  constexpr auto n = static_cast<std::size_t>(kExactRows);
  delassus_.assign(n * n, 0.0);
  block_.assign(n * n, 0.0);
  exact_b_.assign(n, 0.0);
  exact_pb_.assign(n, 0.0);
  exact_px_.assign(n, 0.0);
  exact_impulse_.assign(n, 0.0);
  active_.assign(n, 0);
  active_list_.assign(n, 0);
}

void StopGraph::clear() {
  rows_.clear();
  resting_.clear();
  held_count_ = 0;
}

void StopGraph::add_stop(std::int32_t body_a, std::int32_t body_b, const Vec3& point_m,
                         const Vec3& normal, double wanted_change_m_s) {
  rows_.push_back(
      {body_a, body_b, point_m, normal, wanted_change_m_s, -1, -1, {}, {}, {}, {}, 0, 0});
}

void StopGraph::take(Resting& r, const ContactInfo* info) {
  // Closing no faster than max(closing, 0): the separating speed may drop by -min(closing, 0)
  // at most, i.e. change by at least min(closing, 0). A held point may not close at all, and
  // one deep in an overlap separates at its recovery speed.
  const ContactInfo& c = info[r.info];
  rows_.push_back({r.body_a,
                   r.body_b,
                   c.point_m,
                   c.normal,
                   r.held ? r.closing_m_s + r.recovery_m_s : std::min(r.closing_m_s, 0.0),
                   r.info,
                   r.memory,
                   {},
                   {},
                   {},
                   {},
                   0,
                   std::max(0.0, r.last_impulse_N_s)});
  r.taken = 1;
}

std::size_t StopGraph::reach(const ContactInfo* info) {
  // Stops reach; held points do not (their impulses are a spring's share of a load, which the
  // springs around pass on well enough, and a settled pile holds everywhere).
  for (const Row& r : rows_) {
    reached_[static_cast<std::size_t>(r.body_a)] = 1;
    reached_[static_cast<std::size_t>(r.body_b)] = 1;
  }
  reached_[0] = 0;  // the world passes nothing on
  const bool stops = !rows_.empty();
  if (held_count_ > 0)
    for (Resting& r : resting_)
      if (r.held) take(r, info);
  // A resting point is reached when one of its bodies is; it then reaches its other body.
  // Passes until nothing new (a stack of n bodies needs about n); taken rows keep their order.
  for (bool grew = stops; grew;) {
    grew = false;
    for (Resting& r : resting_) {
      if (r.taken) continue;
      const auto a = static_cast<std::size_t>(r.body_a), b = static_cast<std::size_t>(r.body_b);
      if (!reached_[a] && !reached_[b]) continue;
      if (!reached_[a] || (b != 0 && !reached_[b])) grew = true;
      reached_[a] = 1;
      if (b != 0) reached_[b] = 1;
      take(r, info);
    }
  }
  return rows_.size();
}

std::int32_t StopGraph::root(std::int32_t body) {
  auto& parent = parent_;
  while (parent[static_cast<std::size_t>(body)] >= 0) {
    const std::int32_t up = parent[static_cast<std::size_t>(body)];
    if (parent[static_cast<std::size_t>(up)] >= 0)
      parent[static_cast<std::size_t>(body)] = parent[static_cast<std::size_t>(up)];  // halving
    body = up;
  }
  return body;
}

std::size_t StopGraph::group_rows(std::size_t count) {
  // Union–find over the rows' bodies, then the rows grouped by their first row's order (a
  // counting sort, stable: each group keeps its rows' order).
  for (std::size_t i = 0; i < count; ++i) {
    const Row& r = rows_[i];
    if (r.body_b == 0) continue;
    const std::int32_t a = root(r.body_a), b = root(r.body_b);
    if (a != b) parent_[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
  row_group_.clear();
  group_begin_.assign(1, 0);
  std::size_t groups = 0;
  for (std::size_t i = 0; i < count; ++i) {
    std::int32_t& group = group_of_root_[static_cast<std::size_t>(root(rows_[i].body_a))];
    if (group < 0) {
      group = static_cast<std::int32_t>(groups++);
      group_begin_.push_back(0);
    }
    row_group_.push_back(group);
    ++group_begin_[static_cast<std::size_t>(group) + 1];
  }
  for (std::size_t g = 0; g < groups; ++g)
    group_begin_[g + 1] += group_begin_[g];
  order_.resize(count);
  for (std::size_t i = 0; i < count; ++i)
    order_[group_begin_[static_cast<std::size_t>(row_group_[i])]++] = i;
  for (std::size_t g = groups; g > 0; --g)  // back to each group's first row
    group_begin_[g] = group_begin_[g - 1];
  group_begin_[0] = 0;
  for (std::size_t i = 0; i < count; ++i) {  // forget, for the next solve
    const Row& r = rows_[i];
    group_of_root_[static_cast<std::size_t>(root(r.body_a))] = -1;
  }
  for (std::size_t i = 0; i < count; ++i) {
    parent_[static_cast<std::size_t>(rows_[i].body_a)] = -1;
    parent_[static_cast<std::size_t>(rows_[i].body_b)] = -1;
  }
  return groups;
}

double StopGraph::change_of(const Row& r) const {
  const auto a = static_cast<std::size_t>(r.body_a), b = static_cast<std::size_t>(r.body_b);
  double change = dot(r.normal, linear_[a]) + dot(r.lever_a, angular_[a]);
  if (b != 0) change -= dot(r.normal, linear_[b]) + dot(r.lever_b, angular_[b]);
  return change;
}

void StopGraph::push(const Row& r, double impulse_N_s, const BodyInertiaView& bodies) {
  const auto a = static_cast<std::size_t>(r.body_a), b = static_cast<std::size_t>(r.body_b);
  linear_[a] += r.normal * (impulse_N_s * bodies.inverse_mass[a]);
  angular_[a] += r.turn_a * impulse_N_s;
  if (b != 0) {
    linear_[b] -= r.normal * (impulse_N_s * bodies.inverse_mass[b]);
    angular_[b] -= r.turn_b * impulse_N_s;
  }
}

bool StopGraph::solve_group_exactly(const BodyInertiaView& bodies, const std::size_t* first,
                                    const std::size_t* last) {
  const auto n = static_cast<int>(last - first);
  if (n > kExactRows || delassus_.empty()) return false;
  const auto row = [&](int i) -> Row& { return rows_[first[i]]; };
  // A_ij: the change of row i's separating speed per unit impulse of row j, through the bodies
  // they share (the world moves for none). b_i: what row i needs from the impulses alone, its
  // wanted change less what the forces so far give (the change now, less its impulses' share).
  double* A = delassus_.data();
  const auto effect = [&](const Row& on, const Row& by) {
    double e = 0;
    const auto through = [&](std::int32_t body, const Vec3& lever_on, double sign_on) {
      if (body == 0) return;
      const auto k = static_cast<std::size_t>(body);
      if (by.body_a == body)
        e += sign_on *
             (dot(on.normal, by.normal) * bodies.inverse_mass[k] + dot(lever_on, by.turn_a));
      if (by.body_b == body)
        e -= sign_on *
             (dot(on.normal, by.normal) * bodies.inverse_mass[k] + dot(lever_on, by.turn_b));
    };
    through(on.body_a, on.lever_a, 1.0);
    through(on.body_b, on.lever_b, -1.0);
    return e;
  };
  double largest_diagonal = 0;
  for (int i = 0; i < n; ++i) {
    const Row& r = row(i);
    const double change = change_of(r);
    for (int j = 0; j <= i; ++j)
      A[i * n + j] = A[j * n + i] = effect(r, row(j));
    largest_diagonal = std::max(largest_diagonal, A[i * n + i]);
    exact_b_[static_cast<std::size_t>(i)] = r.wanted_m_s - change;
  }
  if (!(largest_diagonal > 0)) return false;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      exact_b_[static_cast<std::size_t>(i)] += A[i * n + j] * row(j).impulse_N_s;

  // Active set: at first the rows that pushed last step (a load held from step to step: one
  // round) and those the other forces leave short of their change; then, each round, the most
  // negative impulse leaves, or else the row most short of its wanted change joins, until
  // neither is left.
  for (int i = 0; i < n; ++i) {
    // exact_b_: the change the row is short of with no impulse at all.
    active_[static_cast<std::size_t>(i)] =
        row(i).impulse_N_s > 0 || exact_b_[static_cast<std::size_t>(i)] > 0;
  }
  double* x = exact_impulse_.data();
  for (int round = 0; round < 4 * n + 4; ++round) {
    int m = 0;
    for (int i = 0; i < n; ++i)
      if (active_[static_cast<std::size_t>(i)]) active_list_[static_cast<std::size_t>(m++)] = i;
    for (int i = 0; i < n; ++i)
      x[i] = 0;
    if (m > 0) {
      double* block = block_.data();
      for (int p = 0; p < m; ++p) {
        const int i = active_list_[static_cast<std::size_t>(p)];
        exact_pb_[static_cast<std::size_t>(p)] = exact_b_[static_cast<std::size_t>(i)];
        for (int q = 0; q <= p; ++q)
          block[p * m + q] = A[i * n + active_list_[static_cast<std::size_t>(q)]];
      }
      // Coplanar points are redundant rows (four corners of a face, three unknowns): a
      // regularisation of 1e-9 of the largest diagonal picks, among the impulses that give
      // every active row its change (to that share), the least-norm one, shared evenly.
      for (int p = 0; p < m; ++p)
        block[p * m + p] += kRegularisation * largest_diagonal;
      if (!common::cholesky_factor(block, m)) return false;
      common::cholesky_substitute(block, m, exact_pb_.data(), exact_px_.data());
      // Two rounds of refinement against A itself take the regularisation's bias out of the
      // rows' changes (to rounding) and leave the shares as they are.
      for (int refine = 0; refine < 2; ++refine) {
        for (int p = 0; p < m; ++p) {
          const int i = active_list_[static_cast<std::size_t>(p)];
          double residual = exact_b_[static_cast<std::size_t>(i)];
          for (int q = 0; q < m; ++q)
            residual -= A[i * n + active_list_[static_cast<std::size_t>(q)]] *
                        exact_px_[static_cast<std::size_t>(q)];
          exact_pb_[static_cast<std::size_t>(p)] = residual;
        }
        common::cholesky_substitute(block, m, exact_pb_.data(), exact_pb_.data());
        for (int p = 0; p < m; ++p)
          exact_px_[static_cast<std::size_t>(p)] += exact_pb_[static_cast<std::size_t>(p)];
      }
      for (int p = 0; p < m; ++p)
        x[active_list_[static_cast<std::size_t>(p)]] = exact_px_[static_cast<std::size_t>(p)];
    }
    int leave = -1;
    double most_negative = 0;
    for (int p = 0; p < m; ++p) {
      const int i = active_list_[static_cast<std::size_t>(p)];
      if (x[i] < most_negative) most_negative = x[i], leave = i;
    }
    if (leave >= 0) {
      active_[static_cast<std::size_t>(leave)] = 0;
      continue;
    }
    int join = -1;
    double most_short = kShort_m_s;
    for (int i = 0; i < n; ++i) {
      if (active_[static_cast<std::size_t>(i)]) continue;
      double change = -exact_b_[static_cast<std::size_t>(i)];
      for (int j = 0; j < n; ++j)
        change += A[i * n + j] * x[j];
      if (-change > most_short) most_short = -change, join = i;
    }
    if (join < 0) {
      // Settled: every impulse pushes and every row gets its wanted change. The velocity
      // changes follow the impulses' differences.
      for (int i = 0; i < n; ++i) {
        Row& r = row(i);
        push(r, x[i] - r.impulse_N_s, bodies);
        r.impulse_N_s = x[i];
      }
      return true;
    }
    active_[static_cast<std::size_t>(join)] = 1;
  }
  return false;
}

void StopGraph::solve(const BodyInertiaView& bodies, double step_s, Wrench* wrenches,
                      ContactInfo* info) {
  if (empty()) return;
  const std::size_t count = reach(info);
  // Each row's lever arms and its own effective mass.
  auto lever = [&](std::int32_t body, const Vec3& point, const Vec3& normal, Vec3& arm,
                   Vec3& turn) {
    if (body == 0) return 0.0;
    const auto b = static_cast<std::size_t>(body);
    const Mat3& rt = bodies.to_body[b];
    arm = cross(rt * (point - bodies.poses[body].position) - bodies.com_m[b], rt * normal);
    turn = bodies.inverse_inertia[b] * arm;
    return bodies.inverse_mass[b] + dot(arm, turn);
  };
  // The velocity changes the forces found so far (the springs, the dampers, friction) and
  // gravity give in this step: a stop or a held point must not be undone by a spring pushing
  // its body on, nor a held point sink under its load.
  auto start = [&](std::int32_t body) {
    const auto b = static_cast<std::size_t>(body);
    if (body == 0 || reached_[b] == 2) return;
    reached_[b] = 2;
    const Wrench& w = wrenches[b];
    const Mat3& rt = bodies.to_body[b];
    const Vec3 com_offset = bodies.poses[body].rotation * bodies.com_m[b];
    const Vec3 torque_about_com = w.torque_Nm - cross(com_offset, w.force_N);
    linear_[b] = w.force_N * (step_s * bodies.inverse_mass[b]);
    linear_[b].z -= bodies.falls_m_s2[b] * step_s;
    angular_[b] = bodies.inverse_inertia[b] * (rt * torque_about_com) * step_s;
  };
  for (std::size_t i = 0; i < count; ++i) {
    start(rows_[i].body_a);
    start(rows_[i].body_b);
  }
  for (std::size_t i = 0; i < count; ++i) {
    Row& r = rows_[i];
    const double inverse = lever(r.body_a, r.point_m, r.normal, r.lever_a, r.turn_a) +
                           lever(r.body_b, r.point_m, r.normal, r.lever_b, r.turn_b);
    r.mass_kg = inverse > 0 ? 1 / inverse : 0;
    // Warm start: the resting rows begin with last step's impulse.
    if (r.impulse_N_s != 0) push(r, r.impulse_N_s, bodies);
  }
  // Each group of rows joined through their bodies (the world joins nothing) is solved as it
  // would be alone, so that a part of the island-parallel step, which holds whole groups, solves
  // its own to the same bits: exactly when small; else by projected Gauss–Seidel on the velocity
  // changes, each row in turn taking the impulse that gives it its wanted change, never
  // pulling, until the group converges.
  const std::size_t groups = group_rows(count);
  for (std::size_t g = 0; g < groups; ++g) {
    const std::size_t* first = order_.data() + group_begin_[g];
    const std::size_t* last = order_.data() + group_begin_[g + 1];
    if (solve_group_exactly(bodies, first, last)) continue;
    bool has_stop = false;
    for (const std::size_t* i = first; i != last; ++i)
      has_stop = has_stop || rows_[*i].info < 0;
    const int sweeps = has_stop ? kMaxSweeps : kMaxSweepsHeldOnly;
    for (int sweep = 0; sweep < sweeps; ++sweep) {
      double largest = 0;
      for (const std::size_t* i = first; i != last; ++i) {
        Row& r = rows_[*i];
        const double impulse =
            std::max(0.0, r.impulse_N_s + (r.wanted_m_s - change_of(r)) * r.mass_kg);
        const double d = impulse - r.impulse_N_s;
        if (d == 0) continue;
        r.impulse_N_s = impulse;
        largest = std::max(largest, std::abs(d) / r.mass_kg);
        push(r, d, bodies);
      }
      if (largest < kConverged_m_s) break;
    }
  }
  for (std::size_t i = 0; i < count; ++i) {
    const Row& r = rows_[i];
    const auto a = static_cast<std::size_t>(r.body_a), b = static_cast<std::size_t>(r.body_b);
    linear_[a] = linear_[b] = angular_[a] = angular_[b] = Vec3{};
    reached_[a] = reached_[b] = 0;
    if (r.impulse_N_s == 0) continue;
    const Vec3 force = r.normal * (r.impulse_N_s / step_s);
    Wrench& wa = wrenches[a];
    wa.force_N += force;
    wa.torque_Nm += cross(r.point_m - bodies.poses[a].position, force);
    if (b != 0) {
      Wrench& wb = wrenches[b];
      wb.force_N -= force;
      wb.torque_Nm -= cross(r.point_m - bodies.poses[b].position, force);
    }
    if (r.info >= 0) info[r.info].force_N += force;
  }
}

}  // namespace s2sim::contact
