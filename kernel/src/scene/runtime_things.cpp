/// \file
/// Spare bodies for things added while running (docs/format.md, "Things added while
/// running"): bodies like any thing, so that signals, contact, snapshots and the parallel
/// parts know them from load, parked out of the world until a thing takes one.
#include "scene/limits.hpp"
#include "scene/mass.hpp"

#include <s2sim/error.hpp>

#include <string>

namespace s2sim::scene {

namespace {
/// Small enough that no two parked bodies touch (they are a metre apart, and parked bodies
/// are left out of contact anyway).
constexpr double kParkedRadius_m = 0.01;
constexpr double kParkDepth_m = 1000;
}  // namespace

Pose runtime_thing_park_pose(int k) {
  Pose pose;
  pose.position = {static_cast<double>(k), 0, -kParkDepth_m};
  return pose;
}

void reserve_runtime_things(Scene& scene, int count) {
  if (count < 0 || count > limits::kMaxRuntimeThings)
    throw Error(ErrorKind::usage, "runtime things must be from 0 to " +
                                      std::to_string(limits::kMaxRuntimeThings) + ", got " +
                                      std::to_string(count));
  for (int k = 0; k < count; ++k) {
    Body b;
    b.id = "runtime thing " + std::to_string(k);
    b.kind = SolidKind::sphere;
    b.pose = runtime_thing_park_pose(k);
    b.mass_kg = 1;
    Geom g;
    g.id = b.id;
    g.shape.type = ShapeType::sphere;
    g.shape.radius_m = kParkedRadius_m;
    b.geoms.push_back(g);
    b.inertia_kg_m2 = uniform_inertia(g.shape, b.mass_kg);
    b.gravity = false;
    scene.runtime_things.push_back(static_cast<int>(scene.bodies.size()));
    scene.bodies.push_back(std::move(b));
  }
}

}  // namespace s2sim::scene
