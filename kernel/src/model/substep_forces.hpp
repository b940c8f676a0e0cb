#pragma once
/// \file
/// Loads that depend on the state inside a tick (contact): the multibody model calls them at
/// every substep with the current poses and velocities, then applies what they return.

#include <s2sim/math.hpp>

#include <cstdint>
#include <vector>

namespace s2sim::model {

/// A contact point on a jointed body whose friction the multibody solves with its axes at the
/// kick's end (implicit, docs/models/contact.md, "Friction on jointed bodies"): the point's
/// slip across the normal is brought to zero while the friction stays within its bounds, and
/// where it cannot, the point slides at the bound. The other side is a static surface.
struct FrictionPoint {
  std::int32_t body = 0;       ///< kernel body (one whose multibody solves_contact_friction())
  Vec3 point_m;                ///< world
  Vec3 direction[2];           ///< unit tangents, orthogonal to each other and to the normal
  double limit_N[2] = {0, 0};  ///< μ·N along each (isotropic: the circle's radius, limit_N[0])
  bool isotropic = true;       ///< the Coulomb circle; else each direction on its own (a pyramid)
  Vec3 surface_velocity_m_s;   ///< of the static side's material at the point (a belt): the slip
                               ///< is measured against it
  std::int32_t report = -1;    ///< the writer's own index of the point (its contact list)
  std::int32_t scene_index = -1;  ///< multibody islands: the entry of the scene-wide list
  Vec3 force_N;  ///< out: the friction the solve applied to the body over the kick (world)
};

/// Room for a substep's friction points, written by the contact, solved by the multibody.
struct FrictionPoints {
  FrictionPoint* points = nullptr;
  std::int32_t count = 0;
  std::int32_t capacity = 0;
};

class SubstepForces {
 public:
  virtual ~SubstepForces() = default;
  /// `poses`, `twists` per kernel body (0 = world); writes `wrenches` (about each body origin,
  /// world frame) for every body, zero where nothing acts. With `friction`, the points whose
  /// friction the multibody solves go there instead of into the wrenches. Must not allocate.
  virtual void compute(const Pose* poses, const Twist* twists, double step_s, Wrench* wrenches,
                       FrictionPoints* friction = nullptr) = 0;
  /// After the substep computed whole by compute() was solved (its friction points' forces
  /// known), on the calling thread.
  virtual void end_substep() {}

  // --- Part by part (MultibodyIslands): each part computes the loads on its own bodies on its
  // own thread, where they are used, when no load couples two parts. The results must be those
  // of compute() to the bit. Forces that cannot be split keep these defaults.

  /// Deals the kernel bodies into `parts` parts (`part_of_body[0]`, the world's, is ignored);
  /// false: these forces cannot be computed part by part.
  virtual bool split(const std::vector<int>& part_of_body, int parts) {
    (void)part_of_body;
    (void)parts;
    return false;
  }
  /// Before a substep, on the calling thread: true if it can be computed part by part (then
  /// compute_part() for each part, and end_parts()); false: compute() instead. `placed`: every
  /// part's place_part() ran with the substep's poses; if not, `poses`/`twists` (all bodies)
  /// are used.
  virtual bool begin_parts(bool placed, const Pose* poses, const Twist* twists, double step_s) {
    (void)placed;
    (void)poses;
    (void)twists;
    (void)step_s;
    return false;
  }
  /// The loads on part `part`'s bodies into `wrenches` (per kernel body; only the part's own
  /// bodies are written and read), from `poses`/`twists` (only the part's bodies are read).
  virtual void compute_part(int part, const Pose* poses, const Twist* twists, double step_s,
                            Wrench* wrenches, FrictionPoints* friction = nullptr) {
    (void)friction;
    (void)part;
    (void)poses;
    (void)twists;
    (void)step_s;
    (void)wrenches;
  }
  /// After every compute_part() of a substep, on the calling thread.
  virtual void end_parts() {}
  /// After a part's substep, on its thread: takes the forces its friction points were solved
  /// with, and prepares the next substep from the part's new poses (read as compute_part reads
  /// them).
  virtual void place_part(int part, const Pose* poses, const Twist* twists, double step_s) {
    (void)part;
    (void)poses;
    (void)twists;
    (void)step_s;
  }

  // --- Running ahead (sim/run_ahead.cpp): the parts step several ticks without the calling
  // thread between their substeps, which is exact while no load can couple two parts.

  /// On the calling thread, instead of begin_parts(), the parts placed at the current poses:
  /// gives each part a fence, a region of its own apart from the others', and starts
  /// substeps computed part by part (compute_part()); false (nothing changed): it cannot.
  virtual bool fence_parts() { return false; }
  /// After place_part(), on the part's thread: whether no load can couple the part with
  /// another in the next substep as long as the others are inside their fences too.
  virtual bool part_inside_fence(int part) const {
    (void)part;
    return false;
  }
  /// On the calling thread after `substeps` substeps run ahead: end_parts() for all of them.
  virtual void end_parts_ahead(std::int64_t substeps) { (void)substeps; }
};

}  // namespace s2sim::model
