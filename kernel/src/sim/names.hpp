#pragma once
/// \file
/// Signal-name helpers: the path segment of a scene ID, glob matching, "did you mean".

#include <string>
#include <string_view>
#include <vector>

namespace s2sim::sim {

/// A scene ID as one path segment of a signal name: '/' would split it, so it becomes '_'.
std::string segment(std::string_view id);

/// Glob match: `*` matches any run of characters (including '/'), `?` exactly one.
bool glob_match(std::string_view pattern, std::string_view text);

/// Up to `count` names closest to `wanted` (edit distance), for error messages.
std::vector<std::string> closest_names(std::string_view wanted,
                                       const std::vector<std::string>& names,
                                       std::size_t count = 3);

/// "unknown signal 'x'; did you mean 'a', 'b'?" from closest_names.
std::string unknown_name_message(std::string_view what, std::string_view wanted,
                                 const std::vector<std::string>& names);

}  // namespace s2sim::sim
