#include "collision/placement.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::collision {

Placement::Placement(const ShapeTable& table, double margin)
    : margin_(margin),
      world_(static_cast<std::size_t>(table.size())),
      box_(world_.size()),
      speculative_m_(world_.size(), 0.0),
      reach2_m2_(world_.size(), 0.0) {
  const auto& shapes = table.shapes();
  const auto& local = table.local_poses();
  for (std::size_t i = 0; i < world_.size(); ++i) {
    const double reach = norm(local[i].position) + shapes[i].bounding_radius_m;
    reach2_m2_[i] = reach * reach;
  }
  for (const std::int32_t s : table.statics()) {
    const auto i = static_cast<std::size_t>(s);
    world_[i] = local[i];
    box_[i] = bounds(shapes[i], world_[i], margin_);
  }
}

void Placement::reshaped(const ShapeTable& table, std::int32_t shape) {
  const auto i = static_cast<std::size_t>(shape);
  const double reach = norm(table.local_poses()[i].position) + table.shapes()[i].bounding_radius_m;
  reach2_m2_[i] = reach * reach;
}

void Placement::update(const ShapeTable& table, const Pose* poses) {
  update(table, poses, nullptr, 0, 0, 0);
}

void Placement::update(const ShapeTable& table, const Pose* poses, const Twist* twists,
                       double step_s, double min_margin_m, double max_margin_m) {
  const auto& moving = table.moving();
  update(table, poses, twists, step_s, min_margin_m, max_margin_m, moving.data(), moving.size());
}

void Placement::update(const ShapeTable& table, const Pose* poses, const Twist* twists,
                       double step_s, double min_margin_m, double max_margin_m,
                       const std::int32_t* moving, std::size_t count) {
  const Shape* shapes = table.shapes().data();
  const std::int32_t* body = table.bodies().data();
  const Pose* local = table.local_poses().data();
  const char* identity = table.local_identity().data();
  for (std::size_t k = 0; k < count; ++k) {
    const auto i = static_cast<std::size_t>(moving[k]);
    const Pose& pose = poses[body[i]];
    world_[i] = identity[i] ? pose : pose * local[i];
    speculative_m_[i] = 0;
    if (twists) {
      // A bound on the speed of any point of the shape: its body origin's, plus the spin times
      // the shape's reach from that origin. (a + b)² <= 2·(a² + b²): most shapes are slow, and
      // need no root.
      const Twist& t = twists[body[i]];
      const double linear2 = dot(t.linear_m_s, t.linear_m_s);
      const double spin2 = dot(t.angular_rad_s, t.angular_rad_s) * reach2_m2_[i];
      if (2 * (linear2 + spin2) * step_s * step_s >= min_margin_m * min_margin_m) {
        const double travel = (std::sqrt(linear2) + std::sqrt(spin2)) * step_s;
        if (travel >= min_margin_m) speculative_m_[i] = std::min(travel, max_margin_m);
      }
    }
    box_[i] = bounds(shapes[i], world_[i], margin_ + speculative_m_[i]);
  }
}

}  // namespace s2sim::collision
