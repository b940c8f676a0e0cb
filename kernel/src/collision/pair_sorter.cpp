#include "collision/pair_sorter.hpp"

#include <algorithm>

namespace s2sim::collision {
namespace {
constexpr std::size_t kInsertionSortBelow = 16;
constexpr std::size_t kDirectSortPerBox = 8;  // sort directly below one pair per 8 boxes
}  // namespace

void PairSorter::reserve(int count, std::size_t pairs) {
  count_ = count;
  first_of_.reserve(static_cast<std::size_t>(count) + 1);
  sorted_.reserve(pairs);
}

void PairSorter::sort(Pairs& out) {
  const auto n = static_cast<std::size_t>(count_);
  // Few pairs among many boxes (a part's own, a few robots'): the counting sort's pass over
  // every box would cost more than sorting them directly, into the same order.
  if (out.size() * kDirectSortPerBox < n) {
    std::sort(out.begin(), out.end());
    return;
  }
  first_of_.assign(n + 1, 0);
  for (const auto& p : out)
    ++first_of_[static_cast<std::size_t>(p.first) + 1];
  for (std::size_t i = 1; i <= n; ++i)
    first_of_[i] += first_of_[i - 1];
  sorted_.resize(out.size());
  for (const auto& p : out)
    sorted_[first_of_[static_cast<std::size_t>(p.first)]++] = p;
  // first_of_[i] is now where i's pairs end; each i has a few, in discovery order.
  std::size_t begin = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t end = first_of_[i];
    if (end - begin < kInsertionSortBelow) {
      for (std::size_t a = begin + 1; a < end; ++a) {
        const auto p = sorted_[a];
        std::size_t b = a;
        for (; b > begin && sorted_[b - 1].second > p.second; --b)
          sorted_[b] = sorted_[b - 1];
        sorted_[b] = p;
      }
    } else {
      std::sort(sorted_.begin() + static_cast<std::ptrdiff_t>(begin),
                sorted_.begin() + static_cast<std::ptrdiff_t>(end));
    }
    begin = end;
  }
  std::copy(sorted_.begin(), sorted_.end(), out.begin());
}

}  // namespace s2sim::collision
