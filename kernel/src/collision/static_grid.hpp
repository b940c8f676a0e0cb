#pragma once
/// \file
/// The ray query's index of the static shapes: a uniform 2-D grid over their XY bounds, each
/// cell listing (CSR) the shapes whose box covers it; a ray walks the cells its XY projection
/// crosses (Amanatides–Woo). Built once at load from the static shapes' padded boxes.

#include "collision/shape.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace s2sim::collision {

class StaticGrid {
 public:
  StaticGrid() = default;
  /// `boxes[k]` is the box of the k-th static shape.
  explicit StaticGrid(const std::vector<Aabb>& boxes);

  /// Calls `visit(k)` for each static shape k listed in the cells the ray o + t·d, t in
  /// [0, t_max], crosses, cell by cell from the origin, and stops after the cell that holds
  /// `nearest()` (the distance of the nearest hit so far, infinity for none). A shape listed
  /// in several cells is visited once per cell.
  template <class Visit, class Nearest>
  void walk(const Vec3& o, const Vec3& d, double t_max, Visit&& visit, Nearest&& nearest) const;

  bool empty() const { return nx_ == 0; }

 private:
  double x0_ = 0, y0_ = 0, cell_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<std::int32_t> cell_start_, cell_items_;
};

template <class Visit, class Nearest>
void StaticGrid::walk(const Vec3& o, const Vec3& d, double t_max, Visit&& visit,
                      Nearest&& nearest) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (nx_ == 0) return;
  double t0 = 0, t1 = t_max;
  const double gx1 = x0_ + nx_ * cell_, gy1 = y0_ + ny_ * cell_;
  bool inside = true;
  auto clip = [&](double oi, double di, double lo, double hi) {
    if (di == 0) {
      if (oi < lo || oi > hi) inside = false;
      return;
    }
    double enter = (lo - oi) / di, leave = (hi - oi) / di;
    if (enter > leave) std::swap(enter, leave);
    t0 = std::max(t0, enter);
    t1 = std::min(t1, leave);
  };
  clip(o.x, d.x, x0_, gx1);
  clip(o.y, d.y, y0_, gy1);
  if (!inside || t0 > t1) return;
  const double px = o.x + d.x * t0, py = o.y + d.y * t0;
  int ix = std::clamp(static_cast<int>(std::floor((px - x0_) / cell_)), 0, nx_ - 1);
  int iy = std::clamp(static_cast<int>(std::floor((py - y0_) / cell_)), 0, ny_ - 1);
  const int step_x = d.x > 0 ? 1 : -1, step_y = d.y > 0 ? 1 : -1;
  double next_x = d.x > 0   ? (x0_ + (ix + 1) * cell_ - o.x) / d.x
                  : d.x < 0 ? (x0_ + ix * cell_ - o.x) / d.x
                            : kInf;
  double next_y = d.y > 0   ? (y0_ + (iy + 1) * cell_ - o.y) / d.y
                  : d.y < 0 ? (y0_ + iy * cell_ - o.y) / d.y
                            : kInf;
  const double dx = d.x != 0 ? cell_ / std::abs(d.x) : kInf;
  const double dy = d.y != 0 ? cell_ / std::abs(d.y) : kInf;
  for (;;) {
    const auto c = static_cast<std::size_t>(iy * nx_ + ix);
    for (std::int32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k)
      visit(cell_items_[static_cast<std::size_t>(k)]);
    const double cell_exit = std::min({next_x, next_y, t1});
    if (nearest() <= cell_exit || cell_exit >= t1) break;
    if (next_x < next_y) {
      ix += step_x;
      next_x += dx;
    } else {
      iy += step_y;
      next_y += dy;
    }
    if (ix < 0 || ix >= nx_ || iy < 0 || iy >= ny_) break;
  }
}

}  // namespace s2sim::collision
