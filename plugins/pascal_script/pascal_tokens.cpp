#include "pascal_tokens.hpp"

#include <algorithm>
#include <cctype>

namespace s2sim::pascal {

std::vector<Token> tokenize(const std::string& s) {
  std::vector<Token> out;
  std::size_t i = 0;
  const std::size_t n = s.size();
  while (i < n) {
    const char c = s[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '/' && i + 1 < n && s[i + 1] == '/') {
      while (i < n && s[i] != '\n')
        ++i;
    } else if (c == '{') {
      while (i < n && s[i] != '}')
        ++i;
      ++i;
    } else if (c == '(' && i + 1 < n && s[i + 1] == '*') {
      i += 2;
      while (i + 1 < n && !(s[i] == '*' && s[i + 1] == ')'))
        ++i;
      i += 2;
    } else if (c == '\'') {
      ++i;
      while (i < n && s[i] != '\'')
        ++i;
      ++i;
      out.push_back({"''", "''", std::min(i, n)});
    } else if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '$' || c == '#') {
      const std::size_t b = i;
      while (i < n && (std::isalnum(static_cast<unsigned char>(s[i])) || s[i] == '_' ||
                       s[i] == '$' || s[i] == '#'))
        ++i;
      std::string t = s.substr(b, i - b), l = t;
      std::transform(l.begin(), l.end(), l.begin(),
                     [](unsigned char ch) { return std::tolower(ch); });
      out.push_back({t, l, i});
    } else {
      // two-character symbols matter only as ".." and ":="
      std::string t(1, c);
      if (i + 1 < n && ((c == '.' && s[i + 1] == '.') || (c == ':' && s[i + 1] == '=')))
        t += s[i + 1];
      i += t.size();
      out.push_back({t, t, i});
    }
  }
  return out;
}

bool mentions_any(const std::string& script, std::initializer_list<const char*> lower_names) {
  for (const Token& t : tokenize(script))
    for (const char* name : lower_names)
      if (t.lower == name) return true;
  return false;
}

}  // namespace s2sim::pascal
