#pragma once
/// \file
/// Where a sensor is: the world pose of the scene sensor whose components' outputs are under
/// a prefix (`robots/<robot>/sensors/<name>`, `sensors/<name>`), for drawing a lidar's point
/// cloud (sensor frame) in the world view.

#include <s2sim/kernel/simulation.hpp>

#include <optional>
#include <string>
#include <string_view>

namespace s2sim::viewer {

/// The prefix of an image's name: all before its last '/'.
std::string image_prefix(std::string_view image_name);
/// The scene sensor (scene().sensors) whose outputs lie under `prefix`, -1 when none does
/// (a sensor placed with `<plugin>`, say).
int sensor_with_prefix(const Simulation& sim, std::string_view prefix);
/// The sensor frame in the world now: its body's pose times its mount.
Pose sensor_world_pose(const Simulation& sim, int sensor);

}  // namespace s2sim::viewer
