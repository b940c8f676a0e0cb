#pragma once
/// \file
/// buoyancy: the lift of a fluid on a body (docs/models/fluids.md).
///
/// Physical form (S2Sim scenes): ρ·g·V_immersed upward at the centroid of the immersed part of
/// a box, cylinder (along the hull's local Z) or sphere hull, below a horizontal surface at
/// z = `surface_z` (absent: the body is wholly in the fluid, e.g. a blimp in air):
///
///     <plugin kind='buoyancy' id='float' body='hull' hull='box' size_x='1' size_y='0.5'
///             size_z='0.3' density='1000' surface_z='0'>
///       <center x='0' y='0' z='0'/>   <!-- hull centre, body frame -->
///     </plugin>
///
/// `hull='cylinder'` takes `radius` and `length`, `hull='sphere'` takes `radius`.
/// SimTwo's form (`semantics='simtwo'`, made by the kernel for a solid's `<buoyant>`): the
/// weight of `mass` reversed in sign, mass·(0, 0, −g), at the body-frame point `point_x/_y/_z`
/// (a negative mass lifts; simtwo-format.md §4.4).
///
/// Signals `force` (N, upward), `volume` (m³ immersed), `immersed_fraction` (0..1). A surface
/// is shown to the viewer (StepContext::show_liquid_surface).

#include "common.hpp"
#include "immersion.hpp"

namespace s2sim::fluids {

class Buoyancy final : public Component {
 public:
  enum class Hull { box, cylinder, sphere };

  void configure(ConfigureContext& ctx) override {
    ctx.refuse_unread_attributes();  // a misspelt coefficient would leave its default
    const Params& p = ctx.params();
    body_ = ctx.body(p.text("body"));
    if (body_.index == 0) throw bad_value(p, "body", "the world does not float");
    simtwo_ = simtwo_semantics(p);
    if (simtwo_) {
      simtwo_mass_ = p.number("mass", 0.0);
      center_ = Vec3{p.number("point_x", 0.0), p.number("point_y", 0.0), p.number("point_z", 0.0)};
    } else {
      const std::string hull = p.choice("hull", {"box", "cylinder", "sphere"}, "box");
      hull_ = hull == "box" ? Hull::box : hull == "cylinder" ? Hull::cylinder : Hull::sphere;
      const Range pos = Range::positive();
      if (hull_ == Hull::box) {
        size_ = {p.number("size_x", pos), p.number("size_y", pos), p.number("size_z", pos)};
        full_volume_ = size_.x * size_.y * size_.z;
      } else {
        radius_ = p.number("radius", pos);
        length_ = hull_ == Hull::cylinder ? p.number("length", pos) : 0;
        full_volume_ = hull_ == Hull::cylinder ? kPi * radius_ * radius_ * length_
                                               : 4.0 / 3.0 * kPi * radius_ * radius_ * radius_;
      }
      density_ = p.number("density", 1000.0, Range::non_negative());
      surface_z_ = p.number("surface_z", std::numeric_limits<double>::infinity());
      center_ = p.vec3("center");
    }
    force_ = ctx.declare_signal("force", "N");
    volume_ = ctx.declare_signal("volume", "m^3");
    fraction_ = ctx.declare_signal("immersed_fraction", "1");
    ctx.set_schedule(Stage::actuate, ctx.tick_s());
  }

  void initialize(StepContext& ctx) override {
    // The viewer draws the surface the body floats on (water blue, see-through).
    if (!simtwo_ && std::isfinite(surface_z_))
      ctx.show_liquid_surface(surface_z_, 0.18, 0.42, 0.62, 0.45);
  }

  void update(StepContext& ctx) override {
    const Pose& pose = ctx.body_pose(body_);
    if (simtwo_) {
      const double lift = -simtwo_mass_ * kGravity_m_s2;
      ctx.apply_force(body_, {0, 0, lift}, pose * center_);
      ctx.publish(force_, lift);
      return;
    }
    const Pose hull{pose * center_, pose.rotation};
    Immersion im;
    if (std::isinf(surface_z_)) {
      im.volume_m3 = full_volume_;
      im.centroid_m = hull.position;
    } else if (hull_ == Hull::box) {
      im = immersed_box(hull, size_, surface_z_);
    } else if (hull_ == Hull::cylinder) {
      im = immersed_cylinder(hull, radius_, length_, surface_z_);
    } else {
      im = immersed_sphere(hull.position, radius_, surface_z_);
    }
    const double lift = density_ * kGravity_m_s2 * im.volume_m3;
    if (im.volume_m3 > 0) ctx.apply_force(body_, {0, 0, lift}, im.centroid_m);
    ctx.publish(force_, lift);
    ctx.publish(volume_, im.volume_m3);
    ctx.publish(fraction_, im.volume_m3 / full_volume_);
  }

 private:
  BodyHandle body_;
  bool simtwo_ = false;
  Hull hull_ = Hull::box;
  Vec3 size_, center_;
  double radius_ = 0, length_ = 0, full_volume_ = 1, density_ = 0, surface_z_ = 0;
  double simtwo_mass_ = 0;
  SignalHandle force_, volume_, fraction_;
};

}  // namespace s2sim::fluids
