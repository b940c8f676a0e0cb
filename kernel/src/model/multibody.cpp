// The only translation unit that sees Simbody (with its Custom force below).
#include "model/multibody.hpp"

#include "model/loose_bodies.hpp"

#include <Simbody.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <string>

namespace s2sim::model {
namespace {

SimTK::Vec3 to_simtk(const Vec3& v) {
  return {v.x, v.y, v.z};
}
Vec3 from_simtk(const SimTK::Vec3& v) {
  return {v[0], v[1], v[2]};
}

SimTK::Rotation to_simtk(const Mat3& m) {
  SimTK::Mat33 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r(i, j) = m.m[i][j];
  return SimTK::Rotation(r);  // re-orthonormalised: scene rotations carry rounding
}
Mat3 from_simtk(const SimTK::Rotation& r) {
  Mat3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      m.m[i][j] = r.asMat33()(i, j);
  return m;
}
SimTK::Transform to_simtk(const Pose& p) {
  return SimTK::Transform(to_simtk(p.rotation), to_simtk(p.position));
}

Error scene_error(const Location& where, const std::string& message) {
  return Error(ErrorKind::scene, where, message);
}

/// Two unit vectors perpendicular to `a` and to each other.
void perpendiculars(const SimTK::UnitVec3& a, SimTK::UnitVec3& p1, SimTK::UnitVec3& p2) {
  p1 = a.perp();
  p2 = SimTK::UnitVec3(SimTK::cross(a, p1));
}

/// How an axis's value is realised.
struct AxisImpl {
  // Tree joint: a mobilizer coordinate.
  SimTK::MobilizedBodyIndex mobod;
  int coordinate = 0;  // which q/u of the mobilizer
  double sign = 1;     // axis value = sign * q (ODE convention: body1 relative to body2)
  // Loop joint: measured from the two bodies.
  int body1 = -1, body2 = -1;     // kernel body indices (0 = world)
  SimTK::UnitVec3 axis_in_body2;  // rotation axis or slide direction, body2 frame
  SimTK::Rotation relative0;      // initial body1 orientation in body2 frame
  SimTK::Vec3 offset0_in_body2;   // initial body1 origin in body2 frame
  SimTK::Vec3 anchor_in_body1;    // slider force application point
};

}  // namespace

struct Multibody::Impl {
  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter{system};
  SimTK::GeneralForceSubsystem forces{system};
  // Gravity is applied by AppliedLoads, not by a Force::Gravity: Simbody's costs a tenth of
  // a small robot's step in cache bookkeeping for three multiplications per body.
  struct Weight {
    SimTK::MobilizedBodyIndex mobod;
    double mass_kg;
    SimTK::Vec3 com_m;  // body frame
  };
  std::vector<Weight> weights;
  std::vector<SimTK::MobilizedBodyIndex> mobod_of_body;  // kernel body -> mobod (invalid: loose)
  LooseBodies loose;               // bodies with no joint, integrated outside Simbody
  std::vector<Pose> initial_pose;  // kernel body -> pose at load
  std::vector<AxisInfo> axes;
  std::vector<AxisImpl> axis_impl;
  std::vector<std::string> warnings;
  /// A joint stop: a linear spring-damper on one axis outside [low, high], never pulling.
  struct Stop {
    int axis;
    double low, high;
    double stiffness = 0, damping = 0;
  };
  std::vector<Stop> stops;
  std::vector<Wrench> wrenches;
  std::vector<double> axis_forces;
  std::vector<double> axis_friction;
  // Velocity-level Coulomb friction on tree axes (preallocated: stepping must not allocate).
  std::vector<int> braked;                 // axes with a bound this substep
  std::vector<SimTK::Vector> minv_column;  // per braked axis: M^-1 * e_axis
  std::vector<double> delassus, impulse;   // braked x braked, braked
  std::vector<int> axis_u;                 // per tree axis, its index in u (-1: loop axis)
  std::vector<double> axis_mobility;       // per axis, (M^-1)_aa at its last solve (0: none)
  std::vector<char> sliding;               // per axis: Coulomb friction as a plain force
  // M^-1 columns of the braked axes are reused while the configuration stays put (a robot at
  // rest): M depends on q only.
  std::vector<int> columns_for;   // the braked axes the columns belong to
  std::vector<double> columns_q;  // the q they were computed at
  bool bodies_fresh = false;      // substep_poses/twists hold the current state
  SimTK::Vector unit_force;
  SubstepForces* substep_forces = nullptr;
  std::vector<Pose> substep_poses;
  std::vector<Twist> substep_twists;
  std::vector<Wrench> substep_wrenches;
  // Joint reactions (request_joint_reactions): per scene joint, the mobilizer realising it
  // (invalid for a loop-closing joint) and whether its child is body1.
  struct JointReaction {
    SimTK::MobilizedBodyIndex mobod;
    bool child_is_body1 = true;
    int body1 = 0;  // kernel index
  };
  std::vector<JointReaction> joint_reaction_source;
  std::vector<Wrench> joint_reactions;               // world frame, at the current state
  std::vector<Wrench> joint_reactions_in_body1;      // body1's frame, as computed
  SimTK::Vector_<SimTK::SpatialVec> reactions_at_M;  // preallocated, one per mobilized body
  bool reactions_wanted = false;
  SimTK::State initial_state;
  SimTK::State current;
  SimTK::Vector udot, qdot;  // preallocated: stepping must not allocate
  bool half_kick_pending = true;
  std::vector<int> quaternion_q;  // first q index of each quaternion (Free and Ball mobilizers)
  // q' = N(q)·u by hand when every mobilizer is Free or has q' = u: Simbody's multiplyByN goes
  // through its state digest for what is a copy plus one quaternion rate per free body.
  struct FreeCoordinates {
    int q, u;  // first indices: quaternion then position; angular then linear velocity
  };
  std::vector<FreeCoordinates> free_coordinates;
  std::vector<std::pair<int, int>> direct_coordinates;  // (q, u) of mobilizers with q' = u
  bool own_n = true;
  bool has_constraints = false;
  double tick_s = 1e-3;
  int substeps = 1;
  std::int64_t ticks = 0;

  const SimTK::State& state() const { return current; }
  const SimTK::MobilizedBody& mobod(int body) const {
    return matter.getMobilizedBody(mobod_of_body[body]);
  }
  SimTK::MobilizedBody& upd_mobod(int body) { return matter.updMobilizedBody(mobod_of_body[body]); }
};

namespace {

/// An axis's value (rad or m), ODE convention; `state` realized to Position.
double axis_value(const Multibody::Impl& m, const SimTK::State& s, std::size_t a) {
  const AxisImpl& ax = m.axis_impl[a];
  if (!m.axes[a].loop)
    return ax.sign * m.matter.getMobilizedBody(ax.mobod).getOneQ(s, ax.coordinate);
  const auto& b1 = m.mobod(ax.body1);
  const auto& b2 = m.mobod(ax.body2);
  const SimTK::Rotation& R2 = b2.getBodyRotation(s);
  if (m.axes[a].linear) {
    const SimTK::Vec3 offset = ~R2 * (b1.getBodyOriginLocation(s) - b2.getBodyOriginLocation(s));
    return SimTK::dot(offset - ax.offset0_in_body2, ax.axis_in_body2);
  }
  // Rotation of body1 relative to body2 since load, about the axis (in (-pi, pi]).
  const SimTK::Rotation delta = (~R2 * b1.getBodyRotation(s)) * ~ax.relative0;
  const SimTK::Mat33& D = delta.asMat33();
  const SimTK::Vec3 vee(D(2, 1) - D(1, 2), D(0, 2) - D(2, 0), D(1, 0) - D(0, 1));
  return std::atan2(0.5 * SimTK::dot(vee, ax.axis_in_body2), (D.trace() - 1.0) / 2.0);
}

/// An axis's rate (rad/s or m/s); `state` realized to Velocity.
double axis_rate(const Multibody::Impl& m, const SimTK::State& s, std::size_t a) {
  const AxisImpl& ax = m.axis_impl[a];
  if (!m.axes[a].loop)
    return ax.sign * m.matter.getMobilizedBody(ax.mobod).getOneU(s, ax.coordinate);
  const auto& b1 = m.mobod(ax.body1);
  const auto& b2 = m.mobod(ax.body2);
  const SimTK::Vec3 axis_G = b2.getBodyRotation(s) * ax.axis_in_body2;
  if (m.axes[a].linear) {
    const SimTK::Vec3 r = b1.getBodyOriginLocation(s) - b2.getBodyOriginLocation(s);
    const SimTK::Vec3 v = b1.getBodyOriginVelocity(s) - b2.getBodyOriginVelocity(s) -
                          SimTK::cross(b2.getBodyAngularVelocity(s), r);
    return SimTK::dot(v, axis_G);
  }
  return SimTK::dot(b1.getBodyAngularVelocity(s) - b2.getBodyAngularVelocity(s), axis_G);
}

constexpr double kGravity = 9.81;  // m/s², along −Z

/// Speed (rad/s or m/s) over which a loop axis's Coulomb friction ramps to its bound.
constexpr double kLoopFrictionSpeed = 1e-2;

/// Body poses and velocities (kernel indices); `state` realized to Velocity.
void read_bodies(const Multibody::Impl& m, const SimTK::State& s, Pose* poses, Twist* twists);

/// Applies the kernel's loads for the tick: body wrenches and axis forces.
class AppliedLoads : public SimTK::Force::Custom::Implementation {
 public:
  explicit AppliedLoads(const Multibody::Impl* impl) : m_(impl) {}

  void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                 SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector& mobility_forces) const override {
    const auto& mb = *m_;
    for (const auto& w : mb.weights) {
      const SimTK::Vec3 force(0, 0, -kGravity * w.mass_kg);
      const SimTK::Vec3 com_G =
          mb.matter.getMobilizedBody(w.mobod).getBodyRotation(state) * w.com_m;
      body_forces[w.mobod] += SimTK::SpatialVec(SimTK::cross(com_G, force), force);
    }
    add_wrenches(mb.wrenches, body_forces);
    if (mb.substep_forces) add_wrenches(mb.substep_wrenches, body_forces);
    for (std::size_t a = 0; a < mb.axis_impl.size(); ++a)
      if (mb.axis_forces[a] != 0.0)
        apply_axis_force(state, a, mb.axis_forces[a], body_forces, mobility_forces);
    for (std::size_t a = 0; a < mb.axis_impl.size(); ++a)
      if (mb.sliding[a]) {  // clearly sliding: Coulomb's law as it is, no impulse needed
        const double v = axis_rate(mb, state, a);
        apply_axis_force(state, a, v > 0 ? -mb.axis_friction[a] : mb.axis_friction[a], body_forces,
                         mobility_forces);
      } else if (mb.axes[a].loop && mb.axis_friction[a] > 0.0) {
        // No velocity-level brake on a constraint-realised axis: a steep regularisation.
        const double v = axis_rate(mb, state, a);
        const double f = -mb.axis_friction[a] * std::clamp(v / kLoopFrictionSpeed, -1.0, 1.0);
        apply_axis_force(state, a, f, body_forces, mobility_forces);
      }
    for (const auto& stop : mb.stops) {
      const auto a = static_cast<std::size_t>(stop.axis);
      const double q = axis_value(mb, state, a);
      if (q <= stop.high && q >= stop.low) continue;
      const double limit = q > stop.high ? stop.high : stop.low;
      const double f = -stop.stiffness * (q - limit) - stop.damping * axis_rate(mb, state, a);
      // A stop pushes back into the range, never pulls toward the limit.
      const double push = q > stop.high ? std::min(0.0, f) : std::max(0.0, f);
      if (push != 0.0) apply_axis_force(state, a, push, body_forces, mobility_forces);
    }
  }

 private:
  /// A generalized force on one axis: a mobility force for a tree joint, equal and opposite
  /// body loads about / along the axis for a loop joint.
  void apply_axis_force(const SimTK::State& state, std::size_t a, double f,
                        SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                        SimTK::Vector& mobility_forces) const {
    const auto& mb = *m_;
    const AxisImpl& ax = mb.axis_impl[a];
    if (!mb.axes[a].loop) {
      mb.matter.getMobilizedBody(ax.mobod).applyOneMobilityForce(state, ax.coordinate, ax.sign * f,
                                                                 mobility_forces);
      return;
    }
    const auto& b1 = mb.mobod(ax.body1);
    const auto& b2 = mb.mobod(ax.body2);
    const SimTK::Vec3 axis_G = b2.getBodyRotation(state) * ax.axis_in_body2;
    if (mb.axes[a].linear) {
      const SimTK::Vec3 point_G = b1.findStationLocationInGround(state, ax.anchor_in_body1);
      const SimTK::Vec3 force = f * axis_G;
      b1.applyForceToBodyPoint(state, ax.anchor_in_body1, force, body_forces);
      b2.applyForceToBodyPoint(state, b2.findStationAtGroundPoint(state, point_G), -force,
                               body_forces);
    } else {
      b1.applyBodyTorque(state, f * axis_G, body_forces);
      b2.applyBodyTorque(state, -f * axis_G, body_forces);
    }
  }

 public:
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }

 private:
  /// Per-kernel-body wrenches (about each body origin, world frame) on Simbody's bodies; the
  /// loose bodies take theirs in LooseBodies::kick.
  void add_wrenches(const std::vector<Wrench>& wrenches,
                    SimTK::Vector_<SimTK::SpatialVec>& body_forces) const {
    for (std::size_t b = 1; b < wrenches.size(); ++b) {
      if (!m_->mobod_of_body[b].isValid()) continue;
      const Wrench& w = wrenches[b];
      body_forces[m_->mobod_of_body[b]] +=
          SimTK::SpatialVec(to_simtk(w.torque_Nm), to_simtk(w.force_N));
    }
  }

 private:
  const Multibody::Impl* m_;
};

/// The gear-reflected rotor inertia N²·J of a hinge or Universal joint's motors, carried by
/// the joint's child body as a massless disk on the axis (axial N²·J, N²·J/2 across): exact
/// for the spin of the axis when the parent does not turn about it, and a valid inertia
/// whatever the body (docs/models/multibody.md).
SimTK::Inertia reflected_rotor_inertia(const scene::Joint& jt, const scene::Body& child) {
  SimTK::Inertia sum(0);
  if (jt.type != scene::JointType::hinge && jt.type != scene::JointType::universal) return sum;
  const SimTK::Rotation R_GB = to_simtk(child.pose.rotation);
  auto add = [&](const scene::DriveTrain& d, const Vec3& axis_G) {
    const double J = d.gear.ratio * d.gear.ratio * d.rotor.inertia_kg_m2;
    if (!d.motor.active || !(J > 0)) return;
    const SimTK::UnitVec3 a(~R_GB * to_simtk(axis_G));
    const SimTK::Mat33 aa = a * ~a;
    const SimTK::Mat33 disk = J * aa + 0.5 * J * (SimTK::Mat33(1) - aa);
    sum += SimTK::Inertia(
        SimTK::SymMat33(disk(0, 0), disk(1, 0), disk(1, 1), disk(2, 0), disk(2, 1), disk(2, 2)));
  };
  add(jt.drive1, jt.axis1);
  if (jt.type == scene::JointType::universal) add(jt.drive2, jt.axis2);
  return sum;
}

/// Orientation of a joint frame whose `primary` axis is `a`.
SimTK::Rotation joint_frame(const Vec3& a, SimTK::CoordinateAxis primary) {
  return SimTK::Rotation(SimTK::UnitVec3(to_simtk(a)), primary);
}

}  // namespace

Multibody::Multibody(const scene::Scene& scene, double tick_s, int substeps,
                     bool lone_bodies_in_simbody)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.tick_s = tick_s;
  const int n_bodies = static_cast<int>(scene.bodies.size());
  m.mobod_of_body.assign(n_bodies + 1, SimTK::MobilizedBodyIndex());
  m.mobod_of_body[0] = SimTK::GroundIndex;
  m.initial_pose.assign(n_bodies + 1, Pose{});
  for (int i = 0; i < n_bodies; ++i)
    m.initial_pose[i + 1] = scene.bodies[i].pose;

  // Spanning forest of the joint graph: world-connected bodies hang from Ground through their
  // joint, every other group gets a Free root (the robot's main body where there is one).
  const int n_joints = static_cast<int>(scene.joints.size());
  std::vector<std::vector<int>> incident(n_bodies);
  for (int j = 0; j < n_joints; ++j) {
    const auto& jt = scene.joints[j];
    if (jt.body1 >= 0) incident[jt.body1].push_back(j);
    if (jt.body2 >= 0) incident[jt.body2].push_back(j);
  }
  struct TreeEdge {
    int joint, parent, child;  // scene body indices, parent -1 = world, joint -1 = Free
  };
  std::vector<TreeEdge> tree;
  std::vector<int> loops;
  std::vector<char> visited(n_bodies, 0), used(n_joints, 0);
  std::deque<int> queue;
  auto expand = [&]() {
    while (!queue.empty()) {
      const int b = queue.front();
      queue.pop_front();
      for (int j : incident[b]) {
        if (used[j]) continue;
        used[j] = 1;
        const auto& jt = scene.joints[j];
        const int other = jt.body1 == b ? jt.body2 : jt.body1;
        if (other < 0 || visited[other]) {
          loops.push_back(j);
        } else {
          visited[other] = 1;
          tree.push_back({j, b, other});
          queue.push_back(other);
        }
      }
    }
  };
  for (int j = 0; j < n_joints; ++j) {
    const auto& jt = scene.joints[j];
    if (jt.body2 >= 0 && jt.body1 >= 0) continue;
    const int b = jt.body1 >= 0 ? jt.body1 : jt.body2;
    if (b < 0) throw scene_error(jt.where, "joint '" + jt.id + "' connects the world to itself");
    if (used[j]) continue;  // already met as a loop while expanding another world joint
    used[j] = 1;
    if (visited[b]) {
      loops.push_back(j);
      continue;
    }
    visited[b] = 1;
    tree.push_back({j, -1, b});
    queue.push_back(b);
    expand();
  }
  std::vector<int> root_order;
  for (const auto& r : scene.robots)
    if (r.main_body >= 0) root_order.push_back(r.main_body);
  for (int b = 0; b < n_bodies; ++b)
    root_order.push_back(b);
  for (int b : root_order) {
    if (visited[b]) continue;
    visited[b] = 1;
    if (incident[b].empty() && !lone_bodies_in_simbody) {
      m.loose.add(b + 1, scene.bodies[b]);
      continue;
    }
    tree.push_back({-1, -1, b});
    queue.push_back(b);
    expand();
  }

  auto kernel_index = [](int scene_body) { return scene_body + 1; };
  auto pose_of = [&](int scene_body) {
    return scene_body < 0 ? SimTK::Transform() : to_simtk(scene.bodies[scene_body].pose);
  };

  // Bodies and mobilizers in tree order (parents first).
  std::vector<int> free_bodies;
  struct AxisPending {
    int joint, which;
    SimTK::MobilizedBodyIndex mobod;
    int coordinate;
    double sign;
  };
  std::vector<AxisPending> tree_axes;
  m.joint_reaction_source.assign(static_cast<std::size_t>(n_joints), Impl::JointReaction{});
  m.joint_reactions.assign(static_cast<std::size_t>(n_joints), Wrench{});
  m.joint_reactions_in_body1.assign(static_cast<std::size_t>(n_joints), Wrench{});
  for (const TreeEdge& e : tree) {
    const auto& sb = scene.bodies[e.child];
    SimTK::Inertia inertia_com;
    try {
      const Mat3& I = sb.inertia_kg_m2;
      inertia_com =
          SimTK::Inertia(I.m[0][0], I.m[1][1], I.m[2][2], I.m[0][1], I.m[0][2], I.m[1][2]);
      if (e.joint >= 0) inertia_com += reflected_rotor_inertia(scene.joints[e.joint], sb);
      const SimTK::Vec3 com = to_simtk(sb.com_m);
      SimTK::Body::Rigid body(SimTK::MassProperties(
          sb.mass_kg, com, inertia_com.shiftFromMassCenter(-com, sb.mass_kg)));
      SimTK::MobilizedBody& parent = m.upd_mobod(kernel_index(e.parent));
      SimTK::MobilizedBodyIndex index;
      if (e.joint < 0) {
        SimTK::MobilizedBody::Free free(m.matter.updGround(), SimTK::Transform(), body,
                                        SimTK::Transform());
        index = free.getMobilizedBodyIndex();
        free_bodies.push_back(e.child);
      } else {
        const auto& jt = scene.joints[e.joint];
        const SimTK::Transform X_GP = pose_of(e.parent);
        const SimTK::Transform X_GC = pose_of(e.child);
        const bool child_is_body1 = jt.body1 == e.child;
        const double sign = child_is_body1 ? 1.0 : -1.0;
        const SimTK::Vec3 anchor = to_simtk(jt.anchor_m);
        auto frames = [&](const SimTK::Rotation& R_GJ, SimTK::Transform& F, SimTK::Transform& M) {
          const SimTK::Transform X_GJ(R_GJ, anchor);
          F = ~X_GP * X_GJ;
          M = ~X_GC * X_GJ;
        };
        SimTK::Transform F, M;
        switch (jt.type) {
          case scene::JointType::hinge: {
            frames(joint_frame(jt.axis1, SimTK::ZAxis), F, M);
            index = SimTK::MobilizedBody::Pin(parent, F, body, M).getMobilizedBodyIndex();
            tree_axes.push_back({e.joint, 0, index, 0, sign});
            break;
          }
          case scene::JointType::slider: {
            frames(joint_frame(jt.axis1, SimTK::XAxis), F, M);
            index = SimTK::MobilizedBody::Slider(parent, F, body, M).getMobilizedBodyIndex();
            tree_axes.push_back({e.joint, 0, index, 0, sign});
            break;
          }
          case scene::JointType::universal: {
            // Simbody: rotation about F's X (fixed in the parent), then about the new Y (fixed
            // in the child). ODE: axis1 fixed in body1, axis2 fixed in body2.
            const Vec3 first = child_is_body1 ? jt.axis2 : jt.axis1;
            const Vec3 second = child_is_body1 ? jt.axis1 : jt.axis2;
            if (norm(cross(first, second)) < 1e-6)
              throw scene_error(
                  jt.where, "Universal joint '" + jt.id + "': axis and axis2 must not be parallel");
            const SimTK::Rotation R(SimTK::UnitVec3(to_simtk(first)), SimTK::XAxis,
                                    to_simtk(second), SimTK::YAxis);
            frames(R, F, M);
            index = SimTK::MobilizedBody::Universal(parent, F, body, M).getMobilizedBodyIndex();
            const int coord_axis1 = child_is_body1 ? 1 : 0;
            tree_axes.push_back({e.joint, 0, index, coord_axis1, sign});
            tree_axes.push_back({e.joint, 1, index, 1 - coord_axis1, sign});
            break;
          }
          case scene::JointType::ball:
            frames(SimTK::Rotation(), F, M);
            index = SimTK::MobilizedBody::Ball(parent, F, body, M).getMobilizedBodyIndex();
            break;
          case scene::JointType::fixed:
            index = SimTK::MobilizedBody::Weld(parent, ~X_GP * X_GC, body, SimTK::Transform())
                        .getMobilizedBodyIndex();
            break;
        }
      }
      m.mobod_of_body[kernel_index(e.child)] = index;
      if (e.joint >= 0)
        m.joint_reaction_source[static_cast<std::size_t>(e.joint)] = {
            index, scene.joints[e.joint].body1 == e.child,
            kernel_index(scene.joints[e.joint].body1)};
      if (sb.gravity) m.weights.push_back({index, sb.mass_kg, to_simtk(sb.com_m)});
    } catch (const Error&) {
      throw;
    } catch (const std::exception& ex) {
      throw scene_error(e.joint >= 0 ? scene.joints[e.joint].where : sb.where,
                        "Simbody refused body '" + sb.id + "': " + ex.what());
    }
  }

  // Loop-closing joints become constraints.
  std::vector<std::pair<int, AxisImpl>> loop_axes;  // joint, impl (which encoded in order)
  for (int j : loops) {
    const auto& jt = scene.joints[j];
    const int k1 = kernel_index(jt.body1), k2 = kernel_index(jt.body2);
    SimTK::MobilizedBody& b1 = m.upd_mobod(k1);
    SimTK::MobilizedBody& b2 = m.upd_mobod(k2);
    const SimTK::Transform X_G1 = pose_of(jt.body1), X_G2 = pose_of(jt.body2);
    const SimTK::Vec3 anchor = to_simtk(jt.anchor_m);
    const SimTK::Vec3 p1 = ~X_G1 * anchor, p2 = ~X_G2 * anchor;
    auto axis_in = [&](const SimTK::Transform& X, const Vec3& a) {
      return SimTK::UnitVec3(~X.R() * to_simtk(a));
    };
    AxisImpl base;
    base.body1 = k1;
    base.body2 = jt.body2 < 0 ? 0 : k2;
    base.relative0 = ~X_G2.R() * X_G1.R();
    base.offset0_in_body2 = ~X_G2 * X_G1.p();
    base.anchor_in_body1 = p1;
    switch (jt.type) {
      case scene::JointType::fixed:
        SimTK::Constraint::Weld(b1, SimTK::Transform(p1), b2,
                                SimTK::Transform(~X_G2.R() * X_G1.R(), p2));
        break;
      case scene::JointType::ball:
        SimTK::Constraint::Ball(b1, p1, b2, p2);
        break;
      case scene::JointType::hinge: {
        SimTK::Constraint::Ball(b1, p1, b2, p2);
        SimTK::UnitVec3 q1, q2;
        const SimTK::UnitVec3 a2 = axis_in(X_G2, jt.axis1);
        perpendiculars(a2, q1, q2);
        const SimTK::UnitVec3 a1 = axis_in(X_G1, jt.axis1);
        SimTK::Constraint::ConstantAngle(b2, q1, b1, a1);
        SimTK::Constraint::ConstantAngle(b2, q2, b1, a1);
        AxisImpl ax = base;
        ax.axis_in_body2 = a2;
        loop_axes.push_back({j, ax});
        break;
      }
      case scene::JointType::universal: {
        SimTK::Constraint::Ball(b1, p1, b2, p2);
        SimTK::Constraint::ConstantAngle(b1, axis_in(X_G1, jt.axis1), b2, axis_in(X_G2, jt.axis2));
        AxisImpl ax1 = base, ax2 = base;
        ax1.axis_in_body2 = axis_in(X_G2, jt.axis1);
        ax2.axis_in_body2 = axis_in(X_G2, jt.axis2);
        loop_axes.push_back({j, ax1});
        loop_axes.push_back({j, ax2});
        break;
      }
      case scene::JointType::slider: {
        SimTK::Constraint::ConstantOrientation(b2, SimTK::Rotation(), b1, ~base.relative0);
        const SimTK::UnitVec3 a2 = axis_in(X_G2, jt.axis1);
        SimTK::Constraint::PointOnLine(b2, a2, p2, b1, p1);
        AxisImpl ax = base;
        ax.axis_in_body2 = a2;
        loop_axes.push_back({j, ax});
        break;
      }
    }
  }

  // The axis table, in joint order (then axis 1, axis 2).
  for (int j = 0; j < n_joints; ++j) {
    const auto& jt = scene.joints[j];
    auto add = [&](int which, const AxisImpl& impl, bool loop) {
      AxisInfo info;
      info.name = which == 0 ? jt.id : jt.id + ":2";
      info.robot = jt.robot;
      info.joint = j;
      info.which = which;
      info.linear = jt.type == scene::JointType::slider;
      info.loop = loop;
      m.axes.push_back(info);
      m.axis_impl.push_back(impl);
    };
    for (const auto& t : tree_axes)
      if (t.joint == j) {
        AxisImpl impl;
        impl.mobod = t.mobod;
        impl.coordinate = t.coordinate;
        impl.sign = t.sign;
        add(t.which, impl, false);
      }
    int which = 0;
    for (const auto& [lj, impl] : loop_axes)
      if (lj == j) add(which++, impl, true);
  }
  m.wrenches.assign(n_bodies + 1, Wrench{});
  m.axis_forces.assign(m.axes.size(), 0.0);
  m.axis_friction.assign(m.axes.size(), 0.0);

  SimTK::Force::Custom(m.forces, new AppliedLoads(&m));

  // Joint stops, in axis values (limits as written, whatever the mobilizer's direction).
  for (std::size_t a = 0; a < m.axes.size(); ++a) {
    const auto& jt = scene.joints[m.axes[a].joint];
    const scene::Limits& lim = m.axes[a].which == 0 ? jt.limits1 : jt.limits2;
    if (lim.active) m.stops.push_back({static_cast<int>(a), lim.min, lim.max});
  }

  try {
    m.system.realizeTopology();
    SimTK::State state = m.system.getDefaultState();
    for (int b : free_bodies)
      m.mobod(kernel_index(b)).setQToFitTransform(state, pose_of(b));
    m.system.realize(state, SimTK::Stage::Position);
    if (!m.stops.empty()) {
      // Stiffness from the axis's effective (articulated) inertia so that a stop rings at
      // omega*h = 0.2, far inside the integrator's stability limit, critically damped.
      SimTK::Matrix M_inv;
      m.matter.calcMInv(state, M_inv);
      const double omega = 0.2 * substeps / tick_s;
      for (auto& stop : m.stops) {
        const AxisImpl& ax = m.axis_impl[stop.axis];
        double inertia;
        if (!m.axes[stop.axis].loop) {
          const int u = m.matter.getMobilizedBody(ax.mobod).getFirstUIndex(state) + ax.coordinate;
          inertia = 1.0 / M_inv(u, u);
        } else {
          // A loop axis: body1's mass (slider) or inertia about the axis (hinge), a fair bound.
          const auto& mp = m.mobod(ax.body1).getBodyMassProperties(state);
          const SimTK::Vec3 axis_B1 = ~m.mobod(ax.body1).getBodyRotation(state) *
                                      (m.mobod(ax.body2).getBodyRotation(state) * ax.axis_in_body2);
          inertia = m.axes[stop.axis].linear ? mp.getMass()
                                             : SimTK::dot(axis_B1, mp.getInertia() * axis_B1);
        }
        stop.stiffness = inertia * omega * omega;
        stop.damping = 2.0 * inertia * omega;
      }
    }
    m.system.realize(state, SimTK::Stage::Velocity);
    m.initial_state = state;
  } catch (const std::exception& ex) {
    throw scene_error(Location{scene.file.string(), "", ""},
                      std::string("the multibody system could not be built: ") + ex.what());
  }
  m.substeps = substeps;
  // Free and Ball mobilizers keep their orientation as a quaternion in their first four q's.
  // Normalising them here costs a fraction of Simbody's normalizeQuaternions(), which walks
  // the whole tree through its state digest.
  for (SimTK::MobilizedBodyIndex i(1); i < m.matter.getNumBodies(); ++i) {
    const auto& mob = m.matter.getMobilizedBody(i);
    const int nq = mob.getNumQ(m.initial_state), nu = mob.getNumU(m.initial_state);
    const int q0 = mob.getFirstQIndex(m.initial_state), u0 = mob.getFirstUIndex(m.initial_state);
    if (nq != nu) m.quaternion_q.push_back(q0);
    if (nq == nu) {
      for (int c = 0; c < nq; ++c)
        m.direct_coordinates.emplace_back(q0 + c, u0 + c);
    } else if (nq == 7 && nu == 6) {
      m.free_coordinates.push_back({q0, u0});
    } else {
      m.own_n = false;  // a Ball: leave it to Simbody
    }
  }
  m.has_constraints = m.matter.getNumConstraints() > 0;
  m.udot.resize(m.initial_state.getNU());
  m.substep_poses.assign(m.mobod_of_body.size(), Pose{});
  m.substep_twists.assign(m.mobod_of_body.size(), Twist{});
  m.substep_wrenches.assign(m.mobod_of_body.size(), Wrench{});
  m.unit_force.resize(m.initial_state.getNU());
  m.braked.reserve(m.axes.size());
  m.columns_for.reserve(m.axes.size());
  m.columns_q.assign(static_cast<std::size_t>(m.initial_state.getNQ()), 0.0);
  m.minv_column.assign(m.axes.size(), SimTK::Vector(m.initial_state.getNU(), 0.0));
  m.delassus.assign(m.axes.size() * m.axes.size(), 0.0);
  m.impulse.assign(m.axes.size(), 0.0);
  m.axis_mobility.assign(m.axes.size(), 0.0);
  m.sliding.assign(m.axes.size(), 0);
  m.axis_u.assign(m.axes.size(), -1);
  for (std::size_t a = 0; a < m.axes.size(); ++a)
    if (!m.axes[a].loop)
      m.axis_u[a] =
          m.matter.getMobilizedBody(m.axis_impl[a].mobod).getFirstUIndex(m.initial_state) +
          m.axis_impl[a].coordinate;
  m.qdot.resize(m.initial_state.getNQ());
  m.reactions_at_M.resize(m.matter.getNumBodies());
  reset();
}

Multibody::~Multibody() = default;

int Multibody::body_count() const {
  return static_cast<int>(impl_->mobod_of_body.size());
}
const std::vector<AxisInfo>& Multibody::axes() const {
  return impl_->axes;
}
const std::vector<std::string>& Multibody::warnings() const {
  return impl_->warnings;
}
Wrench* Multibody::applied_wrenches() {
  return impl_->wrenches.data();
}
double* Multibody::applied_axis_forces() {
  return impl_->axis_forces.data();
}
double* Multibody::applied_axis_friction() {
  return impl_->axis_friction.data();
}
void Multibody::request_joint_reactions() {
  impl_->reactions_wanted = true;
}
const Wrench* Multibody::joint_reactions() const {
  return impl_->joint_reactions.data();
}
bool Multibody::joint_is_loop(int joint) const {
  return !impl_->joint_reaction_source.at(static_cast<std::size_t>(joint)).mobod.isValid();
}
void Multibody::set_substep_forces(SubstepForces* forces) {
  Impl& m = *impl_;
  m.substep_forces = forces;
}

std::vector<double> Multibody::apparent_mass_kg() const {
  const Impl& m = *impl_;
  const SimTK::State& s = m.initial_state;
  m.system.realize(s, SimTK::Stage::Position);
  const int nb = m.matter.getNumBodies();
  std::vector<double> out(m.mobod_of_body.size(), 0.0);
  SimTK::Vector_<SimTK::SpatialVec> load(nb), accel(nb);
  SimTK::Vector f, udot;
  for (std::size_t b = 1; b < m.mobod_of_body.size(); ++b) {
    if (!m.mobod_of_body[b].isValid()) {  // a loose body: its own mass
      out[b] = m.loose.mass_kg(static_cast<int>(b));
      continue;
    }
    const auto& mob = m.matter.getMobilizedBody(m.mobod_of_body[b]);
    const SimTK::Vec3 com_G = mob.getBodyRotation(s) * mob.getBodyMassProperties(s).getMassCenter();
    double smallest = SimTK::Infinity;
    for (int axis = 0; axis < 3; ++axis) {
      SimTK::Vec3 force(0);
      force[axis] = 1;
      load.setToZero();
      load[mob.getMobilizedBodyIndex()] = SimTK::SpatialVec(SimTK::cross(com_G, force), force);
      m.matter.multiplyBySystemJacobianTranspose(s, load, f);
      m.matter.multiplyByMInv(s, f, udot);
      m.matter.multiplyBySystemJacobian(s, udot, accel);
      const SimTK::SpatialVec& A = accel[mob.getMobilizedBodyIndex()];
      const double a = (A[1] + SimTK::cross(A[0], com_G))[axis];
      if (a > 1e-12) smallest = std::min(smallest, 1 / a);
    }
    out[b] = smallest;
  }
  return out;
}

double Multibody::time_s() const {
  return static_cast<double>(impl_->ticks) * impl_->tick_s;
}

namespace {
void compute_joint_reactions(Multibody::Impl& m, const SimTK::State& s);
void carry_joint_reactions(Multibody::Impl& m, const Pose* poses);
}  // namespace

void Multibody::reset() {
  impl_->ticks = 0;
  std::fill(impl_->joint_reactions.begin(), impl_->joint_reactions.end(), Wrench{});
  impl_->current = impl_->initial_state;
  impl_->half_kick_pending = true;
  impl_->bodies_fresh = false;
  impl_->columns_for.clear();
  std::fill(impl_->axis_mobility.begin(), impl_->axis_mobility.end(), 0.0);
  impl_->loose.reset();
  impl_->system.realize(impl_->current, SimTK::Stage::Velocity);
  if (impl_->reactions_wanted) {
    // The reading before the first step: the initial state under gravity alone (the kernel
    // rewrites every applied load before each step, so clearing them here changes nothing).
    Impl& m = *impl_;
    std::fill(m.wrenches.begin(), m.wrenches.end(), Wrench{});
    std::fill(m.substep_wrenches.begin(), m.substep_wrenches.end(), Wrench{});
    std::fill(m.axis_forces.begin(), m.axis_forces.end(), 0.0);
    std::fill(m.axis_friction.begin(), m.axis_friction.end(), 0.0);
    std::fill(m.sliding.begin(), m.sliding.end(), 0);
    m.current.invalidateAllCacheAtOrAbove(SimTK::Stage::Dynamics);
    m.system.realize(m.current, SimTK::Stage::Acceleration);
    compute_joint_reactions(m, m.current);
  }
}

namespace {

void read_bodies(const Multibody::Impl& m, const SimTK::State& s, Pose* poses, Twist* twists) {
  poses[0] = Pose{};
  twists[0] = Twist{};
  for (std::size_t b = 1; b < m.mobod_of_body.size(); ++b) {
    if (!m.mobod_of_body[b].isValid()) continue;
    const auto& mob = m.matter.getMobilizedBody(m.mobod_of_body[b]);
    const SimTK::Transform& X = mob.getBodyTransform(s);
    poses[b] = Pose{from_simtk(X.p()), from_simtk(X.R())};
    const SimTK::SpatialVec& V = mob.getBodyVelocity(s);
    twists[b] = Twist{from_simtk(V[0]), from_simtk(V[1])};
  }
  m.loose.read(poses, twists);
}

/// v += a·x, through raw storage where it is contiguous (element access goes through a
/// non-inline helper, and Vector expressions allocate).
void add_scaled(SimTK::Vector& v, double a, const SimTK::Vector& x) {
  const int n = v.size();
  if (v.hasContiguousData() && x.hasContiguousData()) {
    double* pv = v.updContiguousScalarData();
    const double* px = x.getContiguousScalarData();
    for (int i = 0; i < n; ++i)
      pv[i] += a * px[i];
  } else {
    for (int i = 0; i < n; ++i)
      v[i] += a * x[i];
  }
}

/// q' = N(q)·u for Free mobilizers (q = quaternion of R_FM then p_FM, u = ω then v, both in
/// F: q̇_quat = ½·(0, ω)⊗q, ṗ = v) and mobilizers whose q' = u (Pin, Slider, Universal).
void calc_qdot(const Multibody::Impl& m, const SimTK::Vector& u, const SimTK::Vector& q,
               SimTK::Vector& qdot) {
  for (const auto& [qi, ui] : m.direct_coordinates)
    qdot[qi] = u[ui];
  for (const auto& f : m.free_coordinates) {
    const double w0 = u[f.u], w1 = u[f.u + 1], w2 = u[f.u + 2];
    const double a = q[f.q], b = q[f.q + 1], c = q[f.q + 2], d = q[f.q + 3];
    qdot[f.q] = -0.5 * (w0 * b + w1 * c + w2 * d);
    qdot[f.q + 1] = 0.5 * (w0 * a + w1 * d - w2 * c);
    qdot[f.q + 2] = 0.5 * (-w0 * d + w1 * a + w2 * b);
    qdot[f.q + 3] = 0.5 * (w0 * c - w1 * b + w2 * a);
    for (int k = 0; k < 3; ++k)
      qdot[f.q + 4 + k] = u[f.u + 3 + k];
  }
}

/// Whether the M^-1 columns computed last are those of the axes braked now, at a configuration
/// within 1e-7 (rad or m) of the current one in every coordinate.
bool columns_still_valid(const Multibody::Impl& m, const SimTK::State& s) {
  if (m.columns_for != m.braked) return false;
  const SimTK::Vector& q = s.getQ();
  const double* now = q.hasContiguousData() ? q.getContiguousScalarData() : nullptr;
  if (!now) return false;
  for (int i = 0; i < q.size(); ++i)
    if (std::abs(now[i] - m.columns_q[static_cast<std::size_t>(i)]) > 1e-7) return false;
  return true;
}

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

/// The joint reactions from a state realized to Acceleration: Simbody's mobilizer reaction
/// on the child at M (mobility forces included), turned into the load on body1 about the
/// anchor carried by body1 (M's origin when the child is body1, F's when it is the parent).
void compute_joint_reactions(Multibody::Impl& m, const SimTK::State& s) {
  m.matter.calcMobilizerReactionForces(s, m.reactions_at_M);
  for (std::size_t j = 0; j < m.joint_reaction_source.size(); ++j) {
    const auto& src = m.joint_reaction_source[j];
    if (!src.mobod.isValid()) continue;  // a loop joint: zeros
    const SimTK::SpatialVec& R = m.reactions_at_M[src.mobod];
    SimTK::Vec3 force = R[1], torque = R[0];
    if (!src.child_is_body1) {
      // On the parent: the opposite load, moved from Mo to Fo (they part along a slider).
      const auto& mob = m.matter.getMobilizedBody(src.mobod);
      const SimTK::Rotation R_GF =
          mob.getParentMobilizedBody().getBodyRotation(s) * mob.getInboardFrame(s).R();
      const SimTK::Vec3 p_FM_G = R_GF * mob.getMobilizerTransform(s).p();
      force = -R[1];
      torque = -R[0] + SimTK::cross(p_FM_G, force);
    }
    m.joint_reactions[j] = Wrench{from_simtk(torque), from_simtk(force)};
    // Also in body1's frame: the step carries it to body1's pose at the step's end.
    const SimTK::Rotation& R_G1 = m.mobod(src.body1).getBodyRotation(s);
    m.joint_reactions_in_body1[j] = Wrench{from_simtk(~R_G1 * torque), from_simtk(~R_G1 * force)};
  }
}

/// The reactions computed in the step, carried with body1 to its pose at the step's end: the
/// reaction is taken at the last substep's start, the sensors read it with the poses after the
/// drift (a steadily spinning joint would otherwise read a tangential ω·h fraction of its
/// centripetal force). `poses` are the step-end body poses.
void carry_joint_reactions(Multibody::Impl& m, const Pose* poses) {
  for (std::size_t j = 0; j < m.joint_reaction_source.size(); ++j) {
    const auto& src = m.joint_reaction_source[j];
    if (!src.mobod.isValid()) continue;
    const Mat3& R = poses[src.body1].rotation;
    const Wrench& local = m.joint_reactions_in_body1[j];
    m.joint_reactions[j] = Wrench{R * local.torque_Nm, R * local.force_N};
  }
}

}  // namespace

namespace {
void advance(Multibody::Impl& m, SimTK::State& s, double h);
}  // namespace

// Semi-explicit Euler, u first then q with the new u, started with a half step of u
// (leapfrog): the same single acceleration evaluation per step, but positions are second
// order and exact under constant acceleration (free fall), and the generalized speeds u live
// at the middle of the step (docs/models/integrator.md).
void Multibody::step() {
  Impl& m = *impl_;
  SimTK::State& s = m.current;
  const double h = m.tick_s / m.substeps;
  try {
    advance(m, s, h);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    // Simbody refuses a state that went non-finite inside the tick (a blow-up).
    throw Error(ErrorKind::runtime, "the simulation failed at t = " + std::to_string(time_s()) +
                                        " s (" + e.what() +
                                        "); the scene may need a smaller step or more substeps");
  }
  ++m.ticks;
  m.system.realize(s, SimTK::Stage::Velocity);
  // Read the bodies once here: for read() and for the next substep's contact.
  read_bodies(m, s, m.substep_poses.data(), m.substep_twists.data());
  m.bodies_fresh = true;
  if (m.reactions_wanted) carry_joint_reactions(m, m.substep_poses.data());
  // A NaN anywhere poisons the sums: one cheap check per tick.
  double sum = m.loose.checksum();
  const SimTK::Vector& q = s.getQ();
  const SimTK::Vector& u = s.getU();
  for (int i = 0; i < q.size(); ++i)
    sum += q[i];
  for (int i = 0; i < u.size(); ++i)
    sum += u[i];
  if (!std::isfinite(sum))
    throw Error(ErrorKind::runtime,
                "the simulation state became non-finite at t = " + std::to_string(time_s()) + " s");
}

namespace {

/// The substeps of one tick.
void advance(Multibody::Impl& m, SimTK::State& s, double h) {
  for (int k = 0; k < m.substeps; ++k) {
    if (m.substep_forces) {
      if (!m.bodies_fresh) {
        m.system.realize(s, SimTK::Stage::Velocity);
        read_bodies(m, s, m.substep_poses.data(), m.substep_twists.data());
      }
      m.substep_forces->compute(m.substep_poses.data(), m.substep_twists.data(), h,
                                m.substep_wrenches.data());
    }
    m.bodies_fresh = false;
    if (!m.axis_friction.empty()) classify_sliding(m, s, h);
    // The applied loads changed outside Simbody's knowledge: drop any cached forces.
    s.invalidateAllCacheAtOrAbove(SimTK::Stage::Dynamics);
    m.system.realize(s, SimTK::Stage::Acceleration);
    m.udot = 0.0;
    add_scaled(m.udot, 1.0, s.getUDot());  // a copy: updU() below invalidates UDot
    // The reactions of the tick's last acceleration evaluation: no extra realize, and the
    // same loads as the kick that follows (the friction brake's impulse excepted).
    if (m.reactions_wanted && k == m.substeps - 1) compute_joint_reactions(m, s);
    const double kick = m.half_kick_pending ? 0.5 * h : h;
    m.half_kick_pending = false;
    add_scaled(s.updU(), kick, m.udot);
    brake_axes(m, s, kick);
    m.loose.kick(m.wrenches.data(), m.substep_forces ? m.substep_wrenches.data() : nullptr, kick);
    m.loose.drift(h);
    if (m.own_n) {
      calc_qdot(m, s.getU(), s.getQ(), m.qdot);
    } else {
      m.matter.multiplyByN(s, false, s.getU(), m.qdot);
    }
    SimTK::Vector& q = s.updQ();
    add_scaled(q, h, m.qdot);
    for (int first : m.quaternion_q) {
      double n2 = 0;
      for (int c = 0; c < 4; ++c)
        n2 += q[first + c] * q[first + c];
      const double inverse_norm = 1 / std::sqrt(n2);
      for (int c = 0; c < 4; ++c)
        q[first + c] *= inverse_norm;
    }
    s.updTime() =
        (static_cast<double>(m.ticks) + static_cast<double>(k + 1) / m.substeps) * m.tick_s;
    m.system.realize(s, SimTK::Stage::Time);
    if (m.has_constraints) m.system.project(s, 1e-10);
  }
}

}  // namespace

void Multibody::read(Pose* poses, Twist* twists, double* axis_position,
                     double* axis_velocity) const {
  const Impl& m = *impl_;
  const SimTK::State& s = m.state();
  m.system.realize(s, SimTK::Stage::Velocity);
  if (m.bodies_fresh) {
    std::copy(m.substep_poses.begin(), m.substep_poses.end(), poses);
    std::copy(m.substep_twists.begin(), m.substep_twists.end(), twists);
  } else {
    read_bodies(m, s, poses, twists);
  }
  for (std::size_t a = 0; a < m.axis_impl.size(); ++a) {
    axis_position[a] = axis_value(m, s, a);
    axis_velocity[a] = axis_rate(m, s, a);
  }
}

double Multibody::kinetic_energy_J() const {
  const SimTK::State& s = impl_->state();
  impl_->system.realize(s, SimTK::Stage::Velocity);
  return impl_->matter.calcKineticEnergy(s) + impl_->loose.kinetic_energy_J();
}

double Multibody::potential_energy_J() const {
  const SimTK::State& s = impl_->state();
  impl_->system.realize(s, SimTK::Stage::Dynamics);
  double energy = impl_->loose.potential_energy_J();
  for (const auto& w : impl_->weights) {
    const auto& mob = impl_->matter.getMobilizedBody(w.mobod);
    energy += w.mass_kg * kGravity * mob.findStationLocationInGround(s, w.com_m)[2];
  }
  return energy;
}

std::vector<double> Multibody::save() const {
  const SimTK::State& s = impl_->state();
  std::vector<double> out;
  out.push_back(static_cast<double>(impl_->ticks));
  out.push_back(impl_->half_kick_pending ? 1.0 : 0.0);
  for (const SimTK::Vector* v : {&s.getQ(), &s.getU(), &s.getZ()})
    for (int i = 0; i < v->size(); ++i)
      out.push_back((*v)[i]);
  const Impl& m = *impl_;
  m.loose.save(out);
  // The brakes' memory decides what the next steps compute: part of the state.
  out.insert(out.end(), m.axis_mobility.begin(), m.axis_mobility.end());
  out.push_back(static_cast<double>(m.columns_for.size()));
  for (std::size_t c = 0; c < m.columns_for.size(); ++c) {
    out.push_back(m.columns_for[c]);
    const SimTK::Vector& column = m.minv_column[c];
    for (int i = 0; i < column.size(); ++i)
      out.push_back(column[i]);
  }
  out.insert(out.end(), m.columns_q.begin(), m.columns_q.end());
  // The last reactions: what a joint sensor reads before the next step.
  for (const Wrench& w : m.joint_reactions)
    for (const Vec3* v : {&w.torque_Nm, &w.force_N})
      out.insert(out.end(), {v->x, v->y, v->z});
  return out;
}

void Multibody::restore(const std::vector<double>& saved) {
  Impl& m = *impl_;
  SimTK::State s = m.initial_state;
  std::size_t k = 0;
  m.ticks = static_cast<std::int64_t>(saved.at(k++));
  m.half_kick_pending = saved.at(k++) != 0.0;
  for (SimTK::Vector* v : {&s.updQ(), &s.updU(), &s.updZ()})
    for (int i = 0; i < v->size(); ++i)
      (*v)[i] = saved.at(k++);
  k = m.loose.restore(saved, k);
  for (double& w : m.axis_mobility)
    w = saved.at(k++);
  m.columns_for.resize(static_cast<std::size_t>(saved.at(k++)));
  for (std::size_t c = 0; c < m.columns_for.size(); ++c) {
    m.columns_for[c] = static_cast<int>(saved.at(k++));
    SimTK::Vector& column = m.minv_column[c];
    for (int i = 0; i < column.size(); ++i)
      column[i] = saved.at(k++);
  }
  for (double& q : m.columns_q)
    q = saved.at(k++);
  for (Wrench& w : m.joint_reactions)
    for (Vec3* v : {&w.torque_Nm, &w.force_N}) {
      v->x = saved.at(k++);
      v->y = saved.at(k++);
      v->z = saved.at(k++);
    }
  m.bodies_fresh = false;
  s.setTime(time_s());
  m.current = s;
  m.system.realize(m.current, SimTK::Stage::Velocity);
}

bool Multibody::place_free_body(int body, const Pose& pose) {
  Impl& m = *impl_;
  if (body <= 0 || body >= static_cast<int>(m.mobod_of_body.size())) return false;
  m.bodies_fresh = false;  // the cached body poses no longer hold the state
  if (!m.mobod_of_body[body].isValid()) return m.loose.place(body, pose);  // a loose body
  SimTK::MobilizedBody& b = m.upd_mobod(body);
  if (!SimTK::MobilizedBody::Free::isInstanceOf(b) || !b.getParentMobilizedBody().isGround())
    return false;
  SimTK::State& s = m.current;
  b.setQToFitTransform(s, to_simtk(pose));
  b.setUToFitVelocity(s, SimTK::SpatialVec(SimTK::Vec3(0), SimTK::Vec3(0)));
  m.system.realize(s, SimTK::Stage::Velocity);
  return true;
}

}  // namespace s2sim::model
