/// `solenoid` (simtwo-format.md §4.11): a ferromagnetic detector that is also an actuator.
/// It runs every tick in the actuate stage (its force acts during the coming tick, as in
/// SimTwo where it acts during the next step) and publishes its measurement at its period.
#include "kinds.hpp"

namespace s2sim::sensors {

void Solenoid::configure(ConfigureContext& ctx) {
  s_.read(ctx);
  const SolenoidForce& force = s_.spec.simtwo.solenoid_force;
  if (!(force.fmax_N >= 0))
    fail(ctx.params(), "force", "fmax", "must be >= 0 N, got " + num(force.fmax_N));
  if (!(force.k2 >= 0)) fail(ctx.params(), "force", "k2", "must be >= 0, got " + num(force.k2));
  ctx.set_schedule(Stage::actuate, ctx.tick_s());
  vin_ = ctx.declare_input("vin", "1", 0.0);
  value_ = ctx.declare_signal("value", "1");
  force_ = ctx.declare_signal("force", "N");
}

void Solenoid::update(StepContext& ctx) {
  const Pose w = s_.world_pose(ctx);
  const Vec3 dir = w.rotation.column(0);
  const RayHit h = ctx.cast_ray(w.position, dir, s_.spec.beam.length_m, s_.ignore);
  const bool ferro = h.hit && (h.material & material_ferromagnetic);
  const double vin = ctx.input(vin_);
  double f = 0;
  if (ferro && vin > 0) {
    const double d = h.distance_m > 0 ? h.distance_m : 0;
    const double k = 1 + s_.spec.simtwo.solenoid_force.k2 * d;
    f = 0.5 * vin * s_.spec.simtwo.solenoid_force.fmax_N / (k * k);
    // Toward the sensor on the hit body; the reaction on the sensor's body.
    if (h.body.index > 0) ctx.apply_force(h.body, dir * -f, h.point_m);
    if (s_.body.index > 0) ctx.apply_force(s_.body, dir * f, w.position);
  }
  ctx.publish(force_, f);
  if (s_.measures_now(ctx)) {
    RandomStream r = ctx.random();
    ctx.publish(value_, s_.noise.apply(r, ferro ? 1.0 : 0.0));
  }
}

}  // namespace s2sim::sensors
