#include "common/closest_names.hpp"

#include <algorithm>
#include <numeric>

namespace s2sim::common {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), 0);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::vector<std::string> closest_names(std::string_view wanted,
                                       const std::vector<std::string>& names, std::size_t count) {
  std::vector<std::pair<std::size_t, const std::string*>> scored;
  scored.reserve(names.size());
  for (const auto& n : names)
    scored.emplace_back(edit_distance(wanted, n), &n);
  const std::size_t k = std::min(count, scored.size());
  std::partial_sort(scored.begin(), scored.begin() + static_cast<std::ptrdiff_t>(k), scored.end(),
                    [](const auto& x, const auto& y) {
                      return x.first != y.first ? x.first < y.first : *x.second < *y.second;
                    });
  std::vector<std::string> out;
  for (std::size_t i = 0; i < k; ++i)
    out.push_back(*scored[i].second);
  return out;
}

std::string unknown_name_message(std::string_view what, std::string_view wanted,
                                 const std::vector<std::string>& names) {
  std::string msg = "unknown " + std::string(what) + " '" + std::string(wanted) + "'";
  const auto close = closest_names(wanted, names);
  if (!close.empty()) {
    msg += "; did you mean";
    for (std::size_t i = 0; i < close.size(); ++i)
      msg += (i ? ", '" : " '") + close[i] + "'";
    msg += "?";
  }
  return msg;
}

}  // namespace s2sim::common
