#pragma once
/// \file
/// Each robot's trail: where its main body went, as a ring of timed points (no allocation
/// after `reset`), trimmed to the last `length_s` of simulated time when drawn.

#include "render_names.hpp"

#include <cstddef>
#include <vector>

namespace s2sim::viewer {

class Trails {
 public:
  static constexpr std::size_t capacity = 2048;  ///< points kept per robot
  /// Closer points than this are not added (a robot at rest adds none).
  static constexpr float min_step_m = 0.005f;

  /// Forgets every point; sizes the rings for `robots` robots.
  void reset(std::size_t robots);
  /// Adds the main body's position of robot `r` at simulated time `time_s`. A time earlier
  /// than the newest point (a reset of the simulation) clears that robot's trail first.
  void add(std::size_t r, double time_s, const Vec3f& position_m);
  /// Number of points of robot `r` not older than `length_s` before its newest point.
  std::size_t count(std::size_t r, double length_s) const;
  /// The i-th (oldest first) of the `n` newest points of robot `r` (n from `count`).
  const Vec3f& point(std::size_t r, std::size_t n, std::size_t i) const;
  std::size_t robots() const { return rings_.size(); }

 private:
  struct Point {
    double time_s;
    Vec3f position_m;
  };
  struct Ring {
    std::vector<Point> points;  ///< `capacity` long
    std::size_t newest = 0, size = 0;
  };
  std::vector<Ring> rings_;
};

}  // namespace s2sim::viewer
