// Coulomb friction on the joint axes: a velocity-level brake (tree axes) or a plain force on
// axes that clearly slide (docs/models/multibody.md).
#include "model/multibody_impl.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::model {

/// Whether the M^-1 columns computed last are those of the axes braked now, at a configuration
/// within 1e-7 (rad or m) of the current one in every coordinate.
namespace {

bool columns_still_valid(const Multibody::Impl& m, const SimTK::State& s) {
  if (m.columns_for != m.braked) return false;
  const SimTK::Vector& q = s.getQ();
  const double* now = q.hasContiguousData() ? q.getContiguousScalarData() : nullptr;
  if (!now) return false;
  for (int i = 0; i < q.size(); ++i)
    if (std::abs(now[i] - m.columns_q[static_cast<std::size_t>(i)]) > 1e-7) return false;
  return true;
}

}  // namespace

/// Which braked axes slide so fast that friction cannot stop them within a step (ten times
/// the speed change the bound can make): they get Coulomb's law as a plain force and skip the
/// impulse solve (and its M^-1 products). (M^-1)_aa is remembered from the last solve.
void classify_sliding(Multibody::Impl& m, const SimTK::State& s, double h) {
  const SimTK::Vector& u = s.getU();
  for (std::size_t a = 0; a < m.axis_friction.size(); ++a) {
    m.sliding[a] = 0;
    if (!(m.axis_friction[a] > 0.0) || m.axes[a].loop || !(m.axis_mobility[a] > 0)) continue;
    const double threshold = 10 * m.axis_friction[a] * h * m.axis_mobility[a];
    m.sliding[a] = std::abs(u[m.axis_u[a]]) > threshold;
  }
}

/// Coulomb friction on tree axes as a velocity-level brake (ODE's joint motor with zero target
/// speed): after the kick, find impulses p_k, |p_k| <= F_k·kick, that stop the braked axes where
/// the bounds allow, coupled through M^-1 (projected Gauss-Seidel on the small Delassus
/// matrix W = M^-1 restricted to the braked axes). Loop axes get a regularised force instead.
void brake_axes(Multibody::Impl& m, SimTK::State& s, double kick_s) {
  m.braked.clear();
  for (std::size_t a = 0; a < m.axis_friction.size(); ++a)
    if (m.axis_friction[a] > 0.0 && !m.axes[a].loop && !m.sliding[a])
      m.braked.push_back(static_cast<int>(a));
  if (m.braked.empty()) return;
  const std::size_t n = m.braked.size();
  auto u_index = [&](int a) { return m.axis_u[a]; };
  if (!columns_still_valid(m, s)) {
    for (std::size_t k = 0; k < n; ++k) {
      m.unit_force = 0.0;
      m.unit_force[u_index(m.braked[k])] = 1.0;
      m.matter.multiplyByMInv(s, m.unit_force, m.minv_column[k]);
    }
    m.columns_for = m.braked;
    const SimTK::Vector& q = s.getQ();
    for (int i = 0; i < q.size(); ++i)
      m.columns_q[static_cast<std::size_t>(i)] = q[i];
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < n; ++k)
      m.delassus[i * n + k] = m.minv_column[k][u_index(m.braked[i])];
    m.axis_mobility[m.braked[i]] = m.delassus[i * n + i];
  }
  SimTK::Vector& u = s.updU();
  for (std::size_t k = 0; k < n; ++k)
    m.impulse[k] = 0.0;
  // Generalized-coordinate impulses; sign conventions cancel (W is symmetric in u space).
  for (int iteration = 0; iteration < (n == 1 ? 1 : 8); ++iteration) {
    for (std::size_t i = 0; i < n; ++i) {
      const int a = m.braked[i];
      const double v = u[u_index(a)];
      const double w = m.delassus[i * n + i];
      if (!(w > 0)) continue;
      const double bound = m.axis_friction[a] * kick_s;
      const double p_new = std::clamp(m.impulse[i] - v / w, -bound, bound);
      const double dp = p_new - m.impulse[i];
      if (dp == 0.0) continue;
      m.impulse[i] = p_new;
      add_scaled(u, dp, m.minv_column[i]);
    }
  }
}

}  // namespace s2sim::model
