/// \file
/// Synthesises the drive-train components of every axis (see the header).

#include "sim/drive_train_components.hpp"
#include "sim/names.hpp"

#include <cstdio>

namespace s2sim::sim {
namespace {

std::string flag(bool b) {
  return b ? "1" : "0";
}

}  // namespace

scene::ParamSource drive_train_params(const scene::Scene& scene, const DriveAxis& axis) {
  const scene::Joint& jt = scene.joints.at(static_cast<std::size_t>(axis.joint));
  const scene::Limits& limits = axis.which == 0 ? jt.limits1 : jt.limits2;
  const bool wrap = (axis.which == 0 ? jt.wrap1 : jt.wrap2) && !axis.linear && !limits.active;

  scene::ParamSource p = axis.which == 0 ? jt.drive1 : jt.drive2;  // the elements as written
  if (p.file.empty()) p.file = jt.where.file;
  scene::Element& e = p.element;
  e.name = "drive_train";
  e.path = jt.where.element;
  e.attributes = {
      {"axis", axis.prefix},
      {"linear", flag(axis.linear)},
      {"wheel", flag(jt.from_wheels)},
      {"wrap", flag(wrap)},
      {"control_period", exact_decimal(scene.settings.control_period_s * 1000.0)},
      {"semantics",
       scene.settings.control_semantics == scene::ControlSemantics::simtwo ? "simtwo" : "s2sim"}};
  e.attribute_paths.clear();
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
