#pragma once
/// \file
/// The convex hull of a point set (qhull), for mesh collision geometry.

#include <s2sim/kernel/scene.hpp>

#include <memory>
#include <string>
#include <vector>

namespace s2sim::scene {

/// The hull of `points`; nullptr with `why` set when they span no volume (a flat or
/// degenerate mesh) or qhull fails.
std::shared_ptr<const ConvexHull> convex_hull(const std::vector<Vec3>& points, std::string& why);

}  // namespace s2sim::scene
