#include "collision/broad_phase.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::collision {
namespace {

constexpr int kBruteForceBelow = 48;
constexpr double kLargeOverPercentile = 2.0;  // boxes above twice the 90th percentile are large
constexpr double kCellHeadroom = 1.125;       // a new cell: this much above the largest box
constexpr double kCellSlack = 1.25;           // the last cell is kept up to this coarse

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

/// floor(coordinate / cell) as an integer, inline (std::floor is a library call without
/// SSE4.1): truncation, one less below zero when it rounded up.
std::int64_t cell_index(double coordinate_m, double inverse_cell) {
  // Clamped first: converting a double outside the int64 range is undefined (a body flung to
  // 1e20 m, found by the fuzzer). Cells ±2^52 away alias in pack() anyway, and every pair is
  // checked for overlap, so the clamp only costs far boxes a shared cell. NaN goes to +2^52.
  constexpr double kFar = 0x1p52;
  double x = coordinate_m * inverse_cell;
  if (!(x > -kFar)) x = -kFar;
  if (!(x < kFar)) x = kFar;
  const auto truncated = static_cast<std::int64_t>(x);
  return truncated - (x < static_cast<double>(truncated) ? 1 : 0);
}

bool entry_less(std::uint64_t cell_a, std::int32_t box_a, std::uint64_t cell_b,
                std::int32_t box_b) {
  return cell_a < cell_b || (cell_a == cell_b && box_a < box_b);
}

}  // namespace

void BroadPhase::resize(int count) {
  count_ = count;
  cell_m_ = 0;
  const auto n = static_cast<std::size_t>(count);
  sizes_.reserve(n);
  entries_.clear();
  entries_.reserve(8 * n);
  fresh_.reserve(8 * n);
  merged_.reserve(8 * n);
  spans_.assign(n, Span{});
  places_.assign(n, Place::unknown);
  moved_.assign(n, 0);
  large_.reserve(n);
  is_large_.reserve(n);
  sorter_.reserve(count, 64 + 16 * n);  // as many pairs as ContactQuery reserves for
}

void BroadPhase::choose_cell(const Aabb* boxes) {
  const int n = count_;
  sizes_.clear();
  for (int i = 0; i < n; ++i)
    sizes_.push_back(largest_side(boxes[i]));
  const auto k = static_cast<std::ptrdiff_t>((n - 1) * 9 / 10);
  std::nth_element(sizes_.begin(), sizes_.begin() + k, sizes_.end());
  const double percentile = sizes_[static_cast<std::size_t>(k)];
  // The cell must hold every ordinary box (at most 8 cells each); after nth_element the
  // boxes at or above the percentile are those from k on.
  double needed = std::max(percentile, 1e-3);
  for (std::size_t i = static_cast<std::size_t>(k); i < sizes_.size(); ++i)
    if (sizes_[i] <= kLargeOverPercentile * percentile) needed = std::max(needed, sizes_[i]);
  // Kept while it fits: the same cell gives the same cells to boxes that hardly moved.
  if (!(cell_m_ >= needed && cell_m_ <= kCellSlack * needed)) cell_m_ = kCellHeadroom * needed;
}

void BroadPhase::update_entries(const Aabb* boxes) {
  const int n = count_;
  const double inverse_cell = 1 / cell_m_;
  large_.clear();
  is_large_.assign(static_cast<std::size_t>(n), 0);
  fresh_.clear();
  bool any_moved = false;
  for (int i = 0; i < n; ++i) {
    const auto index = static_cast<std::size_t>(i);
    const Aabb& b = boxes[i];
    const Place place = largest_side(b) > cell_m_ ? Place::large : Place::grid;
    Span span{};
    if (place == Place::large) {
      large_.push_back(i);
      is_large_[index] = 1;
    } else {
      span = {{cell_index(b.min.x, inverse_cell), cell_index(b.min.y, inverse_cell),
               cell_index(b.min.z, inverse_cell)},
              {cell_index(b.max.x, inverse_cell), cell_index(b.max.y, inverse_cell),
               cell_index(b.max.z, inverse_cell)}};
    }
    const bool moved =
        place != places_[index] || (place == Place::grid && !(span == spans_[index]));
    moved_[index] = moved;
    if (!moved) continue;
    any_moved = true;
    places_[index] = place;
    spans_[index] = span;
    if (place == Place::large) continue;
    for (auto x = span.lo[0]; x <= span.hi[0]; ++x)
      for (auto y = span.lo[1]; y <= span.hi[1]; ++y)
        for (auto z = span.lo[2]; z <= span.hi[2]; ++z)
          fresh_.push_back(
              {pack(x, y, z), i,
               static_cast<std::uint8_t>((x == span.lo[0] ? 1 : 0) | (y == span.lo[1] ? 2 : 0) |
                                         (z == span.lo[2] ? 4 : 0))});
  }
  if (!any_moved) return;
  // The moved boxes' entries out, their new ones in: a merge of two sorted runs, the same
  // array a full sort of every entry gives ((cell, box) is unique).
  std::sort(fresh_.begin(), fresh_.end(), [](const Entry& a, const Entry& b) {
    return entry_less(a.cell, a.box, b.cell, b.box);
  });
  merged_.clear();
  auto kept = entries_.begin();
  const auto kept_end = entries_.end();
  auto skip_moved = [&] {
    while (kept != kept_end && moved_[static_cast<std::size_t>(kept->box)])
      ++kept;
  };
  skip_moved();
  for (const Entry& e : fresh_) {
    while (kept != kept_end && entry_less(kept->cell, kept->box, e.cell, e.box)) {
      merged_.push_back(*kept++);
      skip_moved();
    }
    merged_.push_back(e);
  }
  for (; kept != kept_end; ++kept)
    if (!moved_[static_cast<std::size_t>(kept->box)]) merged_.push_back(*kept);
  entries_.swap(merged_);
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
  choose_cell(boxes);
  update_entries(boxes);
  // Pairs within each cell; a pair that shares several cells is reported only from the cell
  // holding the corner max(min_a, min_b), which both boxes cover when they overlap. That
  // cell is, along each axis, the first cell of a or of b (the floor of the larger minimum is
  // the larger of the floors): no coordinate is needed to tell it.
  for (std::size_t first = 0; first < entries_.size();) {
    std::size_t last = first + 1;
    while (last < entries_.size() && entries_[last].cell == entries_[first].cell)
      ++last;
    for (std::size_t i = first; i < last; ++i) {
      const Entry& ei = entries_[i];
      const Aabb& a = boxes[ei.box];
      for (std::size_t j = i + 1; j < last; ++j) {
        const Entry& ej = entries_[j];
        if ((ei.first_along | ej.first_along) != 7 || !overlap(a, boxes[ej.box])) continue;
        out.emplace_back(ei.box, ej.box);
        if (out.size() > max_pairs) return false;
      }
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
  sorter_.sort(out);
  return true;
}

}  // namespace s2sim::collision
