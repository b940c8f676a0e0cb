#include "sim/names.hpp"

#include <cstdio>

#include <algorithm>
#include <numeric>

namespace s2sim::sim {

std::string segment(std::string_view id) {
  std::string s(id);
  std::replace(s.begin(), s.end(), '/', '_');
  return s;
}

std::string robot_path(std::string_view robot_id) {
  return "robots/" + segment(robot_id);
}
std::string solid_path(std::string_view robot_path, std::string_view solid_id) {
  return std::string(robot_path) + "/solids/" + segment(solid_id);
}
std::string thing_path(std::string_view thing_id) {
  return "things/" + segment(thing_id);
}
std::string axis_path(std::string_view scope, std::string_view axis_name) {
  return std::string(scope) + "/axes/" + segment(axis_name);
}
std::string joint_path(std::string_view scope, std::string_view joint_id) {
  return std::string(scope) + "/joints/" + segment(joint_id);
}
std::string component_path(std::string_view robot_path, std::string_view folder,
                           std::string_view id) {
  std::string p = robot_path.empty() ? std::string() : std::string(robot_path) + "/";
  return p + std::string(folder) + "/" + segment(id);
}
std::string field_path(std::string_view prefix, std::string_view field) {
  return std::string(prefix) + "/" + std::string(field);
}

bool glob_match(std::string_view pattern, std::string_view text) {
  // Iterative matcher with one backtrack point for the last '*': linear in practice.
  std::size_t p = 0, t = 0, star = std::string_view::npos, mark = 0;
  while (t < text.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == text[t])) {
      ++p;
      ++t;
    } else if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      mark = t;
    } else if (star != std::string_view::npos) {
      p = star + 1;
      t = ++mark;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*')
    ++p;
  return p == pattern.size();
}

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

std::string exact_decimal(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace s2sim::sim
