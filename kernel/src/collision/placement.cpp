#include "collision/placement.hpp"

namespace s2sim::collision {

Placement::Placement(const ShapeTable& table, double margin)
    : margin_(margin), world_(static_cast<std::size_t>(table.size())), box_(world_.size()) {
  const auto& shapes = table.shapes();
  const auto& local = table.local_poses();
  for (const std::int32_t s : table.statics()) {
    const auto i = static_cast<std::size_t>(s);
    world_[i] = local[i];
    box_[i] = bounds(shapes[i], world_[i], margin_);
  }
}

void Placement::update(const ShapeTable& table, const Pose* poses) {
  const Shape* shapes = table.shapes().data();
  const std::int32_t* body = table.bodies().data();
  const Pose* local = table.local_poses().data();
  const char* identity = table.local_identity().data();
  for (const std::int32_t s : table.moving()) {
    const auto i = static_cast<std::size_t>(s);
    world_[i] = identity[i] ? poses[body[i]] : poses[body[i]] * local[i];
    box_[i] = bounds(shapes[i], world_[i], margin_);
  }
}

}  // namespace s2sim::collision
