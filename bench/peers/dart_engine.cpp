// DART 6.12 in the peer benchmark, built from the scene's numbers as ODE and Bullet are
// (peer_model.hpp): a dart::simulation::World with its default constraint solver (boxed LCP,
// Dantzig), one World::step of 1 ms per step. Each robot is a skeleton (chassis on a free joint,
// two wheel hinges), the humanoid and the arm one skeleton each (Featherstone, reduced
// coordinates), each pile body its own skeleton on a free joint.
//
// Collision: `dart` swaps DART's default detector, FCL, for DART's ODE one (libdart-collision-ode,
// ODE's own analytic box, sphere, cylinder and plane tests, as the ODE peer's), on a plane floor.
// FCL in DART meshes the primitives (a wheel is a 16-sided prism, a box 12 triangles, a plane a
// vertical sheet): the pile's bodies sink into each other and through the floor, and with FCL's
// analytic boxes and spheres the wheels are still meshes and the robots veer
// (docs/benchmarks-peers.md). `dart-fcl` keeps FCL as DART sets it up, on a box floor, to show it.
//
// The same laws as the other engines, as far as DART lets them be set:
// - contacts: DART's contact rows are global ERP/CFM, its CFM relative to each row's diagonal.
//   ERP = h·k/(h·k + c) and CFM = 1/(h·(h·k + c)) of k = m·300², c = 2·m·300 make every contact a
//   spring-damper at 300 rad/s, critically damped, for the effective mass m of its row (the other
//   engines take the lighter body's mass); the correcting speed is not capped (DART caps it at
//   1 mm/s by default, which would make the contact a slow, stiff one instead).
// - friction: DART takes the smaller of two coefficients. No two surfaces of these scenes that
//   both set one ever touch, so the floor (none of its own) is given one larger than any, and a
//   surface without one kDefaultMu: the geometric-mean rule of the others, pair by pair.
// - a DC motor: the torque Ks/Ri·V − (Ks²/Ri + bv)·ω within ±Ks·imax set on the joint before
//   every step (explicit, as Bullet's). DART's implicit joint damping would do, but it enters
//   the unconstrained step and not the constraint impulses, which shifts the closed arm's rest
//   by h·d/M, about 1 % (0.2015 m where the others rest at 0.2032–0.2034 m). Coulomb friction
//   fc is the joint's own (DART's JointCoulombFrictionConstraint, an impulse bounded by fc·dt); the
//   rotor's J is added to the child's inertia (DART has no armature).
// - collisions: only bodies joined by a hinge skip contact, as in ODE (DART's self-collision
//   on, adjacent bodies off, the loop's pair black-listed).
#include "engine.hpp"
#include "peer_model.hpp"

#include <dart/collision/CollisionFilter.hpp>
#include <dart/collision/ode/OdeCollisionDetector.hpp>
#include <dart/constraint/BallJointConstraint.hpp>
#include <dart/constraint/ConstraintSolver.hpp>
#include <dart/constraint/ContactConstraint.hpp>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/BoxShape.hpp>
#include <dart/dynamics/CylinderShape.hpp>
#include <dart/dynamics/FreeJoint.hpp>
#include <dart/dynamics/PlaneShape.hpp>
#include <dart/dynamics/RevoluteJoint.hpp>
#include <dart/dynamics/ShapeNode.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/dynamics/SphereShape.hpp>
#include <dart/dynamics/WeldJoint.hpp>
#include <dart/simulation/World.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace peers {
namespace {

using dart::dynamics::BodyNode;
using dart::dynamics::Skeleton;

constexpr double kStep_s = 0.001;
/// Larger than any surface's: DART's min() then gives the other surface's coefficient.
constexpr double kFloorMu = 1e3;

Eigen::Vector3d vec(const Vec3d& v) {
  return {v[0], v[1], v[2]};
}

Eigen::Isometry3d translation(const Eigen::Vector3d& t) {
  Eigen::Isometry3d tf = Eigen::Isometry3d::Identity();
  tf.translation() = t;
  return tf;
}

/// A box's inertia about its centre.
Eigen::Matrix3d box_inertia(double mass_kg, const Vec3d& size_m) {
  const double x2 = size_m[0] * size_m[0], y2 = size_m[1] * size_m[1], z2 = size_m[2] * size_m[2];
  return Eigen::Vector3d(mass_kg * (y2 + z2) / 12, mass_kg * (x2 + z2) / 12,
                         mass_kg * (x2 + y2) / 12)
      .asDiagonal();
}

/// The contact law of the file's header, for every contact of the process (DART's are static).
void set_contact_law() {
  const double h_omega = kStep_s * kContactOmega_rad_s;
  dart::constraint::ContactConstraint::setErrorReductionParameter(h_omega / (h_omega + 2));
  dart::constraint::ContactConstraint::setConstraintForceMixing(1 / (h_omega * (h_omega + 2)));
  dart::constraint::ContactConstraint::setMaxErrorReductionVelocity(1e9);
  dart::constraint::ContactConstraint::setErrorAllowance(0);
}

/// A DC motor (ki = 0: passive) on the single degree of freedom of `joint`.
struct Drive {
  dart::dynamics::Joint* joint = nullptr;
  double source_Nm = 0, damping_Nms = 0, limit_Nm = 0;
};

class DartEngine final : public Engine {
 public:
  DartEngine(const SceneSpec& scene, bool fcl) : scene_(scene), fcl_(fcl) { build(); }

  void reset() override { build(); }

  void step(long steps) override {
    for (long i = 0; i < steps; ++i) {
      for (const Drive& d : drives_)
        d.joint->setForce(0, std::clamp(d.source_Nm - d.damping_Nms * d.joint->getVelocity(0),
                                        -d.limit_Nm, d.limit_Nm));
      world_->step();
    }
  }

  double deepest_penetration_m() const override {
    double deepest = 0;
    for (const auto& contact : world_->getLastCollisionResult().getContacts())
      deepest = std::max(deepest, contact.penetrationDepth);
    return deepest;
  }
  int tracked_count() const override { return static_cast<int>(tracked_.size()); }
  TrackedPose tracked(int index) const override {
    const Eigen::Isometry3d& t = tracked_[static_cast<std::size_t>(index)]->getWorldTransform();
    TrackedPose out;
    out.position_m = {t.translation().x(), t.translation().y(), t.translation().z()};
    out.yaw_rad = std::atan2(t.linear()(1, 0), t.linear()(0, 0));
    return out;
  }

 private:
  void build() {
    tracked_.clear();
    drives_.clear();
    set_contact_law();
    world_ = std::make_shared<dart::simulation::World>();
    world_->setTimeStep(kStep_s);
    world_->setGravity(Eigen::Vector3d(0, 0, -9.81));
    if (!fcl_)
      world_->getConstraintSolver()->setCollisionDetector(
          dart::collision::OdeCollisionDetector::create());

    // The floor: the plane z = 0; for FCL, which makes a plane a vertical sheet, a box whose top
    // is z = 0, wide enough for the largest grid of robots.
    auto floor = Skeleton::create("floor");
    BodyNode* ground = floor->createJointAndBodyNodePair<dart::dynamics::WeldJoint>().second;
    ground->setName("floor");
    constexpr double kFloorSide_m = 200, kFloorThickness_m = 1;
    if (fcl_)
      add_shape(ground,
                std::make_shared<dart::dynamics::BoxShape>(
                    Eigen::Vector3d(kFloorSide_m, kFloorSide_m, kFloorThickness_m)),
                translation({0, 0, -kFloorThickness_m / 2}), kFloorMu);
    else
      add_shape(ground, std::make_shared<dart::dynamics::PlaneShape>(Eigen::Vector3d::UnitZ(), 0.0),
                Eigen::Isometry3d::Identity(), kFloorMu);
    floor->setMobile(false);
    world_->addSkeleton(floor);

    add_scene_bodies(
        scene_, [&](const std::array<double, 2>& xy) { add_robot(xy); },
        [&](const PileBody& b) { add_pile_body(b); },
        [&](const ArticulatedModel& model) { add_articulated(model); });
  }

  /// A colliding shape on `body` at `pose` in its frame; mu < 0: none of its own (kDefaultMu).
  static void add_shape(BodyNode* body, const dart::dynamics::ShapePtr& shape,
                        const Eigen::Isometry3d& pose, double mu) {
    auto* node =
        body->createShapeNodeWith<dart::dynamics::CollisionAspect, dart::dynamics::DynamicsAspect>(
            shape);
    node->setRelativeTransform(pose);
    node->getDynamicsAspect()->setFrictionCoeff(mu >= 0 ? mu : kDefaultMu);
    node->getDynamicsAspect()->setRestitutionCoeff(0);
  }

  /// The motor law of `joint` (ki = 0: passive) and its Coulomb friction.
  void add_drive(dart::dynamics::Joint* joint, double ki, double ri, double imax, double bv,
                 double fc, double volts) {
    const double damping = (ki > 0 ? ki * ki / ri : 0.0) + bv;
    if (damping > 0)
      drives_.push_back(
          {joint, ki > 0 ? ki / ri * volts : 0.0, damping, ki > 0 ? ki * imax : 1e30});
    joint->setCoulombFriction(0, fc);
  }

  void add_robot(const std::array<double, 2>& origin) {
    using namespace diffbot;
    // The chassis: brick and motor housings (massive), caster (massless), its frame at their
    // centre of mass, with the full inertia (the xz product included).
    double mass = 0;
    Eigen::Vector3d com = Eigen::Vector3d::Zero();
    for (const ChassisPart& p : kChassisParts) {
      mass += p.mass_kg;
      com += p.mass_kg * vec(p.centre_m);
    }
    com /= mass;
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
    for (const ChassisPart& p : kChassisParts) {
      const Eigen::Vector3d d = vec(p.centre_m) - com;
      inertia += box_inertia(p.mass_kg, p.size_m) +
                 p.mass_kg * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
    }

    auto robot = Skeleton::create("robot" + std::to_string(world_->getNumSkeletons()));
    const Eigen::Vector3d base(origin[0] + com.x(), origin[1] + com.y(), com.z());
    dart::dynamics::FreeJoint::Properties free;
    free.mT_ParentBodyToJoint = translation(base);
    free.mName = "free";
    BodyNode* chassis =
        robot->createJointAndBodyNodePair<dart::dynamics::FreeJoint>(nullptr, free).second;
    chassis->setName("chassis");
    chassis->setInertia(dart::dynamics::Inertia(mass, Eigen::Vector3d::Zero(), inertia));
    for (const ChassisPart& p : kChassisParts)
      add_shape(chassis, std::make_shared<dart::dynamics::BoxShape>(vec(p.size_m)),
                translation(vec(p.centre_m) - com), -1);
    add_shape(chassis, std::make_shared<dart::dynamics::SphereShape>(kCasterRadius_m),
              translation(vec(kCasterCentre_m) - com), 0.0);
    tracked_.push_back(chassis);

    // The wheels: right at −y turning about +y at +V, left at +y about −y at −V.
    const double r = kWheelRadius_m, w = kWheelWidth_m;
    const Eigen::Matrix3d wheel_inertia = Eigen::Vector3d(kWheelMass_kg * (3 * r * r + w * w) / 12,
                                                          kWheelMass_kg * r * r / 2 + kRotorJ_kgm2,
                                                          kWheelMass_kg * (3 * r * r + w * w) / 12)
                                              .asDiagonal();
    Eigen::Isometry3d axle_along_y = Eigen::Isometry3d::Identity();  // the cylinder's axis is z
    axle_along_y.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).matrix();
    for (double side : {-1.0, 1.0}) {
      const Eigen::Vector3d centre(origin[0], origin[1] + side * kHalfTrack_m, r);
      dart::dynamics::RevoluteJoint::Properties hinge;
      hinge.mName = side < 0 ? "axle_right" : "axle_left";
      hinge.mAxis = Eigen::Vector3d(0, -side, 0);
      hinge.mT_ParentBodyToJoint = translation(centre - base);
      auto [joint, wheel] =
          robot->createJointAndBodyNodePair<dart::dynamics::RevoluteJoint>(chassis, hinge);
      wheel->setName(side < 0 ? "wheel_right" : "wheel_left");
      wheel->setInertia(
          dart::dynamics::Inertia(kWheelMass_kg, Eigen::Vector3d::Zero(), wheel_inertia));
      add_shape(wheel, std::make_shared<dart::dynamics::CylinderShape>(r, w), axle_along_y,
                kWheelMu);
      add_drive(joint, kMotorKi_Nm_A, kMotorRi_ohm, kMotorImax_A, kFrictionBv_Nms, kFrictionFc_Nm,
                side < 0 ? scene_.robot_volts : -scene_.robot_volts);
    }
    // A robot's own parts never touch (ODE: the wheels are hinged to the chassis, the caster
    // and the boxes are one body), so its self-collision stays off, DART's default.
    world_->addSkeleton(robot);
  }

  void add_pile_body(const PileBody& b) {
    auto skeleton = Skeleton::create(b.name);
    dart::dynamics::FreeJoint::Properties free;
    free.mT_ParentBodyToJoint = translation(vec(b.position_m));
    free.mT_ParentBodyToJoint.linear() =
        Eigen::Quaterniond(b.quat_wxyz[0], b.quat_wxyz[1], b.quat_wxyz[2], b.quat_wxyz[3])
            .normalized()
            .toRotationMatrix();
    BodyNode* body =
        skeleton->createJointAndBodyNodePair<dart::dynamics::FreeJoint>(nullptr, free).second;
    const Vec3d& h = b.half_size_m;
    if (b.sphere) {
      const double moment = 0.4 * b.mass_kg * h[0] * h[0];
      body->setInertia(dart::dynamics::Inertia(b.mass_kg, Eigen::Vector3d::Zero(),
                                               moment * Eigen::Matrix3d::Identity()));
      add_shape(body, std::make_shared<dart::dynamics::SphereShape>(h[0]),
                Eigen::Isometry3d::Identity(), -1);
    } else {
      const Vec3d size{2 * h[0], 2 * h[1], 2 * h[2]};
      body->setInertia(dart::dynamics::Inertia(b.mass_kg, Eigen::Vector3d::Zero(),
                                               box_inertia(b.mass_kg, size)));
      add_shape(body, std::make_shared<dart::dynamics::BoxShape>(vec(size)),
                Eigen::Isometry3d::Identity(), -1);
    }
    world_->addSkeleton(skeleton);
    tracked_.push_back(body);
  }

  void add_articulated(const ArticulatedModel& model) {
    const int n = static_cast<int>(model.bodies.size());
    const SpanningTree tree = spanning_tree(model, "DART: " + scene_.name);
    const std::vector<int>& joint_of = tree.joint_of;
    std::vector<int> order = tree.order;  // the floating base first
    if (!tree.fixed) order.insert(order.begin(), 0);

    std::vector<Eigen::Matrix3d> inertia;
    for (const BoxBody& b : model.bodies)
      inertia.push_back(box_inertia(b.mass_kg, b.size_m));
    for (const HingeSpec& h : model.hinges)  // the rotor's inertia about the axis, on the child
      inertia[static_cast<std::size_t>(h.child)] +=
          h.rotor_J_kgm2 * vec(h.axis) * vec(h.axis).transpose();
    auto centre = [&](int body) {
      return body < 0 ? Eigen::Vector3d::Zero()
                      : vec(model.bodies[static_cast<std::size_t>(body)].centre_m);
    };

    auto skeleton = Skeleton::create(scene_.name);
    std::vector<BodyNode*> nodes(static_cast<std::size_t>(n), nullptr);
    for (const int body : order) {
      const auto b = static_cast<std::size_t>(body);
      BodyNode* node = nullptr;
      if (joint_of[b] < 0) {  // the floating base
        dart::dynamics::FreeJoint::Properties free;
        free.mName = "free";
        free.mT_ParentBodyToJoint = translation(centre(body));
        node =
            skeleton->createJointAndBodyNodePair<dart::dynamics::FreeJoint>(nullptr, free).second;
      } else {
        const HingeSpec& h = model.hinges[static_cast<std::size_t>(joint_of[b])];
        dart::dynamics::RevoluteJoint::Properties hinge;
        hinge.mName = h.name;
        hinge.mAxis = vec(h.axis);
        hinge.mT_ParentBodyToJoint = translation(vec(h.anchor_m) - centre(h.parent));
        hinge.mT_ChildBodyToJoint = translation(vec(h.anchor_m) - centre(body));
        BodyNode* parent = h.parent < 0 ? nullptr : nodes[static_cast<std::size_t>(h.parent)];
        auto [joint, child] =
            skeleton->createJointAndBodyNodePair<dart::dynamics::RevoluteJoint>(parent, hinge);
        add_drive(joint, h.ki_Nm_A, h.ri_ohm, h.imax_A, h.bv_Nms, h.fc_Nm, h.volts);
        node = child;
      }
      node->setName(model.bodies[b].name);
      node->setInertia(
          dart::dynamics::Inertia(model.bodies[b].mass_kg, Eigen::Vector3d::Zero(), inertia[b]));
      add_shape(node, std::make_shared<dart::dynamics::BoxShape>(vec(model.bodies[b].size_m)),
                Eigen::Isometry3d::Identity(), -1);
      nodes[b] = node;
    }
    skeleton->setSelfCollisionCheck(true);
    skeleton->setAdjacentBodyCheck(false);  // a hinge's two bodies do not touch
    world_->addSkeleton(skeleton);

    // The loops: a skeleton is a tree, so the fourth hinge of the arm is a
    // BallJointConstraint at its anchor (as Bullet's point-to-point). Every hinge axis of the
    // four-bar is parallel: the tree already keeps the bodies in their plane, and the ball is
    // the hinge's whole remaining content.
    auto* filter = dynamic_cast<dart::collision::BodyNodeCollisionFilter*>(
        world_->getConstraintSolver()->getCollisionOption().collisionFilter.get());
    for (std::size_t k = 0; k < model.hinges.size(); ++k) {
      const HingeSpec& h = model.hinges[k];
      if (joint_of[static_cast<std::size_t>(h.child)] == static_cast<int>(k)) continue;
      if (h.ki_Nm_A > 0 || h.fc_Nm > 0 || h.bv_Nms > 0)
        throw std::runtime_error("DART: the loop hinge " + h.name + " of " + scene_.name +
                                 " has a drive, which a ball constraint cannot carry");
      BodyNode* child = nodes[static_cast<std::size_t>(h.child)];
      std::shared_ptr<dart::constraint::BallJointConstraint> loop;
      if (h.parent < 0) {
        loop = std::make_shared<dart::constraint::BallJointConstraint>(child, vec(h.anchor_m));
      } else {
        BodyNode* parent = nodes[static_cast<std::size_t>(h.parent)];
        loop =
            std::make_shared<dart::constraint::BallJointConstraint>(child, parent, vec(h.anchor_m));
        if (filter == nullptr)
          throw std::runtime_error("DART: the world's collision filter is not a body-pair one");
        filter->addBodyNodePairToBlackList(child, parent);
      }
      world_->getConstraintSolver()->addConstraint(loop);
    }
    const int tracked_body = scene_.kind == SceneSpec::Kind::humanoid ? 0 : n - 1;
    tracked_.push_back(nodes[static_cast<std::size_t>(tracked_body)]);
  }

  SceneSpec scene_;
  bool fcl_;
  std::shared_ptr<dart::simulation::World> world_;
  std::vector<Drive> drives_;
  std::vector<const BodyNode*> tracked_;
};

}  // namespace

std::unique_ptr<Engine> make_dart(const SceneSpec& scene) {
  return std::make_unique<DartEngine>(scene, false);
}
std::unique_ptr<Engine> make_dart_fcl(const SceneSpec& scene) {
  return std::make_unique<DartEngine>(scene, true);
}

}  // namespace peers
