#include "zero_locals.hpp"

#include "pascal_tokens.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <vector>

namespace s2sim::pascal {
namespace {

bool is_identifier(const std::string& t) {
  return !t.empty() && (std::isalpha(static_cast<unsigned char>(t[0])) || t[0] == '_');
}

const char* const kPlain[] = {"integer", "longint",  "cardinal", "longword", "word",
                              "byte",    "smallint", "shortint", "int64",    "double",
                              "single",  "real",     "extended", "boolean",  "char"};

bool is_plain(const std::string& lower) {
  return std::find(std::begin(kPlain), std::end(kPlain), lower) != std::end(kPlain);
}

/// File variables (TextFile, Text, File, file of T) take no Default: fpc refuses it, and
/// Pascal Script never had them zeroed to begin with (they are set by AssignFile).
bool is_file_type(const std::vector<std::string>& type) {
  return !type.empty() && (type[0] == "textfile" || type[0] == "text" || type[0] == "file");
}

}  // namespace

std::string zero_locals(const std::string& script) {
  const std::vector<Token> t = tokenize(script);
  std::map<std::size_t, std::string> inserts;  // offset -> text
  std::size_t i = 0;
  const std::size_t n = t.size();
  while (i < n) {
    const bool routine = t[i].lower == "procedure" || t[i].lower == "function";
    // A procedural type (`= procedure(...)`, `: function...`) is not a routine.
    if (!routine || (i > 0 && (t[i - 1].text == "=" || t[i - 1].text == ":"))) {
      ++i;
      continue;
    }
    const bool is_function = t[i].lower == "function";
    std::size_t k = i + 1;
    if (k < n && is_identifier(t[k].text)) ++k;  // the name
    if (k < n && t[k].text == "(") {             // the parameters
      int depth = 0;
      for (; k < n; ++k) {
        if (t[k].text == "(") ++depth;
        if (t[k].text == ")" && --depth == 0) {
          ++k;
          break;
        }
      }
    }
    std::string result_type;
    if (is_function && k + 1 < n && t[k].text == ":") {
      result_type = t[k + 1].text;
      k += 2;
    }
    if (k < n && t[k].text == ";") ++k;
    if (k < n && (t[k].lower == "forward" || t[k].lower == "external")) {
      i = k;
      continue;
    }
    // Declarations up to the routine's begin.
    std::vector<std::pair<std::string, std::string>> zeroes;  // (variable, statement kind)
    std::string statements;
    bool understood = true;
    std::string section;
    while (k < n && t[k].lower != "begin") {
      const std::string& w = t[k].lower;
      if (w == "procedure" || w == "function" || w == "record") {
        understood = false;  // nested routine or inline record: leave this routine alone
        break;
      }
      if (w == "var" || w == "const" || w == "type" || w == "label") {
        section = w;
        ++k;
        continue;
      }
      if (section != "var") {
        ++k;
        continue;
      }
      // name {, name} : type [= value] ;
      std::vector<std::string> names;
      while (k < n && is_identifier(t[k].text)) {
        names.push_back(t[k].text);
        ++k;
        if (k < n && t[k].text == ",")
          ++k;
        else
          break;
      }
      if (k >= n || t[k].text != ":") {
        understood = false;
        break;
      }
      ++k;
      std::vector<std::string> type;
      int depth = 0;
      for (; k < n && !(depth == 0 && t[k].text == ";"); ++k) {
        if (t[k].text == "(" || t[k].text == "[") ++depth;
        if (t[k].text == ")" || t[k].text == "]") --depth;
        if (t[k].lower == "record" || t[k].lower == "begin") break;
        type.push_back(t[k].lower);
      }
      if (k < n && t[k].text == ";") ++k;
      if (std::find(type.begin(), type.end(), "=") != type.end()) continue;  // initialised
      if (is_file_type(type)) continue;
      for (const auto& name : names) {
        if (type.size() == 1 && is_identifier(type[0])) {
          statements += " " + name + " := Default(" + type[0] + ");";
        } else if (!type.empty() && type[0] == "array" && type.size() >= 3 &&
                   type[type.size() - 2] == "of" && is_plain(type.back()) &&
                   std::find(type.begin(), type.end(), "[") != type.end()) {
          statements += " FillChar(" + name + ", SizeOf(" + name + "), 0);";
        }
      }
    }
    if (!understood || k >= n) {
      i = k;
      continue;
    }
    if (is_function && is_identifier(result_type))
      statements += " Result := Default(" + result_type + ");";
    if (!statements.empty()) inserts[t[k].end] = statements;
    i = k + 1;
    // Skip the body: to the matching end (begin/case/try/record open, end closes).
    int depth = 1;
    for (; i < n && depth > 0; ++i) {
      const std::string& w = t[i].lower;
      if (w == "begin" || w == "case" || w == "try" || w == "record" || w == "asm") ++depth;
      if (w == "end") --depth;
    }
  }
  std::string out;
  std::size_t from = 0;
  for (const auto& [at, text] : inserts) {
    out += script.substr(from, at - from) + text;
    from = at;
  }
  out += script.substr(from);
  return out;
}

}  // namespace s2sim::pascal
