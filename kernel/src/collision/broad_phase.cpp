#include "collision/broad_phase.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::collision {
namespace {

constexpr int kBruteForceBelow = 48;

bool overlap(const Aabb& a, const Aabb& b) {
  return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y &&
         a.min.z <= b.max.z && b.min.z <= a.max.z;
}

double largest_side(const Aabb& b) {
  return std::max({b.max.x - b.min.x, b.max.y - b.min.y, b.max.z - b.min.z});
}

/// A cell index per axis packed in 21 bits each (cells ±2^20 around the origin).
std::uint64_t pack(std::int64_t ix, std::int64_t iy, std::int64_t iz) {
  constexpr std::int64_t offset = 1 << 20, mask = (1 << 21) - 1;
  return (static_cast<std::uint64_t>((ix + offset) & mask) << 42) |
         (static_cast<std::uint64_t>((iy + offset) & mask) << 21) |
         static_cast<std::uint64_t>((iz + offset) & mask);
}

}  // namespace

void BroadPhase::resize(int count) {
  count_ = count;
  sizes_.reserve(static_cast<std::size_t>(count));
  entries_.reserve(8 * static_cast<std::size_t>(count));
  large_.reserve(static_cast<std::size_t>(count));
  is_large_.reserve(static_cast<std::size_t>(count));
}

bool BroadPhase::find_pairs(const Aabb* boxes,
                            std::vector<std::pair<std::int32_t, std::int32_t>>& out,
                            std::size_t max_pairs) {
  out.clear();
  const int n = count_;
  if (n < 2) return true;
  if (n <= kBruteForceBelow) {  // cheaper than any structure for a few robots' parts
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        if (overlap(boxes[i], boxes[j])) {
          out.emplace_back(i, j);
          if (out.size() > max_pairs) return false;
        }
    return true;
  }
  // Cell size: the 90th percentile of the boxes' largest sides.
  sizes_.clear();
  for (int i = 0; i < n; ++i)
    sizes_.push_back(largest_side(boxes[i]));
  const auto k = static_cast<std::ptrdiff_t>((n - 1) * 9 / 10);
  std::nth_element(sizes_.begin(), sizes_.begin() + k, sizes_.end());
  const double cell = std::max(sizes_[static_cast<std::size_t>(k)], 1e-3);
  const double inverse_cell = 1 / cell;

  entries_.clear();
  large_.clear();
  is_large_.assign(static_cast<std::size_t>(n), 0);
  for (int i = 0; i < n; ++i) {
    const Aabb& b = boxes[i];
    if (largest_side(b) > cell) {
      large_.push_back(i);
      is_large_[static_cast<std::size_t>(i)] = 1;
      continue;
    }
    const auto x0 = static_cast<std::int64_t>(std::floor(b.min.x * inverse_cell));
    const auto y0 = static_cast<std::int64_t>(std::floor(b.min.y * inverse_cell));
    const auto z0 = static_cast<std::int64_t>(std::floor(b.min.z * inverse_cell));
    const auto x1 = static_cast<std::int64_t>(std::floor(b.max.x * inverse_cell));
    const auto y1 = static_cast<std::int64_t>(std::floor(b.max.y * inverse_cell));
    const auto z1 = static_cast<std::int64_t>(std::floor(b.max.z * inverse_cell));
    for (auto x = x0; x <= x1; ++x)
      for (auto y = y0; y <= y1; ++y)
        for (auto z = z0; z <= z1; ++z)
          entries_.push_back({pack(x, y, z), i});
  }
  std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
    return a.cell < b.cell || (a.cell == b.cell && a.box < b.box);
  });
  // Pairs within each cell; a pair that shares several cells is reported only from the cell
  // holding the corner max(min_a, min_b), which both boxes cover when they overlap.
  for (std::size_t first = 0; first < entries_.size();) {
    std::size_t last = first + 1;
    while (last < entries_.size() && entries_[last].cell == entries_[first].cell)
      ++last;
    for (std::size_t i = first; i < last; ++i)
      for (std::size_t j = i + 1; j < last; ++j) {
        const Aabb& a = boxes[entries_[i].box];
        const Aabb& b = boxes[entries_[j].box];
        if (!overlap(a, b)) continue;
        const std::uint64_t owner =
            pack(static_cast<std::int64_t>(std::floor(std::max(a.min.x, b.min.x) * inverse_cell)),
                 static_cast<std::int64_t>(std::floor(std::max(a.min.y, b.min.y) * inverse_cell)),
                 static_cast<std::int64_t>(std::floor(std::max(a.min.z, b.min.z) * inverse_cell)));
        if (owner != entries_[first].cell) continue;
        out.emplace_back(entries_[i].box, entries_[j].box);
        if (out.size() > max_pairs) return false;
      }
    first = last;
  }
  // Large boxes against the small ones and each other (large pairs once).
  for (std::size_t a = 0; a < large_.size(); ++a) {
    const std::int32_t l = large_[a];
    for (int i = 0; i < n; ++i)
      if (!is_large_[static_cast<std::size_t>(i)] && overlap(boxes[l], boxes[i])) {
        out.emplace_back(std::min(l, i), std::max(l, i));
        if (out.size() > max_pairs) return false;
      }
    for (std::size_t b = a + 1; b < large_.size(); ++b)
      if (overlap(boxes[l], boxes[large_[b]])) {
        out.emplace_back(std::min(l, large_[b]), std::max(l, large_[b]));
        if (out.size() > max_pairs) return false;
      }
  }
  // The result must not depend on the order of discovery (a restored snapshot repeats the run
  // bit for bit, so forces must be summed in the same order).
  std::sort(out.begin(), out.end());
  return true;
}

}  // namespace s2sim::collision
