#pragma once
/// \file
/// A Pascal script's tokens: identifiers, numbers and symbols, with comments and string
/// literals skipped (a string literal is one token ''), for the passes that read a script
/// without compiling it (zero_locals.hpp, and which ports a script uses).

#include <cstddef>
#include <initializer_list>
#include <string>
#include <vector>

namespace s2sim::pascal {

struct Token {
  std::string text;     // as written
  std::string lower;    // for keywords
  std::size_t end = 0;  // offset just past the token in the script
};

std::vector<Token> tokenize(const std::string& script);

/// Whether the script names any of these identifiers (lower case) outside comments and strings.
bool mentions_any(const std::string& script, std::initializer_list<const char*> lower_names);

}  // namespace s2sim::pascal
