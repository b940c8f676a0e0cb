/// \file
/// Synthesises the fluid components of SimTwo solids (see the header).

#include "sim/fluid_components.hpp"
#include "sim/names.hpp"

#include <cmath>

namespace s2sim::sim {
namespace {

/// Projected areas of a primitive across its local axes (simtwo-format.md §4.4).
Vec3 projected_areas(const scene::Shape& s) {
  switch (s.type) {
    case scene::ShapeType::box:
    case scene::ShapeType::convex:  // a hull: its bounding box
      return {s.size_m.y * s.size_m.z, s.size_m.x * s.size_m.z, s.size_m.x * s.size_m.y};
    case scene::ShapeType::cylinder: {
      const double side = 2 * s.radius_m * s.length_m;
      return {side, side, kPi * s.radius_m * s.radius_m};
    }
    case scene::ShapeType::sphere: {
      const double a = kPi * s.radius_m * s.radius_m;
      return {a, a, a};
    }
  }
  return {};
}

using Attributes = std::vector<std::pair<std::string, std::string>>;

void add(Attributes& a, const char* name, double v) {
  a.emplace_back(name, exact_decimal(v));
}

void add_vec(Attributes& a, const std::string& name, const Vec3& v) {
  add(a, (name + "_x").c_str(), v.x);
  add(a, (name + "_y").c_str(), v.y);
  add(a, (name + "_z").c_str(), v.z);
}

FluidComponent make(const scene::Body& body, const std::string& body_path, const char* kind,
                    Attributes attributes) {
  FluidComponent c;
  c.kind = kind;
  c.id = body.id + "/" + kind;
  c.prefix = body_path + "/" + kind;
  c.robot = body.robot;
  c.where = body.where;
  c.params.file = body.where.file;
  c.params.element.name = kind;
  c.params.element.path = body.where.element;
  attributes.insert(attributes.begin(), {{"body", body_path}, {"semantics", "simtwo"}});
  c.params.element.attributes = std::move(attributes);
  return c;
}

}  // namespace

std::vector<FluidComponent> fluid_components(const scene::Scene& scene,
                                             const std::vector<std::string>& robot_prefixes,
                                             std::vector<std::string>& warnings) {
  std::vector<FluidComponent> out;
  for (const scene::Body& body : scene.bodies) {
    if (body.geoms.empty()) continue;
    const bool thing = body.robot < 0;
    const std::string path =
        thing ? thing_path(body.id)
              : solid_path(robot_prefixes.at(static_cast<std::size_t>(body.robot)), body.id);
    const std::string on_thing = body.where.str() + ": SimTwo applies ";
    if (body.drag.present) {
      double coefficient = body.drag.coefficient;
      if (thing && coefficient != 0) {
        warnings.push_back(on_thing + "the <drag> coefficient to robot solids only; thing '" +
                           body.id + "' gets only its stokes/roll damping");
        coefficient = 0;
      }
      Attributes a;
      add(a, "stokes", body.drag.stokes);
      add(a, "roll", body.drag.roll);
      add(a, "cd", coefficient);
      add_vec(a, "area", projected_areas(body.geoms[0].shape));
      add(a, "mass", body.mass_kg);
      add_vec(a, "com", body.com_m);
      const auto& I = body.inertia_kg_m2.m;
      add(a, "ixx", I[0][0]);
      add(a, "iyy", I[1][1]);
      add(a, "izz", I[2][2]);
      add(a, "ixy", I[0][1]);
      add(a, "ixz", I[0][2]);
      add(a, "iyz", I[1][2]);
      add(a, "gravity", body.gravity ? 1.0 : 0.0);
      add_vec(a, "wind", scene.settings.wind_m_s);
      out.push_back(make(body, path, "drag", std::move(a)));
    }
    if (body.buoyancy.mass_kg != 0) {
      if (thing) {
        warnings.push_back(on_thing + "<buoyant> to robot solids only; thing '" + body.id +
                           "' floats not");
      } else {
        Attributes a;
        add(a, "mass", body.buoyancy.mass_kg);
        add_vec(a, "point", body.buoyancy.point_m);
        out.push_back(make(body, path, "buoyancy", std::move(a)));
      }
    }
    if (body.kind == scene::SolidKind::propeller) {
      if (thing) {
        warnings.push_back(on_thing + "propeller thrust to robot solids only; thing '" + body.id +
                           "' has none");
      } else {
        Attributes a;
        add(a, "coefficient", body.thrust_coefficient);
        add_vec(a, "com", body.com_m);
        out.push_back(make(body, path, "propeller", std::move(a)));
      }
    }
  }
  return out;
}

}  // namespace s2sim::sim
