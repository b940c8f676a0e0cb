#include "trails.hpp"

namespace s2sim::viewer {

void Trails::reset(std::size_t robots) {
  rings_.assign(robots, Ring{});
  for (Ring& ring : rings_)
    ring.points.resize(capacity);
}

void Trails::add(std::size_t r, double time_s, const Vec3f& position_m) {
  if (r >= rings_.size()) return;
  Ring& ring = rings_[r];
  if (ring.size > 0) {
    const Point& newest = ring.points[ring.newest];
    if (time_s < newest.time_s)
      ring.size = 0;  // the simulation went back: a new trail
    else {
      const Vec3f d = position_m - newest.position_m;
      if (dot(d, d) < min_step_m * min_step_m) return;
    }
  }
  ring.newest = ring.size == 0 ? 0 : (ring.newest + 1) % capacity;
  ring.points[ring.newest] = {time_s, position_m};
  if (ring.size < capacity) ++ring.size;
}

std::size_t Trails::count(std::size_t r, double length_s) const {
  if (r >= rings_.size()) return 0;
  const Ring& ring = rings_[r];
  if (ring.size == 0) return 0;
  const double newest_s = ring.points[ring.newest].time_s;
  std::size_t n = 0;
  while (n < ring.size &&
         newest_s - ring.points[(ring.newest + capacity - n) % capacity].time_s <= length_s)
    ++n;
  return n;
}

const Vec3f& Trails::point(std::size_t r, std::size_t n, std::size_t i) const {
  const Ring& ring = rings_[r];
  return ring.points[(ring.newest + capacity - (n - 1 - i)) % capacity].position_m;
}

}  // namespace s2sim::viewer
