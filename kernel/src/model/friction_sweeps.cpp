// The sweeps of contact friction on jointed bodies (contact_friction.cpp says the method): a
// point solved for itself (its two tangents at once, sliding on the Coulomb circle by the
// secular equation), a body's points solved as one block while they stick, and the sweep over
// a group of them.
#include "common/cholesky.hpp"
#include "model/dynamics.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::model {
namespace {

/// Point i's slip along its two tangents at the speeds x, against its surface.
void point_slip(const Multibody::Impl& m, const double* x, int i, double* v) {
  const auto stride = static_cast<std::size_t>(m.friction_stride);
  const FrictionPoint& p = m.friction.points[i];
  const auto b = static_cast<std::size_t>(p.body);
  const int begin = m.friction_u_begin[b], span = m.friction_u_end[b] - begin;
  const double* g0 = m.friction_g.data() + 2 * static_cast<std::size_t>(i) * stride;
  const double* g1 = g0 + stride;
  v[0] = -dot(p.surface_velocity_m_s, p.direction[0]);
  v[1] = -dot(p.surface_velocity_m_s, p.direction[1]);
  const double* xu = x + begin;
  for (int e = 0; e < span; ++e) {
    v[0] += g0[e] * xu[e];
    v[1] += g1[e] * xu[e];
  }
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

/// The block of `k` points at order positions [n, n + k) of one body solved at once when its
/// points all stick (the points of one body nearly repeat each other, a tyre's two tread
/// points, and Gauss–Seidel converges on them slowly); false, changing nothing, when one of
/// them would slide or the block's W cannot be factored. `change`: the largest slip change.
bool solve_block(Multibody::Impl& m, double* x, int n, int k, double kick_s, double& change) {
  const auto dim = static_cast<std::size_t>(2 * k);
  const double* L = m.friction_block_w.data() + 32 * static_cast<std::size_t>(n);
  if (!m.friction_block_factored[static_cast<std::size_t>(n)]) return false;
  double* v = m.friction_block_rhs.data();
  const int* order = m.friction_order.data() + n;
  for (int q = 0; q < k; ++q)
    point_slip(m, x, order[q], v + 2 * q);
  // v₀ = v − W·λ: the slip without the block's impulses (W from the raw rows: W·λ is what the
  // impulses changed the slips by, read back as x moved).
  const double* W = m.friction_block_w.data() + 32 * static_cast<std::size_t>(n) + dim * dim;
  double* lambda = m.friction_block_rhs.data() + dim;
  for (int q = 0; q < k; ++q) {
    lambda[2 * q] = m.friction_impulse[2 * static_cast<std::size_t>(order[q])];
    lambda[2 * q + 1] = m.friction_impulse[2 * static_cast<std::size_t>(order[q]) + 1];
  }
  for (std::size_t r = 0; r < dim; ++r)
    for (std::size_t c = 0; c < dim; ++c)
      v[r] -= W[r * dim + c] * lambda[c];
  double* next = lambda + dim;
  common::cholesky_substitute(L, 2 * k, v, next);
  for (std::size_t r = 0; r < dim; ++r)
    next[r] = -next[r];
  for (int q = 0; q < k; ++q)
    if (!within_bounds(m, order[q], next[2 * q], next[2 * q + 1], kick_s)) return false;
  change = 0;
  for (std::size_t r = 0; r < dim; ++r)
    lambda[r] = next[r] - lambda[r];  // the changes
  for (std::size_t r = 0; r < dim; ++r) {
    double dv = 0;
    for (std::size_t c = 0; c < dim; ++c)
      dv += W[r * dim + c] * lambda[c];
    change = std::max(change, std::abs(dv));
  }
  for (int q = 0; q < k; ++q) {
    const auto i = static_cast<std::size_t>(order[q]);
    apply_impulse(m, x, order[q], lambda[2 * q], lambda[2 * q + 1]);
    m.friction_impulse[2 * i] = next[2 * q];
    m.friction_impulse[2 * i + 1] = next[2 * q + 1];
  }
  return true;
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
      double* L = m.friction_block_w.data() + 32 * static_cast<std::size_t>(n);
      double* W = L + dim * dim;
      const int* order = m.friction_order.data() + n;
      const auto body = static_cast<std::size_t>(m.friction.points[order[0]].body);
      const int span = m.friction_u_end[body] - m.friction_u_begin[body];
      double largest = 0;
      for (std::size_t r = 0; r < dim; ++r)
        for (std::size_t c = 0; c < dim; ++c) {
          const double* g =
              m.friction_g.data() + (2 * static_cast<std::size_t>(order[r / 2]) + r % 2) * stride;
          const double* col = m.friction_effective_column.data() +
                              (2 * static_cast<std::size_t>(order[c / 2]) + c % 2) * stride;
          double sum = 0;
          for (int e = 0; e < span; ++e)
            sum += g[e] * col[e];
          W[r * dim + c] = sum;
          largest = std::max(largest, std::abs(sum));
        }
      // Symmetric to rounding; a whisker on the diagonal for a block whose points repeat
      // each other exactly (W singular).
      for (std::size_t r = 0; r < dim; ++r)
        for (std::size_t c = 0; c < dim; ++c)
          L[r * dim + c] =
              0.5 * (W[r * dim + c] + W[c * dim + r]) + (r == c ? 1e-12 * largest : 0.0);
      m.friction_block_factored[static_cast<std::size_t>(n)] =
          largest > 0 && common::cholesky_factor(L, 2 * k);
    }
    n += std::max(1, k);
  }
}

double sweep_contact_friction(Multibody::Impl& m, SimTK::Vector& u, int group, double kick_s) {
  double* x = u.updContiguousScalarData();  // (a State's u is contiguous)
  double largest = 0;
  const int first = m.friction_group_start[static_cast<std::size_t>(group)];
  const int last = m.friction_group_start[static_cast<std::size_t>(group) + 1];
  for (int n = first; n < last;) {
    const int k = std::max(1, m.friction_block_size[static_cast<std::size_t>(n)]);
    double change = 0;
    if (k > 1 && solve_block(m, x, n, k, kick_s, change)) {
      largest = std::max(largest, change);
    } else {
      for (int q = n; q < n + k; ++q)
        largest = std::max(
            largest, solve_point(m, x, m.friction_order[static_cast<std::size_t>(q)], kick_s));
    }
    n += k;
  }
  return largest;
}

}  // namespace s2sim::model
