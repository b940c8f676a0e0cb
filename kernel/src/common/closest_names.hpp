#pragma once
/// \file
/// "Did you mean": the names closest to one that is unknown (a signal, an input, a plugin kind,
/// a component's parameter), for error messages. Levenshtein distance, ties by name.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace s2sim::common {

/// Levenshtein distance: the edits (insert, delete, replace) that turn `a` into `b`.
std::size_t edit_distance(std::string_view a, std::string_view b);

/// Up to `count` names closest to `wanted` (edit distance), for error messages.
std::vector<std::string> closest_names(std::string_view wanted,
                                       const std::vector<std::string>& names,
                                       std::size_t count = 3);

/// "unknown signal 'x'; did you mean 'a', 'b'?" from closest_names.
std::string unknown_name_message(std::string_view what, std::string_view wanted,
                                 const std::vector<std::string>& names);

}  // namespace s2sim::common
