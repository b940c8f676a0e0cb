/// \file
/// Synthesises the drive-train components of every axis (see the header).

#include "sim/drive_train_components.hpp"

#include <cstdio>
#include <memory>

namespace s2sim::sim {
namespace {

/// Exact decimal text of a double (round-trips through the expression parser).
std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}
std::string flag(bool b) {
  return b ? "1" : "0";
}

scene::Element child(const std::string& parent_path, const std::string& name,
                     const std::string& suffix,
                     std::vector<std::pair<std::string, std::string>> attributes) {
  scene::Element e;
  e.name = name;
  e.attributes = std::move(attributes);
  e.path = parent_path + "/" + name + suffix;  // where the user writes it: motor, motor2...
  return e;
}

const char* mode_name(scene::ControllerMode m) {
  switch (m) {
    case scene::ControllerMode::pid_speed:
      return "pidspeed";
    case scene::ControllerMode::pid_position:
      return "pidposition";
    case scene::ControllerMode::state:
      return "state";
  }
  return "pidspeed";
}

}  // namespace

scene::ParamSource drive_train_params(const scene::Scene& scene, const DriveAxis& axis) {
  const scene::Joint& jt = scene.joints.at(static_cast<std::size_t>(axis.joint));
  const scene::DriveTrain& d = axis.which == 0 ? jt.drive1 : jt.drive2;
  const scene::Limits& limits = axis.which == 0 ? jt.limits1 : jt.limits2;
  const bool wrap = (axis.which == 0 ? jt.wrap1 : jt.wrap2) && !axis.linear && !limits.active;
  const std::string suffix = axis.which == 0 ? "" : "2";
  const std::string& at = jt.where.element;

  scene::ParamSource p;
  p.file = jt.where.file;
  scene::Element& e = p.element;
  e.name = "drive_train";
  e.path = at;
  e.attributes = {{"axis", axis.prefix},
                  {"linear", flag(axis.linear)},
                  {"wheel", flag(jt.from_wheels)},
                  {"wrap", flag(wrap)}};
  const scene::Motor& m = d.motor;
  e.children.push_back(child(at, "motor", suffix,
                             {{"ri", num(m.resistance_ohm)},
                              {"li", num(m.inductance_H)},
                              {"ki", num(m.torque_constant_Nm_A)},
                              {"vmax", num(m.voltage_max_V)},
                              {"imax", num(m.current_max_A)},
                              {"active", flag(m.active)},
                              {"simple", flag(m.simple)},
                              {"backemf", m.back_emf_simtwo ? "simtwo" : "physical"}}));
  const scene::Gear& g = d.gear;
  e.children.push_back(child(at, "gear", suffix,
                             {{"ratio", num(g.ratio)},
                              {"ke", num(g.ke)},
                              {"be", num(g.be)},
                              {"ke2", num(g.ke2)},
                              {"kv2", num(g.kv2)}}));
  e.children.push_back(child(at, "rotor", suffix,
                             {{"J", num(d.rotor.inertia_kg_m2)},
                              {"bv", num(d.rotor.viscous_Nms_rad)},
                              {"fc", num(d.rotor.coulomb_Nm)}}));
  const double encoder_period_s =
      d.encoder.period_s > 0 ? d.encoder.period_s : scene.settings.control_period_s;
  e.children.push_back(child(at, "encoder", suffix,
                             {{"ppr", num(static_cast<double>(d.encoder.ppr))},
                              {"mean", num(d.encoder.mean)},
                              {"stdev", num(d.encoder.stdev)},
                              {"period", num(encoder_period_s * 1000.0)}}));
  const scene::MotorController& k = d.controller;
  e.children.push_back(child(at, "controller", suffix,
                             {{"mode", mode_name(k.mode)},
                              {"kp", num(k.kp)},
                              {"ki", num(k.ki)},
                              {"kd", num(k.kd)},
                              {"kf", num(k.kf)},
                              {"period", num(k.period_s * 1000.0)},
                              {"active", flag(k.active)},
                              {"law", k.simtwo_law ? "simtwo" : "textbook"}}));
  e.children.push_back(child(at, "friction", suffix,
                             {{"bv", num(d.friction.viscous)}, {"fc", num(d.friction.coulomb)}}));
  e.children.push_back(
      child(at, "spring", suffix,
            {{"k", num(d.spring.stiffness)}, {"zeropos", num(d.spring.zero_position)}}));
  p.constants = std::make_shared<const scene::ConstantTable>();
  return p;
}

std::vector<AxisComponent> drive_train_components(const scene::Scene& scene,
                                                  const std::vector<DriveAxis>& axes) {
  std::vector<AxisComponent> out;
  for (const DriveAxis& ax : axes) {
    const scene::ParamSource params = drive_train_params(scene, ax);
    const scene::Joint& jt = scene.joints.at(static_cast<std::size_t>(ax.joint));
    for (const char* kind : kDriveTrainKinds) {
      AxisComponent c;
      c.kind = kind;
      c.id = ax.name + "/" + kind;
      c.prefix = ax.prefix + "/" + kind;
      c.robot = ax.robot;
      c.params = params;
      c.where = jt.where;
      out.push_back(std::move(c));
    }
  }
  return out;
}

}  // namespace s2sim::sim
