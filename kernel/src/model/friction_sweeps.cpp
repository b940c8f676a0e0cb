// The sweeps of contact friction on jointed bodies (contact_friction.cpp says the method): a
// point solved for itself (its two tangents at once, sliding on the Coulomb circle by the
// secular equation), a body's points solved as one block while they stick, and the sweep over
// a group of them.
#include "common/cholesky.hpp"
#include "model/dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace s2sim::model {
namespace {

/// Numbers of friction_block_w per order position: a block of k points keeps its W and the
/// factor of W + ε·I there, 8·k² ≤ 64·k.
constexpr std::size_t kBlockRoom = 64;
/// ε of a block's solve, relative to its largest entry (solve_members).
constexpr double kBlockRegularisation = 1e-6;

/// Calls `fixed(std::integral_constant<int, N>{})` for a block of N rows (two per point) known
/// at compile time, unrolled, else `any()`: the same numbers in fewer instructions.
static_assert(kMaxBlockPoints == 8, "a case per block size below");
template <class Fixed, class Any>
auto at_block_size(int size, Fixed&& fixed, Any&& any) {
  using std::integral_constant;
  switch (size) {
    case 2:
      return fixed(integral_constant<int, 2>{});
    case 4:
      return fixed(integral_constant<int, 4>{});
    case 6:
      return fixed(integral_constant<int, 6>{});
    case 8:
      return fixed(integral_constant<int, 8>{});
    case 10:
      return fixed(integral_constant<int, 10>{});
    case 12:
      return fixed(integral_constant<int, 12>{});
    case 14:
      return fixed(integral_constant<int, 14>{});
    case 16:
      return fixed(integral_constant<int, 16>{});
    default:
      return any();
  }
}
bool factor_block(double* A, int size) {
  return at_block_size(
      size, [&](auto n) { return common::cholesky_factor<decltype(n)::value>(A); },
      [&] { return common::cholesky_factor(A, size); });
}
void substitute_block(const double* L, int size, double* x) {
  at_block_size(
      size, [&](auto n) { common::cholesky_substitute<decltype(n)::value>(L, x, x); },
      [&] { common::cholesky_substitute(L, size, x, x); });
}

/// Point i's slip along its two tangents at the speeds x, against its surface.
void point_slip(const Multibody::Impl& m, const double* x, int i, double* v) {
  const auto stride = static_cast<std::size_t>(m.friction_stride);
  const FrictionPoint& p = m.friction.points[i];
  const auto b = static_cast<std::size_t>(p.body);
  const int begin = m.friction_u_begin[b], span = m.friction_u_end[b] - begin;
  const double* g0 = m.friction_g.data() + 2 * static_cast<std::size_t>(i) * stride;
  const double* g1 = g0 + stride;
  // Summed in locals, not in v: the compiler would store it at every term, as the rows might
  // overlap it.
  double slip0 = -dot(p.surface_velocity_m_s, p.direction[0]);
  double slip1 = -dot(p.surface_velocity_m_s, p.direction[1]);
  const double* xu = x + begin;
  for (int e = 0; e < span; ++e) {
    slip0 += g0[e] * xu[e];
    slip1 += g1[e] * xu[e];
  }
  v[0] = slip0;
  v[1] = slip1;
}

/// Adds point i's impulse change (d0, d1) to the speeds x.
void apply_impulse(const Multibody::Impl& m, double* x, int i, double d0, double d1) {
  const auto stride = static_cast<std::size_t>(m.friction_stride);
  const auto b = static_cast<std::size_t>(m.friction.points[i].body);
  const int begin = m.friction_u_begin[b], span = m.friction_u_end[b] - begin;
  const double* c0 = m.friction_effective_column.data() + 2 * static_cast<std::size_t>(i) * stride;
  const double* c1 = c0 + stride;
  double* xw = x + begin;
  for (int e = 0; e < span; ++e)
    xw[e] += c0[e] * d0 + c1[e] * d1;
}

/// Point i solved for itself, the others held; returns the largest slip change it made.
double solve_point(Multibody::Impl& m, double* x, int i, double kick_s) {
  {  // (one scope: the point's numbers)
    const FrictionPoint& p = m.friction.points[i];
    const double* w = &m.friction_effective_w[4 * static_cast<std::size_t>(i)];
    double* lambda = &m.friction_impulse[2 * static_cast<std::size_t>(i)];
    double v[2];
    point_slip(m, x, i, v);
    m.friction_sweep_slip = std::max(m.friction_sweep_slip, std::abs(v[0]) + std::abs(v[1]));
    double next[2] = {lambda[0], lambda[1]};
    const double det = w[0] * w[3] - w[1] * w[2];
    if (p.isotropic && w[0] > 0 && w[3] > 0 && det > 1e-9 * w[0] * w[3]) {
      // Both tangents at once: the slip this point would have without its friction, then the
      // impulse that cancels it, λ = −W⁻¹·v₀. Past the bound, the point slides: the impulse on
      // the circle that opposes the slip it leaves (Coulomb's law at the step's end),
      // λ = −(W + γ·I)⁻¹·v₀ with γ > 0 such that |λ| is the bound (then v⁺ = −γ·λ).
      const double v0[2] = {v[0] - w[0] * lambda[0] - w[1] * lambda[1],
                            v[1] - w[2] * lambda[0] - w[3] * lambda[1]};
      auto solve = [&](double gamma, double* out) {
        const double a = w[0] + gamma, d = w[3] + gamma;
        const double inverse_det = 1 / (a * d - w[1] * w[2]);
        out[0] = -(d * v0[0] - w[1] * v0[1]) * inverse_det;
        out[1] = -(a * v0[1] - w[2] * v0[0]) * inverse_det;
      };
      solve(0.0, next);
      const double bound = kick_s * p.limit_N[0];
      const double r2 = next[0] * next[0] + next[1] * next[1];
      if (r2 > bound * bound) {
        // |λ(γ)|² = Σ cᵢ²/(eᵢ + γ)² over W's eigenpairs, c = Qᵀ·v₀: Newton on 1/|λ| − 1/bound,
        // nearly linear in γ, from γ = 0 (Moré and Sorensen's secular equation), which
        // converges from below without overshooting.
        const double mean = 0.5 * (w[0] + w[3]), half = 0.5 * (w[0] - w[3]);
        const double off = 0.5 * (w[1] + w[2]), radius = std::hypot(half, off);
        const double e[2] = {mean + radius, mean - radius};
        const double angle = 0.5 * std::atan2(off, half);
        const double cq = std::cos(angle), sq = std::sin(angle);
        const double c[2] = {cq * v0[0] + sq * v0[1], -sq * v0[0] + cq * v0[1]};
        double gamma = 0;
        for (int k = 0; k < 30 && bound > 0; ++k) {
          double norm2 = 0, slope = 0;  // |λ|² and d|λ|²/dγ
          for (int r = 0; r < 2; ++r) {
            const double q = 1 / (e[r] + gamma);
            norm2 += c[r] * c[r] * q * q;
            slope -= 2 * c[r] * c[r] * q * q * q;
          }
          const double length = std::sqrt(norm2);
          // ψ(γ) = 1/|λ| − 1/bound, ψ' = −½·|λ|⁻³·d|λ|²/dγ.
          const double psi = 1 / length - 1 / bound, dpsi = -0.5 * slope / (norm2 * length);
          const double step = -psi / dpsi;
          gamma += step;
          if (!(std::abs(step) > 1e-14 * (gamma + mean))) break;
        }
        solve(bound > 0 ? gamma : 0.0, next);
      }
    } else {
      // One direction at a time (a pyramid's own bounds, or a point movable along one only).
      for (int j = 0; j < 2; ++j) {
        const double wjj = w[3 * j];
        if (!(wjj > 0)) continue;
        double l = next[j] - v[j] / wjj;
        if (!p.isotropic) l = std::clamp(l, -kick_s * p.limit_N[j], kick_s * p.limit_N[j]);
        const double delta = l - next[j];
        next[j] = l;
        v[1 - j] += w[2 * (1 - j) + j] * delta;
      }
    }
    if (p.isotropic) {
      const double bound = kick_s * p.limit_N[0];
      const double r2 = next[0] * next[0] + next[1] * next[1];
      if (r2 > bound * bound) {  // (rounding of the slide's solve, or one direction at a time)
        const double scale = bound / std::sqrt(r2);
        next[0] *= scale;
        next[1] *= scale;
      }
    }
    const double d0 = next[0] - lambda[0], d1 = next[1] - lambda[1];
    if (d0 == 0.0 && d1 == 0.0) return 0;
    apply_impulse(m, x, i, d0, d1);
    lambda[0] = next[0];
    lambda[1] = next[1];
    return std::max(std::abs(w[0] * d0 + w[1] * d1), std::abs(w[2] * d0 + w[3] * d1));
  }
}

/// Whether point i's impulse (l0, l1) is within its bounds.
bool within_bounds(const Multibody::Impl& m, int i, double l0, double l1, double kick_s) {
  const FrictionPoint& p = m.friction.points[i];
  const double b0 = kick_s * p.limit_N[0], b1 = kick_s * p.limit_N[1];
  if (p.isotropic) return l0 * l0 + l1 * l1 <= b0 * b0;
  return std::abs(l0) <= b0 && std::abs(l1) <= b1;
}

/// The points `members` (bit q: order position n + q) of the block at [n, n + k) solved at
/// once, the others held: λ = −(W + ε·I)⁻¹·v₀ over them, W regularised by 1e-6 of its largest
/// entry (the corners of a box on the floor are 8 rows on 3 motions, W singular: this takes
/// the smallest impulses that hold it, its load spread over the corners, and leaves a slip of
/// 1e-6 of the impulses' speed change). False, changing nothing, when some would leave their
/// bounds: their bits in `outside`. `change`: the largest slip change.
bool solve_members(Multibody::Impl& m, double* x, int n, int k, unsigned members, double kick_s,
                   double& change, unsigned& outside) {
  const auto dim = static_cast<std::size_t>(2 * k);
  const double* W = m.friction_block_w.data() + kBlockRoom * static_cast<std::size_t>(n);
  const int* order = m.friction_order.data() + n;
  std::size_t index[2 * kMaxBlockPoints];  // the members' rows in W
  std::size_t size = 0;
  for (int q = 0; q < k; ++q)
    if (members & (1u << q)) {
      index[size++] = 2 * static_cast<std::size_t>(q);
      index[size++] = 2 * static_cast<std::size_t>(q) + 1;
    }
  double* v = m.friction_block_rhs.data();
  double* lambda = v + dim;
  double* next = lambda + dim;
  double* L = next + dim;
  for (int q = 0; q < k; ++q) {
    point_slip(m, x, order[q], v + 2 * q);
    m.friction_sweep_slip =
        std::max(m.friction_sweep_slip, std::abs(v[2 * q]) + std::abs(v[2 * q + 1]));
    lambda[2 * q] = m.friction_impulse[2 * static_cast<std::size_t>(order[q])];
    lambda[2 * q + 1] = m.friction_impulse[2 * static_cast<std::size_t>(order[q]) + 1];
  }
  // v₀ = v − W·λ over the members: their slip without their own impulses.
  double v0[2 * kMaxBlockPoints];
  const bool whole = members == (1u << k) - 1;
  if (whole) {
    // Column by column, W's rows being its columns (it is mirrored): each row's terms in the
    // same order, the rows at once.
    std::copy_n(v, dim, v0);
    for (std::size_t c = 0; c < dim; ++c) {
      const double* column = W + c * dim;
      const double l = lambda[c];
      for (std::size_t r = 0; r < dim; ++r)
        v0[r] -= column[r] * l;
    }
  } else {
    for (std::size_t r = 0; r < size; ++r) {
      v0[r] = v[index[r]];
      for (std::size_t c = 0; c < size; ++c)
        v0[r] -= W[index[r] * dim + index[c]] * lambda[index[c]];
    }
  }
  outside = 0;
  const double* factor = L;
  if (whole) {  // the whole block: its factor, built with W
    if (!m.friction_block_factored[static_cast<std::size_t>(n)]) return false;
    factor = W + dim * dim;
  } else {
    double largest = 0;
    for (std::size_t r = 0; r < size; ++r)
      for (std::size_t c = 0; c < size; ++c) {
        L[r * size + c] = W[index[r] * dim + index[c]];
        largest = std::max(largest, std::abs(L[r * size + c]));
      }
    if (!(largest > 0)) return false;
    for (std::size_t r = 0; r < size; ++r)
      L[r * size + r] += kBlockRegularisation * largest;
    if (!factor_block(L, static_cast<int>(size))) return false;
  }
  substitute_block(factor, static_cast<int>(size), v0);
  for (std::size_t r = 0; r < dim; ++r)
    next[r] = lambda[r];
  for (std::size_t r = 0; r < size; ++r)
    next[index[r]] = -v0[r];
  for (int q = 0; q < k; ++q)
    if ((members & (1u << q)) && !within_bounds(m, order[q], next[2 * q], next[2 * q + 1], kick_s))
      outside |= 1u << q;
  if (outside) return false;
  change = 0;
  for (std::size_t r = 0; r < dim; ++r)
    lambda[r] = next[r] - lambda[r];  // the changes (zero but the members')
  // W·Δλ, column by column as v₀ above.
  double dv[2 * kMaxBlockPoints];
  std::fill_n(dv, dim, 0.0);
  for (std::size_t c = 0; c < dim; ++c) {
    const double* column = W + c * dim;
    const double l = lambda[c];
    for (std::size_t r = 0; r < dim; ++r)
      dv[r] += column[r] * l;
  }
  for (std::size_t r = 0; r < dim; ++r)
    change = std::max(change, std::abs(dv[r]));
  for (int q = 0; q < k; ++q) {
    if (!(members & (1u << q))) continue;
    const auto i = static_cast<std::size_t>(order[q]);
    apply_impulse(m, x, order[q], lambda[2 * q], lambda[2 * q + 1]);
    m.friction_impulse[2 * i] = next[2 * q];
    m.friction_impulse[2 * i + 1] = next[2 * q + 1];
  }
  return true;
}

/// The block of `k` points of one tree at order positions [n, n + k): all at once while they
/// stick (Gauss–Seidel converges slowly on points that nearly repeat each other, a tyre's two
/// tread points, and on points the tree ties together, a humanoid's two feet: a loop through
/// the floor). Those that would leave their bounds slide: each is
/// solved for itself (Coulomb's law exactly), then the rest at once with them held, or each
/// for itself if one of those slides too. Returns the largest slip change.
double solve_block(Multibody::Impl& m, double* x, int n, int k, double kick_s) {
  const unsigned all = (1u << k) - 1;
  double change = 0;
  unsigned outside = 0;
  if (m.friction_block_factored[static_cast<std::size_t>(n)] &&
      solve_members(m, x, n, k, all, kick_s, change, outside))
    return change;
  if (outside == 0) outside = all;  // W unusable: each point for itself
  auto each = [&](unsigned points) {
    for (int q = 0; q < k; ++q)
      if (points & (1u << q))
        change = std::max(
            change, solve_point(m, x, m.friction_order[static_cast<std::size_t>(n + q)], kick_s));
  };
  each(outside);
  const unsigned rest = all & ~outside;
  if (rest == 0) return change;
  double rest_change = 0;
  unsigned sliding = 0;
  if (solve_members(m, x, n, k, rest, kick_s, rest_change, sliding))
    return std::max(change, rest_change);
  each(rest);
  return change;
}

}  // namespace

void build_friction_blocks(Multibody::Impl& m, int group) {
  const auto stride = static_cast<std::size_t>(m.friction_stride);
  const int first = m.friction_group_start[static_cast<std::size_t>(group)];
  const int last = m.friction_group_start[static_cast<std::size_t>(group) + 1];
  for (int n = first; n < last;) {
    const int k = m.friction_block_size[static_cast<std::size_t>(n)];
    if (k > 1) {
      const auto dim = static_cast<std::size_t>(2 * k);
      double* W = m.friction_block_w.data() + kBlockRoom * static_cast<std::size_t>(n);
      double* L = W + dim * dim;
      const int* order = m.friction_order.data() + n;
      const auto body = static_cast<std::size_t>(m.friction.points[order[0]].body);
      const int span = m.friction_u_end[body] - m.friction_u_begin[body];
      // Symmetric (W = G·M_eff⁻¹·Gᵀ): the upper triangle, mirrored, point by point: a point's
      // own 2×2 is its W (the same sums), another's four entries in one pass.
      double largest = 0;
      for (int p = 0; p < k; ++p) {
        const auto i = static_cast<std::size_t>(order[p]);
        const double* g = m.friction_g.data() + 2 * i * stride;
        for (int q = p; q < k; ++q) {
          const auto j = static_cast<std::size_t>(order[q]);
          const auto b = static_cast<std::size_t>(m.friction.points[j].body);
          double pair[4];
          if (q == p && m.friction_u_end[b] - m.friction_u_begin[b] == span) {
            std::copy_n(&m.friction_effective_w[4 * i], 4, pair);
            pair[2] = pair[1];  // (the upper entry, mirrored)
          } else {
            const double* col = m.friction_effective_column.data() + 2 * j * stride;
            friction_pair_w(g, g + stride, col, col + stride, span, pair);
            if (q == p) pair[2] = pair[1];
          }
          for (std::size_t a = 0; a < 2; ++a)
            for (std::size_t c = 0; c < 2; ++c) {
              const std::size_t r = 2 * static_cast<std::size_t>(p) + a;
              const std::size_t col_index = 2 * static_cast<std::size_t>(q) + c;
              const double value = pair[2 * a + c];
              W[r * dim + col_index] = W[col_index * dim + r] = value;
              largest = std::max(largest, std::abs(value));
            }
        }
      }
      std::copy_n(W, dim * dim, L);
      for (std::size_t r = 0; r < dim; ++r)
        L[r * dim + r] += kBlockRegularisation * largest;
      m.friction_block_factored[static_cast<std::size_t>(n)] =
          largest > 0 && factor_block(L, static_cast<int>(dim));
    }
    n += std::max(1, k);
  }
}

double sweep_contact_friction(Multibody::Impl& m, SimTK::Vector& u, int group, double kick_s) {
  double* x = u.updContiguousScalarData();  // (a State's u is contiguous)
  double largest = 0;
  m.friction_sweep_slip = 0;
  const int first = m.friction_group_start[static_cast<std::size_t>(group)];
  const int last = m.friction_group_start[static_cast<std::size_t>(group) + 1];
  for (int n = first; n < last;) {
    const int k = std::max(1, m.friction_block_size[static_cast<std::size_t>(n)]);
    const double change =
        k > 1 ? solve_block(m, x, n, k, kick_s)
              : solve_point(m, x, m.friction_order[static_cast<std::size_t>(n)], kick_s);
    largest = std::max(largest, change);
    n += k;
  }
  return largest;
}

}  // namespace s2sim::model
