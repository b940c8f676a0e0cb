// Multibody's construction in two phases. plan_topology: the scene's joint graph as a spanning
// forest and the axis table, before any Simbody object exists (the components are configured
// against these axes and may declare axis inertias). The constructor: bodies and mobilizers in
// tree order, loop-closing joints as constraints, limits as stops, then the initial state and
// the stepping buffers.
#include "model/dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <new>
#include <string>

namespace s2sim::model {
namespace {

Error scene_error(const Location& where, const std::string& message) {
  return Error(ErrorKind::scene, where, message);
}

/// Two unit vectors perpendicular to `a` and to each other.
void perpendiculars(const SimTK::UnitVec3& a, SimTK::UnitVec3& p1, SimTK::UnitVec3& p2) {
  p1 = a.perp();
  p2 = SimTK::UnitVec3(SimTK::cross(a, p1));
}

/// The declared inertias J (kg·m², e.g. a motor's gear-reflected rotor inertia N²·J_rotor) of
/// a hinge or Universal joint's axes, carried by the joint's child body as a massless disk on
/// each axis (axial J, J/2 across): exact for the spin of the axis when the parent does not turn
/// about it, and a valid inertia whatever the body (docs/models/multibody.md). `J[1]` is read
/// for a Universal joint only.
SimTK::Inertia axis_disks(const scene::Joint& jt, const scene::Body& child, const double* J) {
  SimTK::Inertia sum(0);
  if (jt.type != scene::JointType::hinge && jt.type != scene::JointType::universal) return sum;
  const SimTK::Rotation R_GB = to_simtk(child.pose.rotation);
  auto add = [&](double inertia, const Vec3& axis_G) {
    if (!(inertia > 0)) return;
    const SimTK::UnitVec3 a(~R_GB * to_simtk(axis_G));
    const SimTK::Mat33 aa = a * ~a;
    const SimTK::Mat33 disk = inertia * aa + 0.5 * inertia * (SimTK::Mat33(1) - aa);
    sum += SimTK::Inertia(
        SimTK::SymMat33(disk(0, 0), disk(1, 0), disk(1, 1), disk(2, 0), disk(2, 1), disk(2, 2)));
  };
  add(J[0], jt.axis1);
  if (jt.type == scene::JointType::universal) add(J[1], jt.axis2);
  return sum;
}

/// Orientation of a joint frame whose `primary` axis is `a`.
SimTK::Rotation joint_frame(const Vec3& a, SimTK::CoordinateAxis primary) {
  return SimTK::Rotation(SimTK::UnitVec3(to_simtk(a)), primary);
}

int kernel_index(int scene_body) {
  return scene_body + 1;
}

SimTK::Transform pose_of(const scene::Scene& scene, int scene_body) {
  return scene_body < 0 ? SimTK::Transform() : to_simtk(scene.bodies[scene_body].pose);
}

/// A tree axis before the axis table exists: its mobilizer coordinate.
struct AxisPending {
  int joint, which;
  SimTK::MobilizedBodyIndex mobod;
  int coordinate;
  double sign;
};

/// What the build carries from one phase to the next.
struct Build {
  const scene::Scene& scene;
  const Topology& topology;
  std::vector<int> free_bodies;
  std::vector<AxisPending> tree_axes;
  std::vector<std::pair<int, AxisImpl>> loop_axes;  // joint, impl (which encoded in order)
  std::vector<double> joint_inertia;                // per joint: its axes' declared inertias
};

/// The mobilizer of a jointed tree edge: `body` hung from `parent` through the edge's joint.
SimTK::MobilizedBodyIndex add_joint_mobilizer(Build& b, const Topology::Edge& e,
                                              SimTK::MobilizedBody& parent,
                                              const SimTK::Body::Rigid& body) {
  const auto& jt = b.scene.joints[e.joint];
  const SimTK::Transform X_GP = pose_of(b.scene, e.parent);
  const SimTK::Transform X_GC = pose_of(b.scene, e.child);
  const bool child_is_body1 = jt.body1 == e.child;
  const double sign = child_is_body1 ? 1.0 : -1.0;
  const SimTK::Vec3 anchor = to_simtk(jt.anchor_m);
  auto frames = [&](const SimTK::Rotation& R_GJ, SimTK::Transform& F, SimTK::Transform& M) {
    const SimTK::Transform X_GJ(R_GJ, anchor);
    F = ~X_GP * X_GJ;
    M = ~X_GC * X_GJ;
  };
  SimTK::Transform F, M;
  SimTK::MobilizedBodyIndex index;
  switch (jt.type) {
    case scene::JointType::hinge: {
      frames(joint_frame(jt.axis1, SimTK::ZAxis), F, M);
      index = SimTK::MobilizedBody::Pin(parent, F, body, M).getMobilizedBodyIndex();
      b.tree_axes.push_back({e.joint, 0, index, 0, sign});
      break;
    }
    case scene::JointType::slider: {
      frames(joint_frame(jt.axis1, SimTK::XAxis), F, M);
      index = SimTK::MobilizedBody::Slider(parent, F, body, M).getMobilizedBodyIndex();
      b.tree_axes.push_back({e.joint, 0, index, 0, sign});
      break;
    }
    case scene::JointType::universal: {
      // Simbody: rotation about F's X (fixed in the parent), then about the new Y (fixed
      // in the child). ODE: axis1 fixed in body1, axis2 fixed in body2.
      const Vec3 first = child_is_body1 ? jt.axis2 : jt.axis1;
      const Vec3 second = child_is_body1 ? jt.axis1 : jt.axis2;
      if (norm(cross(first, second)) < 1e-6)
        throw scene_error(jt.where,
                          "Universal joint '" + jt.id + "': axis and axis2 must not be parallel");
      const SimTK::Rotation R(SimTK::UnitVec3(to_simtk(first)), SimTK::XAxis, to_simtk(second),
                              SimTK::YAxis);
      frames(R, F, M);
      index = SimTK::MobilizedBody::Universal(parent, F, body, M).getMobilizedBodyIndex();
      const int coord_axis1 = child_is_body1 ? 1 : 0;
      b.tree_axes.push_back({e.joint, 0, index, coord_axis1, sign});
      b.tree_axes.push_back({e.joint, 1, index, 1 - coord_axis1, sign});
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
  return index;
}

/// Bodies and mobilizers in tree order (parents first).
void add_tree_bodies(Multibody::Impl& m, Build& b) {
  const scene::Scene& scene = b.scene;
  for (const Topology::Edge& e : b.topology.tree) {
    const auto& sb = scene.bodies[e.child];
    try {
      const Mat3& I = sb.inertia_kg_m2;
      SimTK::Inertia inertia_com(I.m[0][0], I.m[1][1], I.m[2][2], I.m[0][1], I.m[0][2], I.m[1][2]);
      if (e.joint >= 0) {
        const SimTK::Inertia disks =
            axis_disks(scene.joints[e.joint], sb, &b.joint_inertia[2 * e.joint]);
        inertia_com += disks;
        m.joint_disk_inertia[kernel_index(e.child)] = disks;
      }
      const SimTK::Vec3 com = to_simtk(sb.com_m);
      SimTK::Body::Rigid body(SimTK::MassProperties(
          sb.mass_kg, com, inertia_com.shiftFromMassCenter(-com, sb.mass_kg)));
      SimTK::MobilizedBody& parent = m.upd_mobod(kernel_index(e.parent));
      SimTK::MobilizedBodyIndex index;
      if (e.joint < 0) {
        SimTK::MobilizedBody::Free free(m.matter.updGround(), SimTK::Transform(), body,
                                        SimTK::Transform());
        index = free.getMobilizedBodyIndex();
        b.free_bodies.push_back(e.child);
      } else {
        index = add_joint_mobilizer(b, e, parent, body);
      }
      m.mobod_of_body[kernel_index(e.child)] = index;
      if (e.joint >= 0)
        m.joint_reaction_source[static_cast<std::size_t>(e.joint)] = {
            index, scene.joints[e.joint].body1 == e.child,
            kernel_index(scene.joints[e.joint].body1)};
      if (sb.gravity) m.weights.push_back({index, sb.mass_kg, to_simtk(sb.com_m)});
    } catch (const Error&) {
      throw;
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& ex) {
      throw scene_error(e.joint >= 0 ? scene.joints[e.joint].where : sb.where,
                        "Simbody refused body '" + sb.id + "': " + ex.what());
    }
  }
}

/// Loop-closing joints become constraints; their axes are measured from the two bodies.
void add_loop_constraints(Multibody::Impl& m, Build& b) {
  const scene::Scene& scene = b.scene;
  for (int j : b.topology.loops) {
    const auto& jt = scene.joints[j];
    const int k1 = kernel_index(jt.body1), k2 = kernel_index(jt.body2);
    SimTK::MobilizedBody& b1 = m.upd_mobod(k1);
    SimTK::MobilizedBody& b2 = m.upd_mobod(k2);
    const SimTK::Transform X_G1 = pose_of(scene, jt.body1), X_G2 = pose_of(scene, jt.body2);
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
        b.loop_axes.push_back({j, ax});
        break;
      }
      case scene::JointType::universal: {
        SimTK::Constraint::Ball(b1, p1, b2, p2);
        SimTK::Constraint::ConstantAngle(b1, axis_in(X_G1, jt.axis1), b2, axis_in(X_G2, jt.axis2));
        AxisImpl ax1 = base, ax2 = base;
        ax1.axis_in_body2 = axis_in(X_G2, jt.axis1);
        ax2.axis_in_body2 = axis_in(X_G2, jt.axis2);
        b.loop_axes.push_back({j, ax1});
        b.loop_axes.push_back({j, ax2});
        break;
      }
      case scene::JointType::slider: {
        SimTK::Constraint::ConstantOrientation(b2, SimTK::Rotation(), b1, ~base.relative0);
        const SimTK::UnitVec3 a2 = axis_in(X_G2, jt.axis1);
        SimTK::Constraint::PointOnLine(b2, a2, p2, b1, p1);
        AxisImpl ax = base;
        ax.axis_in_body2 = a2;
        b.loop_axes.push_back({j, ax});
        break;
      }
    }
  }
}

/// Joint couplings become CoordinateCouplers on the two mobilizer coordinates. In axis values
/// a = s·q (s = ±1, the mobilizer's direction), a_f = k·a_l + c is q_f = s_f·s_l·k·q_l + s_f·c.
void add_couplings(Multibody::Impl& m, const Build& b) {
  for (const scene::JointCoupling& c : b.scene.couplings) {
    const AxisPending* follower = nullptr;
    const AxisPending* leader = nullptr;
    for (const AxisPending& t : b.tree_axes) {
      if (t.joint == c.follower) follower = &t;
      if (t.joint == c.leader) leader = &t;
    }
    if (!follower || !leader) {
      const int j = follower ? c.leader : c.follower;
      throw scene_error(c.where, "joint coupling: joint '" + b.scene.joints[j].id +
                                     "' closes a kinematic loop; only joints of the spanning "
                                     "tree can be coupled");
    }
    Multibody::Impl::Coupler coupler;
    coupler.follower = follower->mobod;
    coupler.leader = leader->mobod;
    coupler.ratio = follower->sign * leader->sign * c.multiplier;
    coupler.offset = follower->sign * c.offset;
    // f(q_f, q_l) = q_f − ratio·q_l − offset, held at zero.
    SimTK::Vector coefficients(3);
    coefficients[0] = 1.0;
    coefficients[1] = -coupler.ratio;
    coefficients[2] = -coupler.offset;
    const SimTK::Constraint::CoordinateCoupler constraint(
        m.matter, new SimTK::Function::Linear(coefficients),
        std::vector<SimTK::MobilizedBodyIndex>{follower->mobod, leader->mobod},
        std::vector<SimTK::MobilizerQIndex>{SimTK::MobilizerQIndex(0), SimTK::MobilizerQIndex(0)});
    coupler.constraint = constraint.getConstraintIndex();
    m.couplers.push_back(coupler);
  }
}

/// The axis table of the plan with how each axis is realised: a mobilizer coordinate for a
/// tree axis, the two bodies of a loop-closing one.
void fill_axis_table(Multibody::Impl& m, const Build& b) {
  m.axes = b.topology.axes;
  for (const AxisInfo& info : m.axes) {
    AxisImpl impl;
    if (!info.loop) {
      for (const auto& t : b.tree_axes)
        if (t.joint == info.joint && t.which == info.which) {
          impl.mobod = t.mobod;
          impl.coordinate = t.coordinate;
          impl.sign = t.sign;
        }
    } else {
      int which = 0;  // a joint's loop axes are recorded axis 1 first
      for (const auto& [joint, loop_impl] : b.loop_axes)
        if (joint == info.joint && which++ == info.which) impl = loop_impl;
    }
    m.axis_impl.push_back(impl);
  }
}

/// Joint stops, in axis values (limits as written, whatever the mobilizer's direction).
void add_stops(Multibody::Impl& m, const scene::Scene& scene) {
  for (std::size_t a = 0; a < m.axes.size(); ++a) {
    const auto& jt = scene.joints[m.axes[a].joint];
    const scene::Limits& lim = m.axes[a].which == 0 ? jt.limits1 : jt.limits2;
    if (lim.active) m.stops.push_back({static_cast<int>(a), lim.min, lim.max});
  }
}

/// The initial state: free roots at their poses, stops tuned, realized to Velocity.
void build_initial_state(Multibody::Impl& m, const Build& b, double tick_s, int substeps) {
  try {
    m.system.realizeTopology();
    SimTK::State state = default_state(m);
    for (int body : b.free_bodies)
      m.mobod(kernel_index(body)).setQToFitTransform(state, pose_of(b.scene, body));
    // A coupling's offset moves its follower off the pose it was written in: followers set
    // from their leaders, as many passes as couplings (a chain of them has no cycle).
    for (std::size_t pass = 0; pass < m.couplers.size(); ++pass)
      for (const Multibody::Impl::Coupler& c : m.couplers)
        m.matter.getMobilizedBody(c.follower)
            .setOneQ(state, 0,
                     c.ratio * m.matter.getMobilizedBody(c.leader).getOneQ(state, 0) + c.offset);
    m.system.realize(state, SimTK::Stage::Position);
    if (!m.stops.empty()) tune_stops(m, state, kStopRinging * substeps / tick_s);
    m.system.realize(state, SimTK::Stage::Velocity);
    m.initial_state = state;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& ex) {
    throw scene_error(Location{b.scene.file.string(), "", ""},
                      std::string("the multibody system could not be built: ") + ex.what());
  }
}

/// The integrator's coordinate maps and every buffer stepping uses (stepping must not
/// allocate).
void prepare_stepping(Multibody::Impl& m, std::size_t drive_slots) {
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
    } else if (nq == 4 && nu == 3) {
      m.ball_coordinates.push_back({q0, u0});
    } else {
      m.own_n = false;  // another kind: leave it to Simbody
    }
  }
  for (std::size_t b = 1; b < m.mobod_of_body.size(); ++b)
    if (m.mobod_of_body[b].isValid()) m.jointed_bodies.push_back({b, m.mobod_of_body[b]});
  m.has_constraints = m.matter.getNumConstraints() > 0;
  m.has_mobilized_bodies = m.matter.getNumBodies() > 1;
  find_mass_matrix_coordinates(m);
  m.udot.resize(m.initial_state.getNU());
  m.substep_poses.assign(m.mobod_of_body.size(), Pose{});
  m.substep_twists.assign(m.mobod_of_body.size(), Twist{});
  m.substep_wrenches.assign(m.mobod_of_body.size(), Wrench{});
  m.unit_force.resize(m.initial_state.getNU());
  m.unit_speed.assign(static_cast<std::size_t>(m.initial_state.getNU()), 0.0);
  m.columns_q.assign(static_cast<std::size_t>(m.initial_state.getNQ()), 0.0);
  m.loop_unit_force.assign(m.axes.size(), SimTK::Vector());
  for (std::size_t a = 0; a < m.axes.size(); ++a)
    if (m.axes[a].loop) m.loop_unit_force[a].resize(m.initial_state.getNU());
  m.column_valid.assign(m.axes.size(), 0);
  m.unit_body_forces.resize(m.matter.getNumBodies());
  // Room for the drives (by default four per axis: a motor and a viscous friction take two),
  // and the rows of the implicit solve: every drive and every loop axis's friction.
  m.drives.assign(drive_slots, AxisDrive{});
  const std::size_t max_rows = m.drives.size() + m.axes.size();
  m.rows.reserve(max_rows);
  m.next_row.assign(max_rows, -1);
  m.first_row.assign(m.axes.size(), -1);
  m.solve_list.reserve(m.axes.size());
  m.friction_bound.assign(m.axes.size(), 0.0);
  m.friction_applied.assign(m.axes.size(), 0.0);
  m.axis_stuck.assign(m.axes.size(), 0);
  m.breakpoints.assign(2 * max_rows, 0.0);
  m.explicit_drive.assign(m.axes.size(), 0.0);
  m.rate0.assign(m.axes.size(), 0.0);
  m.drive_sum.assign(m.axes.size(), 0.0);
  m.drive_applied.assign(m.axes.size(), 0.0);
  m.axis_mobility.assign(m.axes.size(), 0.0);
  m.sliding.assign(m.axes.size(), 0);
  m.axis_u.assign(m.axes.size(), -1);
  m.axis_q.assign(m.axes.size(), -1);
  for (std::size_t a = 0; a < m.axes.size(); ++a) {
    if (m.axes[a].loop) continue;
    const auto& mob = m.matter.getMobilizedBody(m.axis_impl[a].mobod);
    m.axis_u[a] = mob.getFirstUIndex(m.initial_state) + m.axis_impl[a].coordinate;
    m.axis_q[a] = mob.getFirstQIndex(m.initial_state) + m.axis_impl[a].coordinate;
  }
  find_axis_trees(m);
  allocate_axis_columns(m);
  find_friction_ranges(m);
  m.qdot.resize(m.initial_state.getNQ());
  m.reactions_at_M.resize(m.matter.getNumBodies());
  build_fast_path(m);
}

}  // namespace

Topology plan_topology(const scene::Scene& scene, bool lone_bodies_in_simbody) {
  // Spanning forest of the joint graph: world-connected bodies hang from Ground through their
  // joint, every other group gets a Free root (the robot's main body where there is one).
  Topology t;
  const int n_bodies = static_cast<int>(scene.bodies.size());
  const int n_joints = static_cast<int>(scene.joints.size());
  std::vector<std::vector<int>> incident(n_bodies);
  for (int j = 0; j < n_joints; ++j) {
    const auto& jt = scene.joints[j];
    if (jt.body1 >= 0) incident[jt.body1].push_back(j);
    if (jt.body2 >= 0) incident[jt.body2].push_back(j);
  }
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
          t.loops.push_back(j);
        } else {
          visited[other] = 1;
          t.tree.push_back({j, b, other});
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
      t.loops.push_back(j);
      continue;
    }
    visited[b] = 1;
    t.tree.push_back({j, -1, b});
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
      t.loose.push_back(b);
      continue;
    }
    t.tree.push_back({-1, -1, b});
    queue.push_back(b);
    expand();
  }

  // The axis table, in joint order (then axis 1, axis 2).
  t.joint_is_loop.assign(static_cast<std::size_t>(n_joints), 0);
  for (int j : t.loops)
    t.joint_is_loop[static_cast<std::size_t>(j)] = 1;
  for (int j = 0; j < n_joints; ++j) {
    const auto& jt = scene.joints[j];
    const int n_axes = jt.type == scene::JointType::universal ? 2
                       : jt.type == scene::JointType::fixed || jt.type == scene::JointType::ball
                           ? 0
                           : 1;  // hinge, slider
    for (int which = 0; which < n_axes; ++which) {
      AxisInfo info;
      info.name = which == 0 ? jt.id : jt.id + ":2";
      info.robot = jt.robot;
      info.joint = j;
      info.which = which;
      info.linear = jt.type == scene::JointType::slider;
      info.loop = t.joint_is_loop[static_cast<std::size_t>(j)] != 0;
      t.axes.push_back(info);
    }
  }
  return t;
}

Multibody::Multibody(const scene::Scene& scene, double tick_s, int substeps,
                     bool lone_bodies_in_simbody)
    : Multibody(scene, plan_topology(scene, lone_bodies_in_simbody), {}, tick_s, substeps) {}

Multibody::Multibody(const scene::Scene& scene, const Topology& topology,
                     const std::vector<double>& axis_inertia, double tick_s, int substeps,
                     std::int32_t drive_slots)
    : impl_(std::make_unique<Impl>()) {
  scene::validate_couplings(scene);  // scenes built without the loader too
  Impl& m = *impl_;
  m.dynamics = &simbody_dynamics();  // the builder's, until select_dynamics chooses
  m.check.agreement = kDynamicsAgreement;
  m.tick_s = tick_s;
  const int n_bodies = static_cast<int>(scene.bodies.size());
  const auto n_joints = scene.joints.size();
  m.mobod_of_body.assign(n_bodies + 1, SimTK::MobilizedBodyIndex());
  m.joint_disk_inertia.assign(n_bodies + 1, SimTK::Inertia(0));
  m.mobod_of_body[0] = SimTK::GroundIndex;
  m.initial_pose.assign(n_bodies + 1, Pose{});
  m.body_names.assign(n_bodies + 1, "the world");
  for (int i = 0; i < n_bodies; ++i) {
    m.initial_pose[i + 1] = scene.bodies[i].pose;
    const auto& b = scene.bodies[i];
    m.body_names[i + 1] =
        "'" + b.id + "'" +
        (b.robot >= 0 ? " of robot '" + scene.robots[static_cast<std::size_t>(b.robot)].id + "'"
                      : std::string(" (a thing)"));
  }
  for (int b : topology.loose)
    m.loose.add(b + 1, scene.bodies[b]);

  Build b{scene, topology, {}, {}, {}, std::vector<double>(2 * n_joints, 0.0)};
  for (std::size_t a = 0; a < axis_inertia.size() && a < topology.axes.size(); ++a) {
    const AxisInfo& ax = topology.axes[a];
    const scene::JointType type = scene.joints[static_cast<std::size_t>(ax.joint)].type;
    if (!(axis_inertia[a] > 0)) continue;
    if (ax.loop || type == scene::JointType::slider) {
      m.warnings.push_back(
          scene.joints[static_cast<std::size_t>(ax.joint)].where.str() + ": axis '" + ax.name +
          "': a declared axis inertia is carried on hinge and Universal axes of the spanning "
          "tree only; this " +
          (ax.loop ? "loop-closing" : "slider") + " axis ignores it");
      continue;
    }
    b.joint_inertia[2 * static_cast<std::size_t>(ax.joint) + static_cast<std::size_t>(ax.which)] +=
        axis_inertia[a];
  }
  m.joint_reaction_source.assign(n_joints, Impl::JointReaction{});
  m.joint_reactions.assign(n_joints, Wrench{});
  m.joint_reactions_in_body1.assign(n_joints, Wrench{});
  add_tree_bodies(m, b);
  add_loop_constraints(m, b);
  add_couplings(m, b);
  fill_axis_table(m, b);
  m.wrenches.assign(n_bodies + 1, Wrench{});
  m.axis_forces.assign(m.axes.size(), 0.0);
  m.axis_friction.assign(m.axes.size(), 0.0);
  register_applied_loads(m);
  add_stops(m, scene);
  build_initial_state(m, b, tick_s, substeps);
  m.substeps = substeps;
  prepare_stepping(m, drive_slots > 0 ? static_cast<std::size_t>(drive_slots) : 4 * m.axes.size());
  select_dynamics(m);
  reset();
}

SimTK::State default_state(Multibody::Impl& m) {
  SimTK::State state = m.system.getDefaultState();
  // Without constraints the loads bypass Simbody's force subsystem (realize_accelerations).
  if (m.matter.getNumConstraints() == 0)
    m.forces.setForceIsDisabled(state, m.applied_loads_force, true);
  return state;
}

// A stop's stiffness from its axis's effective (articulated) inertia so that it rings at
// omega·h = 0.2, far inside the integrator's stability limit, critically damped.
void tune_stops(Multibody::Impl& m, const SimTK::State& state, double omega) {
  SimTK::Matrix M_inv;
  m.matter.calcMInv(state, M_inv);
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
      inertia =
          m.axes[stop.axis].linear ? mp.getMass() : SimTK::dot(axis_B1, mp.getInertia() * axis_B1);
    }
    stop.stiffness = inertia * omega * omega;
    stop.damping = 2.0 * inertia * omega;
  }
}

}  // namespace s2sim::model
