#include "contact/broad_phase.hpp"

#include <algorithm>
#include <numeric>

namespace s2sim::contact {
namespace {

double component(const Vec3& v, int axis) {
  return axis == 0 ? v.x : axis == 1 ? v.y : v.z;
}

}  // namespace

void BroadPhase::resize(int count) {
  order_.resize(static_cast<std::size_t>(count));
  std::iota(order_.begin(), order_.end(), 0);
  axis_ = -1;  // forces a full sort on the next call
}

void BroadPhase::find_pairs(const Aabb* boxes,
                            std::vector<std::pair<std::int32_t, std::int32_t>>& out) {
  out.clear();
  const std::size_t n = order_.size();
  if (n < 2) return;
  // Sweep along the axis of largest spread of the box centres.
  double mean[3] = {0, 0, 0}, square[3] = {0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 c = (boxes[i].min + boxes[i].max) * 0.5;
    for (int a = 0; a < 3; ++a) {
      const double x = component(c, a);
      mean[a] += x;
      square[a] += x * x;
    }
  }
  int axis = 0;
  double best = -1;
  for (int a = 0; a < 3; ++a) {
    const double variance = square[a] / n - (mean[a] / n) * (mean[a] / n);
    if (variance > best) best = variance, axis = a;
  }
  auto key = [&](std::int32_t i) { return component(boxes[i].min, axis); };
  if (axis != axis_) {
    axis_ = axis;
    std::sort(order_.begin(), order_.end(), [&](std::int32_t a, std::int32_t b) {
      return key(a) < key(b) || (key(a) == key(b) && a < b);
    });
  } else {
    for (std::size_t i = 1; i < n; ++i) {  // insertion sort: near-linear for small motions
      const std::int32_t moving = order_[i];
      const double k = key(moving);
      std::size_t j = i;
      while (j > 0 &&
             (key(order_[j - 1]) > k || (key(order_[j - 1]) == k && order_[j - 1] > moving))) {
        order_[j] = order_[j - 1];
        --j;
      }
      order_[j] = moving;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Aabb& a = boxes[order_[i]];
    const double end = component(a.max, axis);
    for (std::size_t j = i + 1; j < n; ++j) {
      const Aabb& b = boxes[order_[j]];
      if (component(b.min, axis) > end) break;
      if (a.min.x > b.max.x || b.min.x > a.max.x || a.min.y > b.max.y || b.min.y > a.max.y ||
          a.min.z > b.max.z || b.min.z > a.max.z)
        continue;
      out.emplace_back(std::min(order_[i], order_[j]), std::max(order_[i], order_[j]));
    }
  }
  // The sweep order depends on history; the result must not (a restored snapshot repeats the
  // run bit for bit, so forces must be summed in the same order).
  std::sort(out.begin(), out.end());
}

}  // namespace s2sim::contact
