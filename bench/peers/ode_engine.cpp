// ODE 0.16 in the peer benchmark, built through its C API from the scene's numbers: the robot of
// peer_model.hpp, the pile's MJCF bodies, the articulated models' tables. Two steppers:
// dWorldQuickStep with 20 iterations and the exact dWorldStep, both at 1 ms.
//
// The same laws as the other engines: contacts are spring-dampers at 300 rad/s, critically
// damped for the lighter body (ODE's soft ERP/CFM); a DC motor's torque Ks/Ri·V − (Ks²/Ri + bv)·ω
// within ±Ks·imax is the hinge's own motor row with a velocity target and a CFM of
// 1/(Ks²/Ri + bv), which ODE solves implicitly; Coulomb friction fc is an angular motor at
// zero speed bounded by fc.
#include "engine.hpp"
#include "peer_model.hpp"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <stdexcept>

namespace peers {
namespace {

constexpr double kStep_s = 0.001;
constexpr int kQuickStepIterations = 20;
constexpr int kMaxContactsPerPair = 8;

/// dInitODE2 once for the process.
void init_ode_once() {
  static const bool done = [] {
    dInitODE2(0);
    return true;
  }();
  (void)done;
}

class OdeEngine final : public Engine {
 public:
  OdeEngine(const SceneSpec& scene, bool quick) : scene_(scene), quick_(quick) {
    init_ode_once();
    build();
  }
  ~OdeEngine() override { destroy(); }
  OdeEngine(const OdeEngine&) = delete;
  OdeEngine& operator=(const OdeEngine&) = delete;

  void reset() override {
    destroy();
    build();
  }

  void step(long steps) override {
    for (long i = 0; i < steps; ++i) {
      deepest_m_ = 0;
      dSpaceCollide(space_, this, &OdeEngine::near_callback);
      if (quick_)
        dWorldQuickStep(world_, kStep_s);
      else
        dWorldStep(world_, kStep_s);
      dJointGroupEmpty(contacts_);
    }
  }

  double deepest_penetration_m() const override { return deepest_m_; }
  int tracked_count() const override { return static_cast<int>(tracked_.size()); }
  TrackedPose tracked(int index) const override {
    const dBodyID body = tracked_[static_cast<std::size_t>(index)];
    const dReal* p = dBodyGetPosition(body);
    const dReal* r = dBodyGetRotation(body);  // 3 x 4, row-major
    TrackedPose out;
    out.position_m = {p[0], p[1], p[2]};
    out.yaw_rad = std::atan2(r[4], r[0]);
    return out;
  }

 private:
  void build() {
    world_ = dWorldCreate();
    dWorldSetGravity(world_, 0, 0, -9.81);
    dWorldSetQuickStepNumIterations(world_, kQuickStepIterations);
    space_ = dHashSpaceCreate(nullptr);
    contacts_ = dJointGroupCreate(0);
    dCreatePlane(space_, 0, 0, 1, 0);  // no surface of its own: the other's friction applies
    add_scene_bodies(
        scene_, [&](const std::array<double, 2>& xy) { add_robot(xy); },
        [&](const PileBody& b) { add_pile_body(b); },
        [&](const ArticulatedModel& model) { add_articulated(model); });
  }

  void destroy() {
    if (world_ == nullptr) return;
    dJointGroupDestroy(contacts_);
    dSpaceDestroy(space_);  // destroys its geoms
    dWorldDestroy(world_);  // and its bodies and joints
    world_ = nullptr;
    tracked_.clear();
    surface_mu_.clear();
  }

  /// The geom's friction coefficient, or none (negative): the other surface's, or kDefaultMu.
  void set_mu(dGeomID geom, double mu) {
    surface_mu_.push_back(mu);
    dGeomSetData(geom, &surface_mu_.back());
  }

  /// A DC motor on `hinge` (torque about `axis` on its first body), with Coulomb friction.
  void add_drive(dJointID hinge, dBodyID b1, dBodyID b2, const Vec3d& axis, double ki, double ri,
                 double imax, double bv, double fc, double volts) {
    const double damping = (ki > 0 ? ki * ki / ri : 0.0) + bv;
    if (damping > 0) {
      const double source_Nm = ki > 0 ? ki / ri * volts : 0.0;
      dJointSetHingeParam(hinge, dParamVel, source_Nm / damping);
      dJointSetHingeParam(hinge, dParamFMax, ki > 0 ? ki * imax : 1e9);
      dJointSetHingeParam(hinge, dParamCFM, 1.0 / damping);
    }
    if (fc > 0) {
      dJointID brake = dJointCreateAMotor(world_, nullptr);
      dJointAttach(brake, b1, b2);
      dJointSetAMotorMode(brake, dAMotorUser);
      dJointSetAMotorNumAxes(brake, 1);
      dJointSetAMotorAxis(brake, 0, 1, axis[0], axis[1], axis[2]);
      dJointSetAMotorParam(brake, dParamVel, 0);
      dJointSetAMotorParam(brake, dParamFMax, fc);
    }
  }

  void add_robot(const std::array<double, 2>& origin) {
    using namespace diffbot;
    // The chassis: brick and motor housings (massive), caster (massless); ODE wants the body
    // frame at the centre of mass.
    dMass total, part;
    dMassSetZero(&total);
    dMassSetBoxTotal(&part, kBrickMass_kg, kBrickSize_m[0], kBrickSize_m[1], kBrickSize_m[2]);
    dMassTranslate(&part, kBrickCentre_m[0], kBrickCentre_m[1], kBrickCentre_m[2]);
    dMassAdd(&total, &part);
    for (double side : {1.0, -1.0}) {
      dMassSetBoxTotal(&part, kHousingMass_kg, kHousingSize_m[0], kHousingSize_m[1],
                       kHousingSize_m[2]);
      dMassTranslate(&part, kHousingCentre_m[0], side * kHousingCentre_m[1], kHousingCentre_m[2]);
      dMassAdd(&total, &part);
    }
    const Vec3d com{total.c[0], total.c[1], total.c[2]};
    dMassTranslate(&total, -com[0], -com[1], -com[2]);
    dBodyID chassis = dBodyCreate(world_);
    dBodySetMass(chassis, &total);
    dBodySetPosition(chassis, origin[0] + com[0], origin[1] + com[1], com[2]);
    auto attach = [&](dGeomID g, const Vec3d& centre, double mu) {
      dGeomSetBody(g, chassis);
      dGeomSetOffsetPosition(g, centre[0] - com[0], centre[1] - com[1], centre[2] - com[2]);
      set_mu(g, mu);
    };
    attach(dCreateBox(space_, kBrickSize_m[0], kBrickSize_m[1], kBrickSize_m[2]), kBrickCentre_m,
           -1);
    for (double side : {1.0, -1.0})
      attach(dCreateBox(space_, kHousingSize_m[0], kHousingSize_m[1], kHousingSize_m[2]),
             {kHousingCentre_m[0], side * kHousingCentre_m[1], kHousingCentre_m[2]}, -1);
    attach(dCreateSphere(space_, kCasterRadius_m), kCasterCentre_m, 0.0);
    tracked_.push_back(chassis);

    // The wheels: right at −y turning about +y at +V, left at +y about −y at −V.
    for (double side : {-1.0, 1.0}) {
      dBodyID wheel = dBodyCreate(world_);
      dMass m;
      dMassSetCylinderTotal(&m, kWheelMass_kg, 2, kWheelRadius_m, kWheelWidth_m);
      m.I[1 * 4 + 1] += kRotorJ_kgm2;  // the rotor's inertia about the axle (MuJoCo's armature)
      dBodySetMass(wheel, &m);
      dBodySetPosition(wheel, origin[0], origin[1] + side * kHalfTrack_m, kWheelRadius_m);
      dGeomID tyre = dCreateCylinder(space_, kWheelRadius_m, kWheelWidth_m);
      dGeomSetBody(tyre, wheel);
      dMatrix3 r;
      dRFromAxisAndAngle(r, 1, 0, 0, M_PI / 2);  // the cylinder's axis (local z) along y
      dGeomSetOffsetRotation(tyre, r);
      set_mu(tyre, kWheelMu);
      const Vec3d axis{0, -side, 0};
      dJointID hinge = dJointCreateHinge(world_, nullptr);
      dJointAttach(hinge, wheel, chassis);
      dJointSetHingeAnchor(hinge, origin[0], origin[1] + side * kHalfTrack_m, kWheelRadius_m);
      dJointSetHingeAxis(hinge, axis[0], axis[1], axis[2]);
      add_drive(hinge, wheel, chassis, axis, kMotorKi_Nm_A, kMotorRi_ohm, kMotorImax_A,
                kFrictionBv_Nms, kFrictionFc_Nm,
                side < 0 ? scene_.robot_volts : -scene_.robot_volts);
    }
  }

  void add_pile_body(const PileBody& b) {
    dBodyID body = dBodyCreate(world_);
    dMass m;
    dGeomID geom;
    if (b.sphere) {
      dMassSetSphereTotal(&m, b.mass_kg, b.half_size_m[0]);
      geom = dCreateSphere(space_, b.half_size_m[0]);
    } else {
      dMassSetBoxTotal(&m, b.mass_kg, 2 * b.half_size_m[0], 2 * b.half_size_m[1],
                       2 * b.half_size_m[2]);
      geom = dCreateBox(space_, 2 * b.half_size_m[0], 2 * b.half_size_m[1], 2 * b.half_size_m[2]);
    }
    dBodySetMass(body, &m);
    dBodySetPosition(body, b.position_m[0], b.position_m[1], b.position_m[2]);
    const dQuaternion q{b.quat_wxyz[0], b.quat_wxyz[1], b.quat_wxyz[2], b.quat_wxyz[3]};
    dBodySetQuaternion(body, q);
    dGeomSetBody(geom, body);
    set_mu(geom, -1);
    tracked_.push_back(body);
  }

  void add_articulated(const ArticulatedModel& model) {
    std::vector<dBodyID> bodies;
    std::vector<dMass> masses;
    for (const BoxBody& b : model.bodies) {
      dBodyID body = dBodyCreate(world_);
      dMass m;
      dMassSetBoxTotal(&m, b.mass_kg, b.size_m[0], b.size_m[1], b.size_m[2]);
      masses.push_back(m);
      dBodySetPosition(body, b.centre_m[0], b.centre_m[1], b.centre_m[2]);
      dGeomID geom = dCreateBox(space_, b.size_m[0], b.size_m[1], b.size_m[2]);
      dGeomSetBody(geom, body);
      set_mu(geom, -1);
      bodies.push_back(body);
    }
    for (const HingeSpec& h : model.hinges) {  // rotor inertia about the axis, on the child
      dMass& m = masses[static_cast<std::size_t>(h.child)];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          m.I[r * 4 + c] += h.rotor_J_kgm2 * h.axis[r] * h.axis[c];
    }
    for (std::size_t i = 0; i < bodies.size(); ++i)
      dBodySetMass(bodies[i], &masses[i]);
    for (const HingeSpec& h : model.hinges) {
      dBodyID child = bodies[static_cast<std::size_t>(h.child)];
      dBodyID parent = h.parent < 0 ? nullptr : bodies[static_cast<std::size_t>(h.parent)];
      dJointID hinge = dJointCreateHinge(world_, nullptr);
      dJointAttach(hinge, child, parent);
      dJointSetHingeAnchor(hinge, h.anchor_m[0], h.anchor_m[1], h.anchor_m[2]);
      dJointSetHingeAxis(hinge, h.axis[0], h.axis[1], h.axis[2]);
      add_drive(hinge, child, parent, h.axis, h.ki_Nm_A, h.ri_ohm, h.imax_A, h.bv_Nms, h.fc_Nm,
                h.volts);
    }
    tracked_.push_back(scene_.kind == SceneSpec::Kind::humanoid ? bodies.front() : bodies.back());
  }

  static void near_callback(void* self, dGeomID a, dGeomID b) {
    static_cast<OdeEngine*>(self)->collide(a, b);
  }

  void collide(dGeomID ga, dGeomID gb) {
    dBodyID a = dGeomGetBody(ga), b = dGeomGetBody(gb);
    if (a == b) return;  // static against static, or one body's own geoms
    if (a != nullptr && b != nullptr && dAreConnectedExcluding(a, b, dJointTypeContact)) return;
    dContact contact[kMaxContactsPerPair]{};
    const int n = dCollide(ga, gb, kMaxContactsPerPair, &contact[0].geom, sizeof(dContact));
    if (n == 0) return;
    const auto* mu_a = static_cast<const double*>(dGeomGetData(ga));
    const auto* mu_b = static_cast<const double*>(dGeomGetData(gb));
    const double ma = mu_a != nullptr ? *mu_a : -1, mb = mu_b != nullptr ? *mu_b : -1;
    const double mu = ma >= 0 && mb >= 0 ? std::sqrt(ma * mb)
                      : ma >= 0          ? ma
                      : mb >= 0          ? mb
                                         : kDefaultMu;
    // The spring-damper of the lighter body: k = m·ω², c = 2·m·ω.
    double mass = 1e30;
    for (dBodyID body : {a, b})
      if (body != nullptr) {
        dMass m;
        dBodyGetMass(body, &m);
        mass = std::min(mass, m.mass);
      }
    const double k = mass * kContactOmega_rad_s * kContactOmega_rad_s;
    const double c = 2 * mass * kContactOmega_rad_s;
    for (int i = 0; i < n; ++i) {
      dContact& ct = contact[i];
      ct.surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
      ct.surface.mu = mu;
      ct.surface.soft_erp = kStep_s * k / (kStep_s * k + c);
      ct.surface.soft_cfm = 1.0 / (kStep_s * k + c);
      deepest_m_ = std::max(deepest_m_, static_cast<double>(ct.geom.depth));
      dJointID joint = dJointCreateContact(world_, contacts_, &ct);
      dJointAttach(joint, a, b);
    }
  }

  SceneSpec scene_;
  bool quick_;
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID contacts_ = nullptr;
  std::vector<dBodyID> tracked_;
  std::deque<double> surface_mu_;  // stable addresses for dGeomSetData
  double deepest_m_ = 0;
};

}  // namespace

std::unique_ptr<Engine> make_ode_quickstep(const SceneSpec& scene) {
  return std::make_unique<OdeEngine>(scene, true);
}
std::unique_ptr<Engine> make_ode_worldstep(const SceneSpec& scene) {
  return std::make_unique<OdeEngine>(scene, false);
}

}  // namespace peers
