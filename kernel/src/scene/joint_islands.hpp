#pragma once
/// \file
/// The islands of a scene's joint graph: the bodies a chain of joints connects (a robot, an
/// arm). The world joins nothing, so two robots on the floor are two islands. Used to deal the
/// multibody into parts (model/island_plan.cpp) and to group shapes for the contact broad phase
/// (contact/contact_world.cpp). C++17: the model's Simbody translation units include it.

#include <s2sim/kernel/scene.hpp>

#include <cstddef>
#include <numeric>
#include <vector>

namespace s2sim::scene {

/// Per scene body (0-based), the lowest body of its island: union–find over every joint
/// between two bodies. A body without such a joint is its own root.
inline std::vector<int> joint_island_roots(const Scene& scene) {
  std::vector<int> root(scene.bodies.size());
  std::iota(root.begin(), root.end(), 0);
  auto find = [&](int x) {
    while (root[static_cast<std::size_t>(x)] != x) {
      auto& p = root[static_cast<std::size_t>(x)];
      p = root[static_cast<std::size_t>(p)];  // path halving
      x = p;
    }
    return x;
  };
  for (const auto& j : scene.joints) {
    if (j.body1 < 0 || j.body2 < 0) continue;
    const int a = find(j.body1), b = find(j.body2);
    if (a != b) root[static_cast<std::size_t>(a < b ? b : a)] = a < b ? a : b;
  }
  for (std::size_t b = 0; b < root.size(); ++b)
    root[b] = find(static_cast<int>(b));
  return root;
}

}  // namespace s2sim::scene
