#pragma once
/// \file
/// The broad phase: the overlapping pairs among axis-aligned boxes, by a uniform grid kept in
/// a sorted array (no hash table, no allocation once warm). The cell is as large as the
/// ordinary boxes (those up to twice the 90th percentile of size), so each of them touches at
/// most 8 cells; larger boxes (long obstacles, belts) are tested against every box. Sorting
/// the cell entries makes it N log N as objects are added, whatever their layout (a
/// sweep-and-prune degrades to N^1.5 on a floor covered with objects). A few dozen boxes are
/// simply tested pairwise.
///
/// From one call to the next most boxes stay in the same cells: the cell size is kept while
/// it still fits the boxes, and only the entries of boxes whose cells changed are removed and
/// merged back in, so a settled scene costs no sort at all. The result never depends on what
/// was kept: the sorted array is the same as a full sort's.

#include "collision/pair_sorter.hpp"
#include "collision/shape.hpp"

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace s2sim::collision {

class BroadPhase {
 public:
  /// `count` proxies; reserves every buffer once and forgets the cells of the last call.
  void resize(int count);
  /// Pairs (i, j), i < j, whose boxes overlap, in increasing order; `out` is cleared first.
  /// Allocates only when more pairs overlap than ever before. Stops, returning false, once
  /// more than `max_pairs` are found (`out` then holds max_pairs + 1 of them): boxes piled
  /// into one another would otherwise ask for memory quadratic in their number.
  bool find_pairs(const Aabb* boxes, std::vector<std::pair<std::int32_t, std::int32_t>>& out,
                  std::size_t max_pairs = SIZE_MAX);

 private:
  struct Entry {
    std::uint64_t cell;
    std::int32_t box;
    /// Bit k: the cell is the box's first along axis k. A pair is reported from the cell
    /// that is the first of one box or the other along every axis.
    std::uint8_t first_along;
  };
  /// The cells a box covers, per axis the first and the last index.
  struct Span {
    std::int64_t lo[3], hi[3];
    bool operator==(const Span&) const = default;
  };
  enum class Place : char { unknown, grid, large };

  /// Sets cell_m_ for this call's boxes (keeping the last one when it still fits).
  void choose_cell(const Aabb* boxes);
  /// Brings entries_ to this call's cells: the entries of boxes that changed cells are
  /// dropped and their new ones merged in. Fills large_ and is_large_.
  void update_entries(const Aabb* boxes);

  int count_ = 0;
  double cell_m_ = 0;  // 0: none chosen yet
  std::vector<double> sizes_;
  std::vector<Entry> entries_, fresh_, merged_;
  std::vector<Span> spans_;
  std::vector<Place> places_;
  std::vector<char> moved_;
  std::vector<std::int32_t> large_;
  std::vector<char> is_large_;
  PairSorter sorter_;
};

}  // namespace s2sim::collision
