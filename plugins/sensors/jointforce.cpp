/// `jointforce`: the reaction load a joint transmits, as a six-axis force/torque cell in the
/// joint would read it (Gazebo's force_torque sensor, Webots' joint feedback): the force and
/// torque body2 exerts on body1 (ODE's body1/body2 of `<connect B1 B2>`), torque about the
/// joint anchor, expressed in body1's frame (the world frame when body1 is the world). Drive
/// and stop torques about the axis are included: the kernel's reactions carry every mobility
/// force. Each component through SimTwo's generic noise.
#include "kinds.hpp"

namespace s2sim::sensors {

void JointForce::configure(ConfigureContext& ctx) {
  ctx.declare_local();  // its own body (and joint): stepped in that body's part
  s_.read(ctx);
  s_.schedule(ctx);
  const Params& p = ctx.params();
  if (!p.has("joint.id"))
    fail(p, "joint", "id", "a jointforce sensor names its joint: <joint id='...'/>");
  const std::string name = p.text("joint.id");
  try {
    joint_ = ctx.joint(name);
  } catch (const Error& e) {
    fail(p, "joint", "id", e.message());
  }
  body1_ = ctx.joint_body(joint_, 1);
  static constexpr const char* force_names[3] = {"fx", "fy", "fz"};
  static constexpr const char* torque_names[3] = {"tx", "ty", "tz"};
  for (int i = 0; i < 3; ++i) {
    force_[i] = ctx.declare_signal(force_names[i], "N");
    torque_[i] = ctx.declare_signal(torque_names[i], "N*m");
  }
}

void JointForce::update(StepContext& ctx) {
  const Wrench& w = ctx.joint_reaction(joint_);
  const Mat3 to_body1 = ctx.body_pose(body1_).rotation.transposed();
  const Vec3 f = to_body1 * w.force_N;
  const Vec3 t = to_body1 * w.torque_Nm;
  RandomStream r = ctx.random();
  const double fv[3] = {f.x, f.y, f.z}, tv[3] = {t.x, t.y, t.z};
  for (int i = 0; i < 3; ++i)
    ctx.publish(force_[i], s_.noise.apply(r, fv[i]));
  for (int i = 0; i < 3; ++i)
    ctx.publish(torque_[i], s_.noise.apply(r, tv[i]));
}

}  // namespace s2sim::sensors
