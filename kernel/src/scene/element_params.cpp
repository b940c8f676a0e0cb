/// \file
/// ElementParams: dotted paths over an Element, expressions, ranges, located errors.

#include "scene/element_params.hpp"

#include "scene/attributes.hpp"

#include <cmath>

namespace s2sim::scene {
namespace {

std::string describe(const Range& r) {
  const bool has_min = std::isfinite(r.min), has_max = std::isfinite(r.max);
  const std::string lo = (r.min_exclusive ? "> " : ">= ") + format_number(r.min);
  const std::string hi = (r.max_exclusive ? "< " : "<= ") + format_number(r.max);
  if (has_min && has_max) return "must be " + lo + " and " + hi;
  if (has_min) return "must be " + lo;
  return "must be " + hi;
}

}  // namespace

ElementParams::ElementParams(ParamSource source) : source_(std::move(source)) {}

const Element* ElementParams::find_element(std::string_view path, std::string* element_path) const {
  const Element* el = &source_.element;
  std::string where = el->path;
  while (!path.empty()) {
    const auto dot = path.find('.');
    const std::string_view name = path.substr(0, dot);
    path = dot == std::string_view::npos ? std::string_view{} : path.substr(dot + 1);
    const Element* next = el ? el->child(name) : nullptr;
    where = next ? next->path : where + "/" + std::string(name);
    el = next;
  }
  if (element_path) *element_path = where;
  return el;
}

ElementParams::Target ElementParams::resolve(std::string_view path) const {
  Target t;
  const auto dot = path.rfind('.');
  t.attribute = std::string(dot == std::string_view::npos ? path : path.substr(dot + 1));
  t.element = find_element(dot == std::string_view::npos ? std::string_view{} : path.substr(0, dot),
                           &t.element_path);
  if (!t.element) return t;
  asked_.emplace(t.element->path, t.attribute);
  const auto& attributes = t.element->attributes;
  for (std::size_t i = 0; i < attributes.size(); ++i)
    if (attributes[i].first == t.attribute) {
      t.value = &attributes[i].second;
      if (t.element->attribute_paths.size() == attributes.size())
        t.element_path = t.element->attribute_paths[i];  // inherited: where it is written
      break;
    }
  return t;
}

void ElementParams::fail(const Target& t, const std::string& message) const {
  throw Error(ErrorKind::scene, Location{source_.file, t.element_path, t.attribute}, message);
}

double ElementParams::evaluate(const Target& t) const {
  const ConstantTable& c = source_.constants ? *source_.constants : empty_;
  return evaluate_attribute(*t.value, c, Location{source_.file, t.element_path, t.attribute});
}

void ElementParams::check(const Target& t, double v, const Range& r) const {
  const bool below = r.min_exclusive ? !(v > r.min) : !(v >= r.min);
  const bool above = r.max_exclusive ? !(v < r.max) : !(v <= r.max);
  if (below || above) fail(t, describe(r) + ", got " + format_number(v));
}

std::int64_t ElementParams::to_integer(const Target& t) const {
  const double v = evaluate(t);
  if (!(std::abs(v - std::round(v)) <= 1e-9) || std::abs(v) > 9e15)
    fail(t, "must be an integer, got " + format_number(v));
  return static_cast<std::int64_t>(std::llround(v));
}

bool ElementParams::has(std::string_view path) const {
  return resolve(path).value != nullptr;
}

bool ElementParams::has_element(std::string_view path) const {
  return find_element(path, nullptr) != nullptr;
}

double ElementParams::number(std::string_view path, Range range) const {
  const Target t = resolve(path);
  if (!t.value) fail(t, "missing required attribute");
  const double v = evaluate(t);
  check(t, v, range);
  return v;
}

double ElementParams::number(std::string_view path, double fallback, Range range) const {
  const Target t = resolve(path);
  if (!t.value) return fallback;
  const double v = evaluate(t);
  check(t, v, range);
  return v;
}

std::int64_t ElementParams::integer(std::string_view path) const {
  const Target t = resolve(path);
  if (!t.value) fail(t, "missing required attribute");
  return to_integer(t);
}

std::int64_t ElementParams::integer(std::string_view path, std::int64_t fallback) const {
  const Target t = resolve(path);
  return t.value ? to_integer(t) : fallback;
}

bool ElementParams::boolean(std::string_view path, bool fallback) const {
  const Target t = resolve(path);
  if (!t.value) return fallback;
  if (auto b = parse_bool(*t.value)) return *b;
  fail(t, "must be a boolean (1, true, 0 or false), got '" + *t.value + "'");
}

std::string ElementParams::text(std::string_view path) const {
  const Target t = resolve(path);
  if (!t.value) fail(t, "missing required attribute");
  return trim_copy(*t.value);
}

std::string ElementParams::text(std::string_view path, std::string_view fallback) const {
  const Target t = resolve(path);
  return t.value ? trim_copy(*t.value) : std::string(fallback);
}

Vec3 ElementParams::vec3(std::string_view element_path, Vec3 fallback) const {
  const std::string prefix = element_path.empty() ? "" : std::string(element_path) + ".";
  return {number(prefix + "x", fallback.x), number(prefix + "y", fallback.y),
          number(prefix + "z", fallback.z)};
}

Location ElementParams::where(std::string_view path) const {
  const Target t = resolve(path);
  return Location{source_.file, t.element_path, t.attribute};
}

std::string ElementParams::choice(std::string_view path,
                                  std::initializer_list<std::string_view> allowed,
                                  std::string_view fallback) const {
  const Target t = resolve(path);
  if (!t.value) return std::string(fallback);
  std::string value = trim_copy(*t.value);
  for (std::string_view a : allowed)
    if (value == a) return value;
  // "must be 'a'", "must be 'a' or 'b'", "must be 'a', 'b' or 'c'".
  std::string list;
  std::size_t i = 0;
  for (std::string_view a : allowed) {
    if (i > 0) list += i + 1 == allowed.size() ? " or " : ", ";
    list.append(1, '\'').append(a).append(1, '\'');
    ++i;
  }
  fail(t, "must be " + list + ", got '" + value + "'");
}

std::vector<std::string> ElementParams::asked_on(const Element* element) const {
  std::vector<std::string> names;
  for (auto it = asked_.lower_bound({element->path, std::string()});
       it != asked_.end() && it->first == element->path; ++it)
    names.push_back(it->second);
  return names;
}

std::string ElementParams::location() const {
  return Location{source_.file, source_.element.path, ""}.str();
}

}  // namespace s2sim::scene
