#include "sim/names.hpp"

#include <cstdio>

#include <algorithm>

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

std::string short_decimal(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string exact_decimal(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace s2sim::sim
