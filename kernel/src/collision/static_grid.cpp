#include "collision/static_grid.hpp"

namespace s2sim::collision {
namespace {
constexpr int kMaxCellsPerAxis = 256;
}  // namespace

StaticGrid::StaticGrid(const std::vector<Aabb>& boxes) {
  if (boxes.empty()) return;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
  for (const auto& b : boxes) {
    x0 = std::min(x0, b.min.x);
    y0 = std::min(y0, b.min.y);
    x1 = std::max(x1, b.max.x);
    y1 = std::max(y1, b.max.y);
  }
  const double ex = std::max(x1 - x0, 1e-6), ey = std::max(y1 - y0, 1e-6);
  const double n = static_cast<double>(boxes.size());
  cell_ = std::sqrt(ex * ey / (2 * n));  // about two cells per obstacle
  cell_ = std::max({cell_, ex / kMaxCellsPerAxis, ey / kMaxCellsPerAxis, 1e-6});
  nx_ = std::clamp(static_cast<int>(std::ceil(ex / cell_)), 1, kMaxCellsPerAxis);
  ny_ = std::clamp(static_cast<int>(std::ceil(ey / cell_)), 1, kMaxCellsPerAxis);
  x0_ = x0;
  y0_ = y0;
  auto cell_range = [&](const Aabb& b, int& ix0, int& ix1, int& iy0, int& iy1) {
    ix0 = std::clamp(static_cast<int>(std::floor((b.min.x - x0) / cell_)), 0, nx_ - 1);
    ix1 = std::clamp(static_cast<int>(std::floor((b.max.x - x0) / cell_)), 0, nx_ - 1);
    iy0 = std::clamp(static_cast<int>(std::floor((b.min.y - y0) / cell_)), 0, ny_ - 1);
    iy1 = std::clamp(static_cast<int>(std::floor((b.max.y - y0) / cell_)), 0, ny_ - 1);
  };
  cell_start_.assign(static_cast<std::size_t>(nx_ * ny_ + 1), 0);
  int ix0, ix1, iy0, iy1;
  for (const auto& b : boxes) {
    cell_range(b, ix0, ix1, iy0, iy1);
    for (int iy = iy0; iy <= iy1; ++iy)
      for (int ix = ix0; ix <= ix1; ++ix)
        ++cell_start_[static_cast<std::size_t>(iy * nx_ + ix + 1)];
  }
  for (std::size_t c = 1; c < cell_start_.size(); ++c)
    cell_start_[c] += cell_start_[c - 1];
  cell_items_.assign(static_cast<std::size_t>(cell_start_.back()), 0);
  std::vector<std::int32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    cell_range(boxes[i], ix0, ix1, iy0, iy1);
    for (int iy = iy0; iy <= iy1; ++iy)
      for (int ix = ix0; ix <= ix1; ++ix)
        cell_items_[static_cast<std::size_t>(fill[static_cast<std::size_t>(iy * nx_ + ix)]++)] =
            static_cast<std::int32_t>(i);
  }
}

}  // namespace s2sim::collision
