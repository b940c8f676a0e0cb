#include "collision/island_broad_phase.hpp"

#include <algorithm>
#include <map>

namespace s2sim::collision {
namespace {

// Worth it when the groups (islands and statics) are at most this share of the shapes.
constexpr double kMaxGroupsPerShape = 0.75;
// Within islands, at most this many pairs that may touch per shape (a grid of all shapes
// finds a shape's few neighbours for less than testing more).
constexpr std::size_t kMaxWithinPerShape = 8;

}  // namespace

bool IslandBroadPhase::build(const std::vector<std::int32_t>& island_of_shape,
                             const std::function<bool(std::int32_t, std::int32_t)>& may_touch) {
  shape_count_ = static_cast<int>(island_of_shape.size());
  std::map<std::int32_t, std::vector<std::int32_t>> islands;  // label -> shapes, ascending
  std::vector<std::int32_t> statics;
  int searched = 0;
  for (std::int32_t s = 0; s < shape_count_; ++s) {
    const std::int32_t label = island_of_shape[static_cast<std::size_t>(s)];
    if (label == kAbsent) continue;
    (label < 0 ? statics : islands[label]).push_back(s);
    ++searched;
  }
  island_count_ = static_cast<int>(islands.size());
  const std::size_t groups = islands.size() + statics.size();
  if (searched < 2 ||
      static_cast<double>(groups) > kMaxGroupsPerShape * static_cast<double>(searched))
    return false;
  first_shape_.clear();
  shapes_.clear();
  within_.clear();
  for (const auto& [label, members] : islands) {
    first_shape_.push_back(static_cast<std::int32_t>(shapes_.size()));
    shapes_.insert(shapes_.end(), members.begin(), members.end());
    for (std::size_t a = 0; a < members.size(); ++a)
      for (std::size_t b = a + 1; b < members.size(); ++b)
        if (may_touch(members[a], members[b])) {
          within_.emplace_back(members[a], members[b]);
          if (within_.size() > kMaxWithinPerShape * static_cast<std::size_t>(shape_count_))
            return false;
        }
  }
  for (const std::int32_t s : statics) {
    first_shape_.push_back(static_cast<std::int32_t>(shapes_.size()));
    shapes_.push_back(s);
  }
  first_shape_.push_back(static_cast<std::int32_t>(shapes_.size()));
  group_boxes_.assign(groups, Aabb{});
  groups_.resize(static_cast<int>(groups));
  group_pairs_.reserve(64 + 16 * groups);
  sorter_.reserve(shape_count_, 64 + 16 * static_cast<std::size_t>(shape_count_));
  return true;
}

void IslandBroadPhase::reset() {
  groups_.resize(static_cast<int>(group_boxes_.size()));
}

IslandBroadPhase::Found IslandBroadPhase::find_pairs(const Aabb* boxes, Pairs& out,
                                                     std::size_t max_pairs) {
  out.clear();
  auto emit = [&](std::int32_t i, std::int32_t j) {
    out.emplace_back(std::min(i, j), std::max(i, j));
    return out.size() <= max_pairs;
  };
  for (const auto& [i, j] : within_)
    if (overlap(boxes[i], boxes[j]) && !emit(i, j)) return Found::too_many_pairs;
  const std::size_t groups = group_boxes_.size();
  for (std::size_t g = 0; g < groups; ++g) {
    auto s = static_cast<std::size_t>(first_shape_[g]);
    const auto end = static_cast<std::size_t>(first_shape_[g + 1]);
    Aabb box = boxes[shapes_[s]];
    for (++s; s < end; ++s)
      box = united(box, boxes[shapes_[s]]);
    group_boxes_[g] = box;
  }
  if (!groups_.find_pairs(group_boxes_.data(), group_pairs_, max_pairs))
    return Found::too_many_groups;
  for (const auto& [g, h] : group_pairs_) {
    if (g >= island_count_ && h >= island_count_) continue;  // static against static
    const auto g_end = static_cast<std::size_t>(first_shape_[static_cast<std::size_t>(g) + 1]);
    const auto h_begin = static_cast<std::size_t>(first_shape_[static_cast<std::size_t>(h)]);
    const auto h_end = static_cast<std::size_t>(first_shape_[static_cast<std::size_t>(h) + 1]);
    for (auto a = static_cast<std::size_t>(first_shape_[static_cast<std::size_t>(g)]); a < g_end;
         ++a) {
      const std::int32_t i = shapes_[a];
      if (!overlap(boxes[i], group_boxes_[static_cast<std::size_t>(h)])) continue;
      for (std::size_t b = h_begin; b < h_end; ++b)
        if (overlap(boxes[i], boxes[shapes_[b]]) && !emit(i, shapes_[b]))
          return Found::too_many_pairs;
    }
  }
  sorter_.sort(out);
  return Found::pairs;
}

}  // namespace s2sim::collision
