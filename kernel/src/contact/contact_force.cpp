#include "contact/contact_force.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace s2sim::contact {
namespace {

double geometric_mean(double a, double b) {
  return std::sqrt(std::max(0.0, a) * std::max(0.0, b));
}

/// The first friction direction of an anisotropic wheel (spec §4.3), in the tangent plane.
Vec3 first_direction(Anisotropy kind, const Vec3& n, const Vec3& axis) {
  switch (kind) {
    case Anisotropy::omni:
      return cross(n, axis);
    case Anisotropy::mecanum_left:
      return (axis + cross(n, axis)) * (1 / std::sqrt(2.0));
    case Anisotropy::mecanum_right:
      return (axis - cross(n, axis)) * (1 / std::sqrt(2.0));
    case Anisotropy::none:
      break;
  }
  return {};
}

/// The linear Hunt–Crossley impact in units of the contact: x = depth·omega/v_in, tau =
/// omega·t, beta = alpha·v_in, damping capped at critical (beta·x <= 2), never pulling:
///   x'' = −max(0, x + min(beta·x, 2)·x'),  x(0) = 0, x'(0) = 1.
/// Returns the restitution −x'(end) (RK4, fine steps).
double restitution_of(double beta) {
  double x = 0, v = 1;
  auto accel = [beta](double x_, double v_) {
    return -std::max(0.0, x_ + std::min(beta * x_, 2.0) * v_);
  };
  const double dt = 2e-3;
  for (int i = 0; i < 100000; ++i) {
    const double k1x = v, k1v = accel(x, v);
    const double k2x = v + 0.5 * dt * k1v, k2v = accel(x + 0.5 * dt * k1x, v + 0.5 * dt * k1v);
    const double k3x = v + 0.5 * dt * k2v, k3v = accel(x + 0.5 * dt * k2x, v + 0.5 * dt * k2v);
    const double k4x = v + dt * k3v, k4v = accel(x + dt * k3x, v + dt * k3v);
    x += dt / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (x <= 0) break;
    if (v <= 0 && x < 1e-9) return 0;  // came to rest inside: plastic
  }
  return std::max(0.0, -v);
}

/// A jointed body's overlap the spring leaves alone relaxes to zero as a critically damped
/// second-order system, d'' = −2·d'/T − d/T², from rest: the body rises out of it with its
/// contact force its weight plus m·a, a = d₀/T² at the start (2 m/s² for 5 mm), its speed
/// within the scene's largest recovery speed. A spring that pushed at once would throw it at
/// about ω·d₀, and a rest depth that moved at a speed from the start would still jerk it.
void relax_overlap(PointState& state, const ForceLawSettings& law, double h) {
  if (!(state.rest_depth_m > 0)) return;
  const double T = law.jointed_recovery_time_s;
  state.rest_rate_m_s += h * (-2 * state.rest_rate_m_s / T - state.rest_depth_m / (T * T));
  state.rest_rate_m_s = std::max(state.rest_rate_m_s, -law.max_recovery_speed_m_s);
  state.rest_depth_m += h * state.rest_rate_m_s;
  if (!(state.rest_depth_m > 0)) state.rest_depth_m = state.rest_rate_m_s = 0;
}

}  // namespace

// From a table of restitution_of over log-spaced beta, built once.
double restitution_beta(double e) {
  constexpr int kCount = 121;  // beta from 1e-3 to 1e3
  static const auto table = [] {
    struct Table {
      double beta[kCount], e[kCount];
    } t{};
    for (int i = 0; i < kCount; ++i) {
      t.beta[i] = std::pow(10.0, -3.0 + 6.0 * i / (kCount - 1));
      t.e[i] = restitution_of(t.beta[i]);
    }
    return t;
  }();
  if (e >= table.e[0]) return table.beta[0] * (1 - e) / (1 - table.e[0] + 1e-300);
  for (int i = 1; i < kCount; ++i)
    if (e >= table.e[i]) {
      const double f = (table.e[i - 1] - e) / (table.e[i - 1] - table.e[i]);
      return std::exp(std::log(table.beta[i - 1]) +
                      f * (std::log(table.beta[i]) - std::log(table.beta[i - 1])));
    }
  return INFINITY;
}

PairMaterial combine_surfaces(const Surface& a, double beta_a, const Surface* b, double beta_b,
                              double default_mu) {
  // Symmetric rule: a surface without an explicit mu takes no part; two explicit surfaces
  // combine by geometric mean; none at all gives the project's default friction.
  const Surface* sa = a.has_mu ? &a : nullptr;
  const Surface* sb = b && b->has_mu ? b : nullptr;
  auto second = [](const Surface& s) { return s.mu2 >= 0 ? s.mu2 : s.mu; };
  PairMaterial m;
  if (sa && sb) {
    m.mu1 = geometric_mean(sa->mu, sb->mu);
    m.mu2 = geometric_mean(second(*sa), second(*sb));
  } else if (sa || sb) {
    const Surface& s = sa ? *sa : *sb;
    m.mu1 = s.mu;
    m.mu2 = second(s);
  } else {
    m.mu1 = m.mu2 = default_mu;
  }
  if (a.anisotropy != Anisotropy::none) {
    m.anisotropic = true;
    m.anisotropy = a.anisotropy;
    m.anisotropy_on_a = true;
  } else if (b && b->anisotropy != Anisotropy::none) {
    m.anisotropic = true;
    m.anisotropy = b->anisotropy;
    m.anisotropy_on_a = false;
  } else {
    m.mu2 = m.mu1;  // plain solids are isotropic whatever their mu2 (spec §4.3)
  }
  m.restitution = std::max(a.restitution, b ? b->restitution : 0.0);
  m.restitution_beta = b && b->restitution > a.restitution ? beta_b : beta_a;
  m.restitution_threshold_m_s =
      std::max(a.restitution_threshold_m_s, b ? b->restitution_threshold_m_s : 0.0);
  m.softness = std::max(a.softness, b ? b->softness : 0.0);
  return m;
}

double held_recovery_speed(const ForceLawSettings& law, double depth_m) {
  const double beyond_hold = depth_m - law.hold_depth_m;
  if (!(beyond_hold > 0)) return 0;
  const double walking = std::min(law.min_recovery_speed_m_s,
                                  (beyond_hold - law.hold_depth_m) / (0.1 * law.recovery_time_s));
  return std::min(law.max_recovery_speed_m_s, std::max(walking, beyond_hold / law.recovery_time_s));
}

bool pyramid_directions(const PairMaterial& material, const Vec3& n, const Vec3& friction_axis,
                        Vec3& d1, Vec3& d2) {
  if (!material.anisotropic) return false;
  d1 = first_direction(material.anisotropy, n, friction_axis);
  d1 -= dot(d1, n) * n;
  if (!(norm(d1) > 1e-9)) return false;
  d1 = d1 / norm(d1);
  d2 = cross(n, d1);
  return true;
}

Vec3 contact_force(const ContactPoint& point, const PairMaterial& material,
                   const PointKinematics& kin, const ForceLawSettings& law, bool new_point,
                   PointState& state, PointRole& role, double* friction_load_N) {
  if (friction_load_N) *friction_load_N = -1;
  const Vec3& n = point.normal;
  const double m = kin.mass_kg;
  const double h = kin.step_s;
  const double approach = -dot(kin.relative_velocity_m_s, n);  // > 0 when closing
  // The restitution an impact at approach speed v_in rebounds with.
  auto restitution_at = [&material](double v_in) {
    return material.restitution > 0 && v_in >= material.restitution_threshold_m_s
               ? material.restitution
               : 0.0;
  };
  role = PointRole::contact;
  double normal = 0;
  bool impact_completed = false;
  if (state.impact_pending && !new_point) {
    // Second half of an impact caught before touching: the normal speed becomes e·v_in away
    // from the surface (0 when plastic), v_in the approach speed before the stop.
    state.impact_pending = false;
    const double v_in = state.approach_speed_m_s;
    normal = std::max(0.0, m * (restitution_at(v_in) * v_in + approach) / h);
    impact_completed = true;
    role = PointRole::impact;
  } else if (point.depth_m > 0 && approach >= law.min_speculative_speed_m_s) {
    // Touching and closing fast: a point the margins did not catch before it touched (a
    // tumbling box's face, a pair with a cylinder). Stopped now as a caught point would have
    // been, a step late; the rebound at e·v_in is due next step.
    state.approach_speed_m_s = approach;
    state.impact_pending = true;
    normal = m * approach / h;
    impact_completed = true;
    role = PointRole::impact;
  } else if (point.depth_m <= 0) {
    // Speculative: a point short of the surface by `gap`. If it cannot reach it within the
    // step, or is too slow to matter (min_speculative_speed_m_s), it takes no part. Else it is
    // stopped where it would touch: its normal speed after the step's kick is (gap + landing)/h,
    // which brings it just past the surface by the step's end (so the next step finds it
    // touching, whatever its margin then, for the impact's second half).
    const double gap = -point.depth_m;
    if (approach * h <= gap || approach < law.min_speculative_speed_m_s) {
      role = PointRole::apart;
      return {};
    }
    state = PointState{};
    state.approach_speed_m_s = approach;
    state.impact_pending = true;
    role = PointRole::speculative;
    return n * (m * (approach - (gap + law.speculative_landing_depth_m) / h) / h);
  }
  // Stiffness: the surface's own, k_s = ERP / (CFM · reference step) (ODE's softness read at
  // the project's ERP), but never stiffer than the step can integrate:
  // omega_c = frequency_ratio / h.
  const double omega_max = law.frequency_ratio / h;
  const double k_surface = law.erp / (std::max(material.softness, 1e-12) * law.reference_step_s);
  const double k = std::min(k_surface, m * omega_max * omega_max);

  // Normal: Hunt–Crossley, F = k·d·(1 + alpha·v) with the damping capped at critical, alpha
  // from the restitution e and the approach speed v_in so that this very law rebounds at e·v_in
  // (restitution_beta); e = 0, or an approach slower than the threshold, is plastic. Never pulls.
  // Overlap recovery of jointed bodies (docs/models/contact.md): a point born or gone deeper
  // since the last step by a hold depth more than its closing explains was started, placed or
  // grown inside; the spring pushes against what is deeper than that overlap, which relaxes
  // (relax_overlap). Jointless bodies' overlaps are held instead (below, stop_graph.hpp).
  relax_overlap(state, law, h);
  const double moved_m = std::max(approach, 0.0) * h;
  const double deeper_m = point.depth_m - (new_point ? 0.0 : state.last_depth_m);
  if (!kin.bounded_recovery && deeper_m > law.hold_depth_m + 2 * moved_m) {
    state.rest_depth_m += deeper_m - moved_m;
    state.rest_rate_m_s = 0;
  }
  state.last_depth_m = point.depth_m;
  if (!impact_completed) {
    const double depth = point.depth_m - state.rest_depth_m;
    const double critical = 2 * std::sqrt(k * m);
    if (new_point) state.approach_speed_m_s = std::max(approach, 1e-3);
    double damping = critical;
    const double e = material.restitution;
    if (e > 0 && state.approach_speed_m_s >= material.restitution_threshold_m_s) {
      const double alpha = material.restitution_beta / state.approach_speed_m_s;
      damping = std::min(critical, k * alpha * std::max(depth, 0.0));
    }
    // The dampers of the points on one body act on its speed together: each takes at most its
    // share of it per step, or a box on four corners would overshoot every step and ring.
    const double damping_bound = m / (h * kin.points_sharing);
    damping = std::min(damping, damping_bound);
    normal = std::max(0.0, k * depth + damping * approach);
    // Overlap recovery (docs/models/contact.md): between jointless bodies (or one and a
    // static shape) a point deeper than the hold depth is held (stop_graph.hpp), and its row
    // carries the load and separates it at held_recovery_speed(). The spring, which would
    // throw the bodies apart at about omega·depth, is bounded by the point's share of the
    // critical damper times the speed still missing to that one (or to the rebound the
    // restitution asks for), from a quarter of a hold depth beyond it: the whole spring
    // carries a stack's loads just past the hold depth. A closing point (a landing) keeps the
    // whole law until it turns.
    if (kin.bounded_recovery && approach <= 0 && point.depth_m > 1.25 * law.hold_depth_m) {
      const double rebound = restitution_at(state.approach_speed_m_s) * state.approach_speed_m_s;
      const double target = std::max(rebound, held_recovery_speed(law, point.depth_m));
      normal =
          std::min(normal, std::max(0.0, std::min(critical, damping_bound) * (target + approach)));
    }
  }

  // Friction bounds the whole normal load: the spring's and what a hold carried last step.
  const double normal_spring = normal;
  normal += state.held_force_N;
  state.held_force_N = 0;

  if (friction_load_N && role == PointRole::contact) {  // solved with the axes
    *friction_load_N = normal;
    state.bristle_m = Vec3{};
    return n * normal_spring;
  }

  // Tangential: slip velocity in the tangent plane, bristle deflection carried along it.
  const Vec3 v_t = kin.relative_velocity_m_s - dot(kin.relative_velocity_m_s, n) * n;
  Vec3 bristle = new_point ? Vec3{} : state.bristle_m - dot(state.bristle_m, n) * n;
  bristle += v_t * h;
  // The bristle may not ring faster than the normal spring, whatever the tangential mass (a
  // wheel's rim is light across the normal).
  const double k_t = law.bristle_ratio * std::min(k, kin.tangent_mass_kg * omega_max * omega_max);
  // Regularised Coulomb: viscous slope mu·N/v_tr, capped where explicit stepping stays stable
  // and solved implicitly for the point's share of its body's mass, c/(1 + c·h·n/m) with n the
  // points sharing the body: the slope is steep, and the points of a box's face brake the same
  // rocking together (each solved for itself alone, four of them overshoot: the box rocks at
  // the friction limit every other step and walks).
  const double m_t = kin.tangent_mass_kg;
  const double share_h = h * kin.points_sharing;
  auto slope = [&](double mu) {
    const double c = std::min(mu * normal / law.transition_speed_m_s, 2 * std::sqrt(k_t * m_t));
    return c / (1 + c * share_h / m_t);
  };
  // One direction of friction: the bristle and the slope, within ±mu·N; a direction that
  // slides keeps its bristle at exactly the force it carries.
  auto along = [&](const Vec3& d, double mu) {
    const double s_d = dot(bristle, d), v_d = dot(v_t, d), limit = mu * normal;
    const double f = std::clamp(-k_t * s_d - slope(mu) * v_d, -limit, limit);
    const double s_new = k_t > 0 && std::abs(f) >= limit ? -f / k_t : s_d;
    return std::pair<double, double>{f, s_new};
  };
  Vec3 friction;
  Vec3 d1, d2;
  if (pyramid_directions(material, n, kin.friction_axis, d1, d2)) {
    // Anisotropic wheels: ODE's friction pyramid, mu along d1 and mu2 along d2, each on its
    // own (a circle or an ellipse would let the free roller direction steal the grip).
    const auto [f1, s1] = along(d1, material.mu1);
    const auto [f2, s2] = along(d2, material.mu2);
    friction = f1 * d1 + f2 * d2;
    bristle = s1 * d1 + s2 * d2;
  } else {
    // Isotropic: the Coulomb circle, the force scaled onto it when it slides.
    friction = -(k_t * bristle) - slope(material.mu1) * v_t;
    const double f = norm(friction), limit = material.mu1 * normal;
    if (f > limit) {
      friction = f > 0 ? friction * (limit / f) : Vec3{};
      bristle = k_t > 0 ? friction * (-1 / k_t) : Vec3{};
    }
  }
  state.bristle_m = bristle;
  return n * normal_spring + friction;
}

}  // namespace s2sim::contact
