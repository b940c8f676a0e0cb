/// \file
/// Attribute reading with located errors (see attributes.hpp).

#include "scene/attributes.hpp"

#include "scene/expression.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>

namespace s2sim::scene {

double evaluate_attribute(std::string_view text, const ConstantTable& constants,
                          const Location& where) {
  try {
    return evaluate(text, constants);
  } catch (const ExpressionError& e) {
    std::string why = e.what();
    // The evaluator may already say "at column N"; name the column exactly once.
    const std::string column = "column " + std::to_string(e.column());
    if (why.find(column) == std::string::npos) why += " (" + column + ")";
    throw Error(ErrorKind::scene, where, "expression '" + std::string(text) + "': " + why);
  }
}

std::string format_number(double v) {
  if (v == 0) return "0";  // also -0
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string trim_copy(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(first, last - first + 1));
}

std::optional<bool> parse_bool(std::string_view text) {
  std::string t = trim_copy(text);
  for (char& c : t)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (t == "1" || t == "true") return true;
  if (t == "0" || t == "false") return false;
  return std::nullopt;
}

void Reader::fail(const Element& el, std::string_view attr, const std::string& msg) const {
  throw Error(ErrorKind::scene, at(el, attr), msg);
}

double Reader::number(const Element& el, std::string_view attr, double fallback) const {
  const std::string* t = el.attribute(attr);
  return t ? evaluate_attribute(*t, *c_, at(el, attr)) : fallback;
}

std::optional<double> Reader::optional_number(const Element& el, std::string_view attr) const {
  const std::string* t = el.attribute(attr);
  if (!t) return std::nullopt;
  return evaluate_attribute(*t, *c_, at(el, attr));
}

double Reader::required_number(const Element& el, std::string_view attr) const {
  const std::string* t = el.attribute(attr);
  if (!t) fail(el, attr, "missing required attribute");
  return evaluate_attribute(*t, *c_, at(el, attr));
}

std::int64_t Reader::integer(const Element& el, std::string_view attr,
                             std::int64_t fallback) const {
  const std::string* t = el.attribute(attr);
  if (!t) return fallback;
  if (!t->empty() && (*t)[0] == '$') {
    std::int64_t v = 0;
    const auto r = std::from_chars(t->data() + 1, t->data() + t->size(), v, 16);
    if (r.ec == std::errc() && r.ptr == t->data() + t->size() && t->size() > 1) return v;
    fail(el, attr, "not a hexadecimal integer: '" + *t + "'");
  }
  const double v = evaluate_attribute(*t, *c_, at(el, attr));
  if (std::abs(v - std::round(v)) > 1e-9 || std::abs(v) > 9e15)
    fail(el, attr, "must be an integer, got " + format_number(v));
  return static_cast<std::int64_t>(std::llround(v));
}

int Reader::integer_in(const Element& el, std::string_view attr, int fallback, int min,
                       int max) const {
  const std::int64_t v = integer(el, attr, fallback);
  if (v < min || v > max)
    fail(el, attr,
         "must be an integer from " + std::to_string(min) + " to " + std::to_string(max) +
             ", got " + std::to_string(v));
  return static_cast<int>(v);
}

bool Reader::boolean(const Element& el, std::string_view attr, bool fallback) const {
  const std::string* t = el.attribute(attr);
  if (!t) return fallback;
  if (auto b = parse_bool(*t)) return *b;
  fail(el, attr, "must be a boolean (1, true, 0 or false), got '" + *t + "'");
}

std::string Reader::text(const Element& el, std::string_view attr,
                         std::string_view fallback) const {
  const std::string* t = el.attribute(attr);
  return t ? *t : std::string(fallback);
}

Vec3 Reader::xyz(const Element& el, Vec3 fallback) const {
  return {number(el, "x", fallback.x), number(el, "y", fallback.y), number(el, "z", fallback.z)};
}

Color Reader::color_rgb(const Element& el, Color color) const {
  auto channel = [&](std::string_view attr, double current) {
    if (!has(el, attr)) return current;
    const double v = static_cast<double>(integer(el, attr, 128));
    if (v < 0 || v > 255) fail(el, attr, "must be in [0, 255], got " + format_number(v));
    return v / 255.0;
  };
  // SimTwo resets every channel to 128 when the element is present but a channel is absent.
  Color c = color;
  c.r = channel("r", 128.0 / 255.0);
  c.g = channel("g", 128.0 / 255.0);
  c.b = channel("b", 128.0 / 255.0);
  return c;
}

Color color_from_tcolor(std::uint32_t bgr) {
  Color c;
  c.r = static_cast<double>(bgr & 0xFF) / 255.0;
  c.g = static_cast<double>((bgr >> 8) & 0xFF) / 255.0;
  c.b = static_cast<double>((bgr >> 16) & 0xFF) / 255.0;
  return c;
}

Color Reader::rgb24(const Element& el, std::string_view attr, Color fallback) const {
  const std::string* t = el.attribute(attr);
  if (!t) return fallback;
  std::string_view s = *t;
  if (!s.empty() && s[0] == '$') s.remove_prefix(1);
  std::uint32_t v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v, 16);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size() || v > 0xFFFFFF)
    fail(el, attr, "must be 6 hexadecimal digits BBGGRR, got '" + *t + "'");
  Color c = color_from_tcolor(v);
  c.a = fallback.a;
  return c;
}

}  // namespace s2sim::scene
