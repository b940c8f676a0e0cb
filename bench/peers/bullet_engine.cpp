// Bullet 3.24 in the peer benchmark, built from the scene's numbers as ODE is (peer_model.hpp):
// btMultiBody (Featherstone, reduced coordinates) for the robots, the humanoid and the arm, rigid
// bodies in a btDiscreteDynamicsWorld for the pile; one stepSimulation of 1 ms per step, the
// sequential-impulse solver at 20 iterations (as ode-quick20).
//
// The same laws as the other engines: contacts are spring-dampers at 300 rad/s, critically
// damped for the lighter body (Bullet's contact stiffness and damping, set per contact point);
// the friction coefficient is the geometric mean of the two surfaces', or the one set, or
// kDefaultMu; a DC motor's torque Ks/Ri·V − (Ks²/Ri + bv)·ω within ±Ks·imax is added to its
// joint before every step (explicit: Bullet has no implicit joint damper); Coulomb friction fc is
// a joint motor at zero speed whose impulse is bounded by fc·dt, as ODE's brake.
//
// The arm's loop: the tree is world–crank A–coupler and world–crank B; the fourth hinge is a
// point-to-point constraint. Every hinge axis is parallel, so the tree already keeps the bodies
// in the plane and the point constraint is the hinge's whole remaining content.
#include "engine.hpp"
#include "peer_model.hpp"

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <BulletDynamics/Featherstone/btMultiBodyPoint2Point.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

namespace peers {
namespace {

constexpr btScalar kStep_s = 0.001;
constexpr int kSolverIterations = 20;
/// Bullet's default margin (4 cm) is as large as the robot's parts; contacts are found at the
/// surfaces instead.
constexpr btScalar kMargin_m = 0.001;

/// What a collision shape's contacts need: its friction (negative: none of its own) and the
/// mass of its body (the ground's infinite).
struct Surface {
  double mu = -1;
  double mass_kg = 1e30;
};

/// Bullet combines surfaces by product and harmonic mean; the peers' rules are set on each new
/// or refreshed contact point instead (the shapes carry their Surface).
bool on_contact(btManifoldPoint& cp, const btCollisionObjectWrapper* a, int, int,
                const btCollisionObjectWrapper* b, int, int) {
  const auto* sa = static_cast<const Surface*>(a->getCollisionShape()->getUserPointer());
  const auto* sb = static_cast<const Surface*>(b->getCollisionShape()->getUserPointer());
  if (sa == nullptr || sb == nullptr) return false;
  const double ma = sa->mu, mb = sb->mu;
  cp.m_combinedFriction = static_cast<btScalar>(ma >= 0 && mb >= 0 ? std::sqrt(ma * mb)
                                                : ma >= 0          ? ma
                                                : mb >= 0          ? mb
                                                                   : kDefaultMu);
  const double mass = std::min(sa->mass_kg, sb->mass_kg);
  cp.m_combinedContactStiffness1 =
      static_cast<btScalar>(mass * kContactOmega_rad_s * kContactOmega_rad_s);
  cp.m_combinedContactDamping1 = static_cast<btScalar>(2 * mass * kContactOmega_rad_s);
  cp.m_contactPointFlags |= BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING;
  cp.m_combinedRestitution = 0;
  return true;
}

/// As ODE: bodies joined by a loop's hinge do not touch (btMultiBody skips only its tree's
/// parent and child; a link collider ignores setIgnoreCollisionCheck).
struct JoinedPairs final : btOverlapFilterCallback {
  std::vector<std::pair<const void*, const void*>> joined;
  bool needBroadphaseCollision(btBroadphaseProxy* a, btBroadphaseProxy* b) const override {
    if ((a->m_collisionFilterGroup & b->m_collisionFilterMask) == 0 ||
        (b->m_collisionFilterGroup & a->m_collisionFilterMask) == 0)
      return false;
    for (const auto& [p, q] : joined)
      if ((p == a->m_clientObject && q == b->m_clientObject) ||
          (p == b->m_clientObject && q == a->m_clientObject))
        return false;
    return true;
  }
};

/// A DC motor (ki = 0: passive) with its Coulomb friction, on joint `link` of `body`.
struct Drive {
  btMultiBody* body = nullptr;
  int link = 0;
  double source_Nm = 0, damping_Nms = 0, limit_Nm = 0;
};

class BulletEngine final : public Engine {
 public:
  explicit BulletEngine(const SceneSpec& scene) : scene_(scene) {
    gContactAddedCallback = &on_contact;
    build();
  }
  ~BulletEngine() override { destroy(); }
  BulletEngine(const BulletEngine&) = delete;
  BulletEngine& operator=(const BulletEngine&) = delete;

  void reset() override {
    destroy();
    build();
  }

  void step(long steps) override {
    for (long i = 0; i < steps; ++i) {
      for (const Drive& d : drives_) {
        const double w = d.body->getJointVel(d.link);
        const double torque = std::clamp(d.source_Nm - d.damping_Nms * w, -d.limit_Nm, d.limit_Nm);
        d.body->addJointTorque(d.link, static_cast<btScalar>(torque));
      }
      world_->stepSimulation(kStep_s, 0, kStep_s);  // one step of exactly 1 ms
    }
  }

  double deepest_penetration_m() const override {
    double deepest = 0;
    btDispatcher* dispatcher = world_->getDispatcher();
    for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
      const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
      for (int p = 0; p < manifold->getNumContacts(); ++p)
        deepest =
            std::max(deepest, -static_cast<double>(manifold->getContactPoint(p).getDistance()));
    }
    return deepest;
  }
  int tracked_count() const override { return static_cast<int>(tracked_.size()); }
  TrackedPose tracked(int index) const override {
    const btTransform& t = tracked_[static_cast<std::size_t>(index)]->getWorldTransform();
    TrackedPose out;
    out.position_m = {t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z()};
    const btMatrix3x3& r = t.getBasis();
    out.yaw_rad = std::atan2(r[1][0], r[0][0]);
    return out;
  }

 private:
  bool multibody() const { return scene_.kind != SceneSpec::Kind::pile; }

  void build() {
    config_ = std::make_unique<btDefaultCollisionConfiguration>();
    dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
    broadphase_ = std::make_unique<btDbvtBroadphase>();
    if (multibody()) {
      auto solver = std::make_unique<btMultiBodyConstraintSolver>();
      auto world = std::make_unique<btMultiBodyDynamicsWorld>(dispatcher_.get(), broadphase_.get(),
                                                              solver.get(), config_.get());
      mb_world_ = world.get();
      solver_ = std::move(solver);
      world_ = std::move(world);
    } else {
      solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
      world_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(),
                                                         solver_.get(), config_.get());
    }
    filter_.joined.clear();
    world_->getPairCache()->setOverlapFilterCallback(&filter_);
    world_->setGravity(btVector3(0, 0, -9.81));
    world_->getSolverInfo().m_numIterations = kSolverIterations;

    // The floor: no surface of its own, the other's friction applies.
    btCollisionShape* plane = keep(new btStaticPlaneShape(btVector3(0, 0, 1), 0), -1, 1e30);
    auto floor = std::make_unique<btCollisionObject>();
    floor->setCollisionShape(plane);
    floor->setCollisionFlags(floor->getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT |
                             btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
    world_->addCollisionObject(floor.get());
    objects_.push_back(std::move(floor));

    add_scene_bodies(
        scene_, [&](const std::array<double, 2>& xy) { add_robot(xy); },
        [&](const PileBody& b) { add_pile_body(b); },
        [&](const ArticulatedModel& model) { add_articulated(model); });
  }

  void destroy() {
    if (!world_) return;
    for (auto& c : constraints_)
      mb_world_->removeMultiBodyConstraint(c.get());
    for (auto& b : bodies_)
      mb_world_->removeMultiBody(b.get());
    for (int i = world_->getNumCollisionObjects() - 1; i >= 0; --i) {
      btCollisionObject* o = world_->getCollisionObjectArray()[i];
      if (auto* rb = btRigidBody::upcast(o))
        world_->removeRigidBody(rb);
      else
        world_->removeCollisionObject(o);
    }
    constraints_.clear();
    bodies_.clear();
    objects_.clear();
    world_.reset();
    mb_world_ = nullptr;
    solver_.reset();
    broadphase_.reset();
    dispatcher_.reset();
    config_.reset();
    shapes_.clear();
    surfaces_.clear();
    drives_.clear();
    tracked_.clear();
  }

  /// Owns `shape` and gives it its Surface and the small margin.
  btCollisionShape* keep(btCollisionShape* shape, double mu, double mass_kg) {
    shapes_.emplace_back(shape);
    surfaces_.push_back({mu, mass_kg});
    shape->setUserPointer(&surfaces_.back());
    if (shape->getShapeType() != SPHERE_SHAPE_PROXYTYPE) shape->setMargin(kMargin_m);
    return shape;
  }

  btMultiBody* new_multibody(int links, double mass, const btVector3& inertia, bool fixed) {
    bodies_.push_back(
        std::make_unique<btMultiBody>(links, static_cast<btScalar>(mass), inertia, fixed, false));
    btMultiBody* mb = bodies_.back().get();
    mb->setLinearDamping(0);  // Bullet damps by default; the other engines do not
    mb->setAngularDamping(0);
    mb->setHasSelfCollision(true);  // as ODE: only bodies joined by a hinge skip contact
    return mb;
  }

  /// A collider for link `link` (−1: the base) at `origin`, world-aligned.
  btMultiBodyLinkCollider* collide(btMultiBody* mb, int link, btCollisionShape* shape,
                                   const btVector3& origin) {
    auto col = std::make_unique<btMultiBodyLinkCollider>(mb, link);
    col->setCollisionShape(shape);
    col->setWorldTransform(btTransform(btQuaternion::getIdentity(), origin));
    col->setCollisionFlags(col->getCollisionFlags() |
                           btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
    if (link < 0)
      mb->setBaseCollider(col.get());
    else
      mb->getLink(link).m_collider = col.get();
    btMultiBodyLinkCollider* raw = col.get();
    world_->addCollisionObject(raw, btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
    objects_.push_back(std::move(col));
    return raw;
  }

  /// The motor law of `link`, and its Coulomb friction as a zero-speed motor bounded by fc·dt.
  void add_drive(btMultiBody* mb, int link, double ki, double ri, double imax, double bv, double fc,
                 double volts) {
    const double damping = (ki > 0 ? ki * ki / ri : 0.0) + bv;
    if (damping > 0)
      drives_.push_back(
          {mb, link, ki > 0 ? ki / ri * volts : 0.0, damping, ki > 0 ? ki * imax : 1e30});
    if (fc > 0) {
      constraints_.push_back(std::make_unique<btMultiBodyJointMotor>(
          mb, link, btScalar(0), static_cast<btScalar>(fc * kStep_s)));
      mb_world_->addMultiBodyConstraint(constraints_.back().get());
    }
  }

  void finish(btMultiBody* mb) {
    mb->finalizeMultiDof();
    mb_world_->addMultiBody(mb);
  }

  void add_robot(const std::array<double, 2>& origin) {
    using namespace diffbot;
    // The chassis: brick and motor housings (massive), caster (massless), about their centre
    // of mass. btMultiBody takes principal inertias: the xz product (6 % of Iyy, principal
    // axes 10° about y) is left out.
    double mass = 0;
    Vec3d com{};
    for (const ChassisPart& p : kChassisParts) {
      mass += p.mass_kg;
      for (int k = 0; k < 3; ++k)
        com[k] += p.mass_kg * p.centre_m[k];
    }
    for (double& c : com)
      c /= mass;
    btVector3 inertia(0, 0, 0);
    for (const ChassisPart& p : kChassisParts) {
      const Vec3d d{p.centre_m[0] - com[0], p.centre_m[1] - com[1], p.centre_m[2] - com[2]};
      const Vec3d& s = p.size_m;
      inertia += btVector3(
          static_cast<btScalar>(p.mass_kg *
                                ((s[1] * s[1] + s[2] * s[2]) / 12 + d[1] * d[1] + d[2] * d[2])),
          static_cast<btScalar>(p.mass_kg *
                                ((s[0] * s[0] + s[2] * s[2]) / 12 + d[0] * d[0] + d[2] * d[2])),
          static_cast<btScalar>(p.mass_kg *
                                ((s[0] * s[0] + s[1] * s[1]) / 12 + d[0] * d[0] + d[1] * d[1])));
    }
    btMultiBody* mb = new_multibody(2, mass, inertia, false);
    const btVector3 base(static_cast<btScalar>(origin[0] + com[0]),
                         static_cast<btScalar>(origin[1] + com[1]), static_cast<btScalar>(com[2]));
    mb->setBasePos(base);
    mb->setWorldToBaseRot(btQuaternion::getIdentity());

    auto* chassis = new btCompoundShape();
    keep(chassis, -1, mass);
    auto local = [&](const Vec3d& centre) {
      return btTransform(btQuaternion::getIdentity(),
                         btVector3(static_cast<btScalar>(centre[0] - com[0]),
                                   static_cast<btScalar>(centre[1] - com[1]),
                                   static_cast<btScalar>(centre[2] - com[2])));
    };
    for (const ChassisPart& p : kChassisParts)
      chassis->addChildShape(local(p.centre_m),
                             keep(new btBoxShape(btVector3(static_cast<btScalar>(p.size_m[0] / 2),
                                                           static_cast<btScalar>(p.size_m[1] / 2),
                                                           static_cast<btScalar>(p.size_m[2] / 2))),
                                  -1, mass));
    chassis->addChildShape(
        local(kCasterCentre_m),
        keep(new btSphereShape(static_cast<btScalar>(kCasterRadius_m)), 0.0, mass));
    tracked_.push_back(collide(mb, -1, chassis, base));

    // The wheels: right (link 0) at −y turning about +y at +V, left (link 1) at +y about −y at −V.
    const double r = kWheelRadius_m, w = kWheelWidth_m;
    const double axial = kWheelMass_kg * r * r / 2 + kRotorJ_kgm2;
    const double radial = kWheelMass_kg * (3 * r * r + w * w) / 12;
    int link = 0;
    for (double side : {-1.0, 1.0}) {
      const btVector3 centre(static_cast<btScalar>(origin[0]),
                             static_cast<btScalar>(origin[1] + side * kHalfTrack_m),
                             static_cast<btScalar>(r));
      mb->setupRevolute(link, static_cast<btScalar>(kWheelMass_kg),
                        btVector3(static_cast<btScalar>(radial), static_cast<btScalar>(axial),
                                  static_cast<btScalar>(radial)),
                        -1, btQuaternion::getIdentity(),
                        btVector3(0, static_cast<btScalar>(-side), 0), centre - base,
                        btVector3(0, 0, 0), true);
      // btCylinderShape's axis is local y, the axle's.
      btCollisionShape* tyre =
          keep(new btCylinderShape(btVector3(static_cast<btScalar>(r), static_cast<btScalar>(w / 2),
                                             static_cast<btScalar>(r))),
               kWheelMu, kWheelMass_kg);
      collide(mb, link, tyre, centre);
      add_drive(mb, link, kMotorKi_Nm_A, kMotorRi_ohm, kMotorImax_A, kFrictionBv_Nms,
                kFrictionFc_Nm, side < 0 ? scene_.robot_volts : -scene_.robot_volts);
      ++link;
    }
    finish(mb);
  }

  void add_pile_body(const PileBody& b) {
    btCollisionShape* shape;
    if (b.sphere)
      shape = keep(new btSphereShape(static_cast<btScalar>(b.half_size_m[0])), -1, b.mass_kg);
    else
      shape = keep(new btBoxShape(btVector3(static_cast<btScalar>(b.half_size_m[0]),
                                            static_cast<btScalar>(b.half_size_m[1]),
                                            static_cast<btScalar>(b.half_size_m[2]))),
                   -1, b.mass_kg);
    btVector3 inertia;
    shape->calculateLocalInertia(static_cast<btScalar>(b.mass_kg), inertia);
    const btTransform pose(
        btQuaternion(static_cast<btScalar>(b.quat_wxyz[1]), static_cast<btScalar>(b.quat_wxyz[2]),
                     static_cast<btScalar>(b.quat_wxyz[3]), static_cast<btScalar>(b.quat_wxyz[0])),
        btVector3(static_cast<btScalar>(b.position_m[0]), static_cast<btScalar>(b.position_m[1]),
                  static_cast<btScalar>(b.position_m[2])));
    btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(b.mass_kg), nullptr, shape,
                                                  inertia);
    info.m_startWorldTransform = pose;
    auto body = std::make_unique<btRigidBody>(info);
    body->setActivationState(DISABLE_DEACTIVATION);  // the others never put bodies to sleep
    body->setCollisionFlags(body->getCollisionFlags() |
                            btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
    world_->addRigidBody(body.get());
    tracked_.push_back(body.get());
    objects_.push_back(std::move(body));
  }

  void add_articulated(const ArticulatedModel& model) {
    const int n = static_cast<int>(model.bodies.size());
    const SpanningTree tree = spanning_tree(model, "Bullet: " + scene_.name);
    const std::vector<int>& joint_of = tree.joint_of;  // the tree hinge of each body
    const std::vector<int>& order = tree.order;        // bodies, parents first
    const bool fixed = tree.fixed;
    const int root = fixed ? -1 : 0;  // the floating base's body; the world when fixed to it

    std::vector<double> rotor_inertia(3 * static_cast<std::size_t>(n), 0.0);
    for (const HingeSpec& h : model.hinges)  // about the axis, on the child (axes are x, y or z)
      for (int k = 0; k < 3; ++k)
        rotor_inertia[3 * static_cast<std::size_t>(h.child) + static_cast<std::size_t>(k)] +=
            h.rotor_J_kgm2 * h.axis[static_cast<std::size_t>(k)] *
            h.axis[static_cast<std::size_t>(k)];
    auto box_inertia = [&](int body) {
      const BoxBody& b = model.bodies[static_cast<std::size_t>(body)];
      const Vec3d& s = b.size_m;
      const double* rot = &rotor_inertia[3 * static_cast<std::size_t>(body)];
      return btVector3(
          static_cast<btScalar>(b.mass_kg * (s[1] * s[1] + s[2] * s[2]) / 12 + rot[0]),
          static_cast<btScalar>(b.mass_kg * (s[0] * s[0] + s[2] * s[2]) / 12 + rot[1]),
          static_cast<btScalar>(b.mass_kg * (s[0] * s[0] + s[1] * s[1]) / 12 + rot[2]));
    };
    auto centre = [&](int body) {
      if (body < 0) return btVector3(0, 0, 0);
      const Vec3d& c = model.bodies[static_cast<std::size_t>(body)].centre_m;
      return btVector3(static_cast<btScalar>(c[0]), static_cast<btScalar>(c[1]),
                       static_cast<btScalar>(c[2]));
    };
    auto vec = [](const Vec3d& v) {
      return btVector3(static_cast<btScalar>(v[0]), static_cast<btScalar>(v[1]),
                       static_cast<btScalar>(v[2]));
    };

    const int links = static_cast<int>(order.size());
    btMultiBody* mb =
        fixed ? new_multibody(links, 1, btVector3(1, 1, 1), true)  // the base is the world
              : new_multibody(links, model.bodies[0].mass_kg, box_inertia(0), false);
    mb->setBasePos(centre(root));
    mb->setWorldToBaseRot(btQuaternion::getIdentity());
    std::vector<int> link_of(static_cast<std::size_t>(n), -1);  // −1: the base
    auto box = [&](int body) {
      const Vec3d& s = model.bodies[static_cast<std::size_t>(body)].size_m;
      return keep(
          new btBoxShape(btVector3(static_cast<btScalar>(s[0] / 2), static_cast<btScalar>(s[1] / 2),
                                   static_cast<btScalar>(s[2] / 2))),
          -1, model.bodies[static_cast<std::size_t>(body)].mass_kg);
    };
    std::vector<btCollisionObject*> collider(static_cast<std::size_t>(n), nullptr);
    if (!fixed) collider[0] = collide(mb, -1, box(0), centre(0));
    for (int link = 0; link < links; ++link) {
      const int body = order[static_cast<std::size_t>(link)];
      const HingeSpec& h =
          model.hinges[static_cast<std::size_t>(joint_of[static_cast<std::size_t>(body)])];
      link_of[static_cast<std::size_t>(body)] = link;
      const int parent_link = h.parent < 0 ? -1 : link_of[static_cast<std::size_t>(h.parent)];
      const btVector3 parent_centre = h.parent < 0 ? centre(root) : centre(h.parent);
      const btVector3 anchor = vec(h.anchor_m);
      mb->setupRevolute(link,
                        static_cast<btScalar>(model.bodies[static_cast<std::size_t>(body)].mass_kg),
                        box_inertia(body), parent_link, btQuaternion::getIdentity(), vec(h.axis),
                        anchor - parent_centre, centre(body) - anchor, true);
      collider[static_cast<std::size_t>(body)] = collide(mb, link, box(body), centre(body));
      add_drive(mb, link, h.ki_Nm_A, h.ri_ohm, h.imax_A, h.bv_Nms, h.fc_Nm, h.volts);
    }
    finish(mb);
    for (std::size_t k = 0; k < model.hinges.size(); ++k) {  // the loops' hinges
      const HingeSpec& h = model.hinges[k];
      if (joint_of[static_cast<std::size_t>(h.child)] == static_cast<int>(k)) continue;
      if (h.ki_Nm_A > 0 || h.fc_Nm > 0 || h.bv_Nms > 0)
        throw std::runtime_error("Bullet: the loop hinge " + h.name + " of " + scene_.name +
                                 " has a drive, which a point constraint cannot carry");
      const btVector3 anchor = vec(h.anchor_m);
      const int child_link = link_of[static_cast<std::size_t>(h.child)];
      const int parent_link = h.parent < 0 ? -1 : link_of[static_cast<std::size_t>(h.parent)];
      if (h.parent >= 0) {
        btCollisionObject* a = collider[static_cast<std::size_t>(h.child)];
        btCollisionObject* b = collider[static_cast<std::size_t>(h.parent)];
        filter_.joined.emplace_back(a, b);
        // The broadphase paired them when they were added.
        world_->getPairCache()->removeOverlappingPair(a->getBroadphaseHandle(),
                                                      b->getBroadphaseHandle(), dispatcher_.get());
      }
      constraints_.push_back(std::make_unique<btMultiBodyPoint2Point>(
          mb, child_link, mb, parent_link, anchor - centre(h.child),
          anchor - (h.parent < 0 ? centre(root) : centre(h.parent))));
      mb_world_->addMultiBodyConstraint(constraints_.back().get());
    }
    const int tracked_body = scene_.kind == SceneSpec::Kind::humanoid ? 0 : n - 1;
    tracked_.push_back(collider[static_cast<std::size_t>(tracked_body)]);
  }

  SceneSpec scene_;
  // Declared in the order Bullet needs them built; destroy() takes them down in reverse.
  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  btMultiBodyDynamicsWorld* mb_world_ = nullptr;  // world_, when the scene is jointed
  std::deque<Surface> surfaces_;                  // stable addresses for the shapes
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btMultiBody>> bodies_;
  std::vector<std::unique_ptr<btMultiBodyConstraint>> constraints_;
  std::vector<std::unique_ptr<btCollisionObject>> objects_;
  std::vector<Drive> drives_;
  JoinedPairs filter_;
  std::vector<const btCollisionObject*> tracked_;
};

}  // namespace

std::unique_ptr<Engine> make_bullet(const SceneSpec& scene) {
  return std::make_unique<BulletEngine>(scene);
}

}  // namespace peers
