#include "sensor_frames.hpp"

#include <algorithm>

namespace s2sim::viewer {
namespace {

/// A name as one path segment (the kernel's rule: '/' becomes '_').
std::string segment(std::string s) {
  std::replace(s.begin(), s.end(), '/', '_');
  return s;
}

}  // namespace

std::string image_prefix(std::string_view image_name) {
  const std::size_t slash = image_name.rfind('/');
  return std::string(slash == std::string_view::npos ? std::string_view()
                                                     : image_name.substr(0, slash));
}

int sensor_with_prefix(const Simulation& sim, std::string_view prefix) {
  const scene::Scene& scene = sim.scene();
  for (std::size_t i = 0; i < scene.sensors.size(); ++i) {
    const scene::Sensor& s = scene.sensors[i];
    std::string p;
    if (s.robot >= 0)
      p = "robots/" + segment(scene.robots[static_cast<std::size_t>(s.robot)].id) + "/";
    p += "sensors/" + segment(s.name);
    if (p == prefix) return static_cast<int>(i);
  }
  return -1;
}

Pose sensor_world_pose(const Simulation& sim, int sensor) {
  const scene::Sensor& s = sim.scene().sensors[static_cast<std::size_t>(sensor)];
  // Scene body i is the simulation's body i + 1; -1 (fixed to the world) is body 0.
  return sim.body_pose(s.body + 1) * s.pose;
}

}  // namespace s2sim::viewer
