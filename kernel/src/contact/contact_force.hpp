#pragma once
/// \file
/// The contact force law (docs/models/contact.md): a compliant Hunt–Crossley normal force and
/// Coulomb friction regularised by a transition velocity, with an elastic bristle that gives
/// true stiction; anisotropic coefficients for omni and mecanum wheels.

#include "collision/contact_point.hpp"

#include <cstdint>

namespace s2sim::contact {

using collision::Anisotropy;
using collision::ContactPoint;
using collision::Surface;

/// Combined parameters of two surfaces (symmetric in a and b).
struct PairMaterial {
  double mu1 = 0;  ///< along the first friction direction (every direction when isotropic)
  double mu2 = 0;  ///< across it
  bool anisotropic = false;
  Anisotropy anisotropy = Anisotropy::none;
  bool anisotropy_on_a = true;  ///< whose local Z axis orients the friction directions
  double restitution = 0;
  double restitution_threshold_m_s = 0;
  double restitution_beta = 0;  ///< that of the more elastic surface
  double softness = 1e-5;
};

/// beta = alpha·v_in with which the contact law rebounds at restitution e in (0, 1]; infinity
/// where even critical damping cannot absorb enough. Computed once per surface at load.
double restitution_beta(double e);

/// `b` is null for the ground and the walls, which have no surface of their own; `beta_a`,
/// `beta_b` are the surfaces' restitution_beta.
PairMaterial combine_surfaces(const Surface& a, double beta_a, const Surface* b, double beta_b,
                              double default_mu);

/// Numbers of the force law shared by every contact of the run.
struct ForceLawSettings {
  /// Largest speculative margin (docs/models/contact.md, "Speculative contact"): a shape's
  /// points are looked for this far at most before they touch.
  double max_speculative_margin_m = 0.05;
  /// Slower points are left to the force law, which lands them less than about 2.2·v·h deep
  /// (1.1 mm at 1 ms): speculative contact applies to points closing at least this fast, so
  /// that slow scenes (robots set down on the floor, resting stacks) keep their numbers.
  double min_speculative_speed_m_s = 0.5;
  /// How far past the surface a stopped point is brought: the next step must find it touching
  /// (a point slower than min_speculative_speed_m_s has no margin to be found within).
  double speculative_landing_depth_m = 1e-5;
  /// A resting contact between jointless bodies (or one and a static shape) deeper than this
  /// closes no further: the spring carries what it can, an impulse the rest (stop_graph.hpp).
  double hold_depth_m = 0.001;
  /// Overlap recovery (docs/models/contact.md): held points leave a deep overlap at
  /// held_recovery_speed() (`<s2sim><contact recovery_speed>` sets the largest).
  double max_recovery_speed_m_s = 0.3;
  double min_recovery_speed_m_s = 0.1;
  double recovery_time_s = 0.1;
  /// A jointed body's point born deeper than its motion explains (started or placed inside):
  /// the spring leaves that overlap alone and the overlap relaxes to zero with this time
  /// constant, critically damped (contact_force.cpp, relax_overlap).
  double jointed_recovery_time_s = 0.05;
  double frequency_ratio = 0.3;        ///< omega_c·h of the stiffest contact
  double transition_speed_m_s = 0.05;  ///< Coulomb regularisation
  double reference_step_s = 1e-3;      ///< turns ODE's softness (CFM) into a stiffness
  double erp = 0.4;                    ///< the project's ERP, k_s = erp / (softness · reference)
  double bristle_ratio = 0.5;          ///< tangential / normal stiffness
  /// A jointed body's point on a static surface whose tangential effective mass is below this
  /// fraction of its normal one (a tyre's rim, light along its roll) has its friction solved
  /// with the axes (model/substep_forces.hpp); where the two are comparable (a foot, a box's
  /// corner) the bristle is about as stiff as the normal spring and this law holds the point.
  double solved_friction_mass_ratio = 0.5;
};

/// What persists for one contact point between steps.
struct PointState {
  Vec3 bristle_m;                 ///< elastic tangential deflection, world frame
  double approach_speed_m_s = 0;  ///< normal speed when the point first touched
  Vec3 local_point_m;             ///< where it touched, in shape a's frame (matching)
  /// Caught before touching (a speculative stop) last step: the impact's second half, the
  /// rebound at e·approach_speed_m_s, is due this step.
  bool impact_pending = false;
  /// The normal force a hold or a stop's reach added to the point last step (stop_graph.hpp):
  /// part of the load the friction cone bounds, besides the spring's.
  double held_force_N = 0;
  /// A jointed body's overlap the spring does not push against (born or gone deeper than the
  /// point's motion explains), relaxing to zero, and its rate (m/s, never positive).
  double rest_depth_m = 0;
  double rest_rate_m_s = 0;
  double last_depth_m = 0;  ///< the point's depth last step
};

/// What a point found by the narrow phase is this step (speculative contact).
enum class PointRole : std::uint8_t {
  apart,        ///< not touching, and its closing speed cannot cross the gap: no force, forgotten
  speculative,  ///< not touching but would cross within the step: stopped at the surface, a
                ///< normal force only, not reported as a contact
  impact,       ///< completing an impact caught the step before: a contact whose normal
                ///< force is a velocity change (solved with the pair's other stops)
  contact,      ///< touching
};

/// Inputs of the force law for one point.
struct PointKinematics {
  Vec3 relative_velocity_m_s;  ///< of a's material point relative to b's (belt motion included)
  Vec3 friction_axis;          ///< anisotropic surfaces: the axis orienting d1 (a's or b's Z)
  double mass_kg = 1;          ///< the pair's effective mass at the point, along the normal
  double tangent_mass_kg = 1;  ///< the same across the normal (the smaller of two directions)
  double step_s = 1e-3;        ///< physics substep
  /// Touching points on the more crowded of the two bodies (at least 1): the dampers of points
  /// on one body act together, each may take only its share of the body's speed per step.
  int points_sharing = 1;
  /// Overlap recovery bounds the normal force (both bodies jointless, or one static: their
  /// held points make up a resting load the bound leaves short, stop_graph.hpp).
  bool bounded_recovery = false;
};

/// The speed at which a held point (stop_graph.hpp) `depth_m` deep separates: 0 at the hold
/// depth d_h, (d − d_h)/T_r beyond it up to v_max, and at least v_min from 2·d_h on, tapering
/// to (d − 2·d_h)/(T_r/10) below: a load resting on a light point just past the hold depth
/// rises by micrometres, a deep overlap leaves at a walking pace, never faster than v_max.
double held_recovery_speed(const ForceLawSettings& law, double depth_m);

/// The friction directions of an anisotropic pair (omni and mecanum wheels: ODE's pyramid, μ1
/// along d1, μ2 along d2 = n × d1), from the pair's orienting axis; false when the pair is
/// isotropic or its axis lies along the normal (the Coulomb circle then).
bool pyramid_directions(const PairMaterial& material, const Vec3& n, const Vec3& friction_axis,
                        Vec3& d1, Vec3& d2);

/// Force on shape a at the point (world frame). Updates `state` and says what the point is:
/// a point with depth <= 0 (within the speculative margin) gets the force that brings it to the
/// surface by the step's end if it would cross it, else none (`apart`); the step after such a
/// stop gives back e times the approach speed it had before the stop.
/// With `friction_load_N`, a touching point's friction is left to the caller (the multibody
/// solves it with the axes, model/substep_forces.hpp): the force is the normal one alone, the
/// bristle is cleared, and the normal load that bounds the friction is written there (-1 for
/// a point that is not `contact`, whose friction, if any, is in the force).
Vec3 contact_force(const ContactPoint& point, const PairMaterial& material,
                   const PointKinematics& kin, const ForceLawSettings& law, bool new_point,
                   PointState& state, PointRole& role, double* friction_load_N = nullptr);

}  // namespace s2sim::contact
