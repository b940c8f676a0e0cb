/// \file
/// The mutations (see the header). They work on the text, not on a parsed tree: a mutant may
/// be malformed XML, which is input the loader must refuse cleanly too.

#include "xml_mutator.hpp"

#include <array>
#include <cctype>
#include <string_view>
#include <vector>

namespace s2sim::fuzz {
namespace {

/// Values that broke readers before (../shared/repro): non-finite, huge, tiny, negative,
/// integers past 32 bits, empty, non-numeric, expression traps.
constexpr std::array<std::string_view, 26> kHostileValues = {
    "nan",        "inf",         "-inf",  "1e308",  "-1e308",
    "0",          "-0",          "-1",    "1e-300", "4294967297",
    "2147483647", "-2147483648", "1e12",  "",       "abc",
    "1/0",        "0/0",         "(((",   "1e999",  "0x10",
    "1,5",        "sqrt(-1)",    "-1e-9", "1e9",    "99999999999999999999",
    "pow(10,400)"};

struct Span {
  std::size_t begin = 0, end = 0;  // [begin, end)
};

/// Attribute values: the text between the quotes of `name='...'` or `name="..."`.
/// The XML declaration's are left alone: the parser's, not the loader's.
std::vector<Span> attribute_values(const std::string& s) {
  std::vector<Span> out;
  std::size_t from = 1;
  if (s.rfind("<?", 0) == 0 && s.find("?>") != std::string::npos) from = s.find("?>") + 2;
  for (std::size_t i = from; i + 1 < s.size(); ++i) {
    if (s[i] != '=' || (s[i + 1] != '\'' && s[i + 1] != '"')) continue;
    const char quote = s[i + 1];
    const std::size_t close = s.find(quote, i + 2);
    if (close == std::string::npos) break;
    out.push_back({i + 2, close});
    i = close;
  }
  return out;
}

/// Attribute names: the identifier before each `=`.
std::vector<Span> attribute_names(const std::string& s) {
  std::vector<Span> out;
  for (const Span& v : attribute_values(s)) {
    std::size_t end = v.begin - 2, begin = end;  // at the '='
    while (begin > 0 &&
           (std::isalnum(static_cast<unsigned char>(s[begin - 1])) || s[begin - 1] == '_'))
      --begin;
    if (begin < end) out.push_back({begin, end});
  }
  return out;
}

/// Self-closing elements `<name .../>` (comments and declarations excluded).
std::vector<Span> empty_elements(const std::string& s) {
  std::vector<Span> out;
  for (std::size_t i = s.find('<'); i != std::string::npos; i = s.find('<', i + 1)) {
    if (i + 1 >= s.size() || s[i + 1] == '!' || s[i + 1] == '?' || s[i + 1] == '/') continue;
    const std::size_t close = s.find('>', i);
    if (close == std::string::npos) break;
    if (s[close - 1] == '/') out.push_back({i, close + 1});
  }
  return out;
}

std::string where(const std::string& s, std::size_t at) {
  std::size_t line = 1;
  for (std::size_t i = 0; i < at && i < s.size(); ++i)
    line += s[i] == '\n';
  return "line " + std::to_string(line);
}

Mutation byte_level(const std::string& xml, Rng& rng) {
  if (xml.empty()) return {xml, "empty input kept"};
  const std::size_t at = rng.below(xml.size());
  switch (rng.below(3)) {
    case 0:
      return {xml.substr(0, at), "truncated at byte " + std::to_string(at)};
    case 1: {
      static constexpr char kStrayBytes[] = "<>'\"=/&\0\xff";
      constexpr std::string_view kStray(kStrayBytes, sizeof kStrayBytes - 1);
      std::string s = xml;
      s[at] = kStray[rng.below(kStray.size())];
      return {s, "stray byte at " + where(xml, at)};
    }
    default: {
      // Deep nesting: what overflowed the stack of the recursive parsers once.
      const std::size_t depth = 1 + rng.below(4000);
      std::string open, close;
      for (std::size_t k = 0; k < depth; ++k)
        open += "<n>", close += "</n>";
      std::string s = xml;
      s.insert(at, open + close);
      return {s, std::to_string(depth) + " nested elements at " + where(xml, at)};
    }
  }
}

}  // namespace

std::uint64_t Rng::next() {
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

Mutation mutate(const std::string& xml, Rng& rng) {
  const std::size_t kind = rng.below(6);
  if (kind == 0 || kind == 1) {  // the commonest and deepest: a hostile or scaled value
    const auto values = attribute_values(xml);
    if (!values.empty()) {
      const Span v = values[rng.below(values.size())];
      const std::string old = xml.substr(v.begin, v.end - v.begin);
      std::string value;
      if (kind == 0) {
        value = std::string(kHostileValues[rng.below(kHostileValues.size())]);
      } else {
        constexpr std::array<std::string_view, 5> kScale = {"*1e6", "*1e-6", "*-1", "*1e15", "*0"};
        value = "(" + old + ")" + std::string(kScale[rng.below(kScale.size())]);
      }
      std::string s = xml;
      s.replace(v.begin, v.end - v.begin, value);
      return {s, "value '" + old + "' -> '" + value + "' at " + where(xml, v.begin)};
    }
  } else if (kind == 2 || kind == 3) {
    const auto elements = empty_elements(xml);
    if (!elements.empty()) {
      const Span e = elements[rng.below(elements.size())];
      const std::string element = xml.substr(e.begin, e.end - e.begin);
      std::string s = xml;
      if (kind == 2) {
        s.erase(e.begin, e.end - e.begin);
        return {s, "dropped " + element + " at " + where(xml, e.begin)};
      }
      s.insert(e.end, element);
      return {s, "duplicated " + element + " at " + where(xml, e.begin)};
    }
  } else if (kind == 4) {
    const auto names = attribute_names(xml);
    const Span a = names.empty() ? Span{} : names[rng.below(names.size())];
    const std::string from = xml.substr(a.begin, a.end - a.begin);
    std::vector<std::string> others;  // the other names of the document
    for (const Span& b : names)
      if (xml.compare(b.begin, b.end - b.begin, from) != 0)
        others.push_back(xml.substr(b.begin, b.end - b.begin));
    if (!others.empty()) {
      const std::string to = others[rng.below(others.size())];
      std::string s = xml;
      s.replace(a.begin, a.end - a.begin, to);
      return {s, "attribute " + from + " renamed " + to + " at " + where(xml, a.begin)};
    }
  }
  return byte_level(xml, rng);
}

}  // namespace s2sim::fuzz
