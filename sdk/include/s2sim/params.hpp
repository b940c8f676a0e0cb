#pragma once
/// \file
/// A component's parameters, read from its XML element in the scene.

#include <s2sim/error.hpp>
#include <s2sim/math.hpp>

#include <cstdint>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>

namespace s2sim {

/// Accepted range of a number; `min`/`max` are inclusive unless the `_exclusive` flag is set.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;

  /// Strictly positive numbers.
  static constexpr Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true}; }
  /// Zero or more.
  static constexpr Range non_negative() { return {0.0}; }
  /// 0 to 1, both included (also the on/off inputs: 0 off, 1 on).
  static constexpr Range unit_interval() { return {0.0, 1.0}; }
};

/// Read-only view of a component's XML element. A `path` names an attribute: `"gain"` is the
/// attribute `gain` of the component's own element, `"motor.ri"` the attribute `ri` of its
/// first child `<motor>`, `"a.b.c"` the attribute `c` of `<a><b>`. Numbers are SimTwo
/// expressions evaluated with the constants in scope where the element stands.
///
/// Every getter throws `s2sim::Error` naming the file, the element and the attribute when the
/// value is present but unusable (a failing expression, a wrong type, out of `range`), and the
/// getters without a default also when it is absent.
class Params {
 public:
  virtual ~Params() = default;

  /// Whether the attribute at `path` is present.
  virtual bool has(std::string_view path) const = 0;
  /// Whether a child element `<name>` (dotted path allowed) is present.
  virtual bool has_element(std::string_view path) const = 0;

  /// A required number.
  virtual double number(std::string_view path, Range range = {}) const = 0;
  /// A number, or `fallback` when absent.
  virtual double number(std::string_view path, double fallback, Range range = {}) const = 0;
  /// A required integer (an expression whose value is integral).
  virtual std::int64_t integer(std::string_view path) const = 0;
  /// An integer, or `fallback` when absent.
  virtual std::int64_t integer(std::string_view path, std::int64_t fallback) const = 0;
  /// A boolean (`1`/`true`/`0`/`false`), or `fallback` when absent.
  virtual bool boolean(std::string_view path, bool fallback) const = 0;
  /// A required string, whitespace-trimmed.
  virtual std::string text(std::string_view path) const = 0;
  /// A string, or `fallback` when absent.
  virtual std::string text(std::string_view path, std::string_view fallback) const = 0;
  /// The `x`, `y`, `z` attributes of the element at `element_path`, each defaulting to
  /// `fallback`'s component.
  virtual Vec3 vec3(std::string_view element_path, Vec3 fallback = {}) const = 0;

  /// "file: element" of the component's element, for messages of the component's own.
  virtual std::string location() const = 0;

  /// Where the attribute at `path` is written (or would be, when absent): file, element path
  /// and attribute, to locate a component's own checks as the getters locate theirs:
  /// `throw Error(ErrorKind::scene, p.where("controller.mode"), "unknown mode 'x'")`. The
  /// default, for Params implementations outside the kernel, knows only location().
  virtual Location where(std::string_view path) const {
    return Location{"", location(), std::string(path)};
  }

  /// A keyword out of `allowed` (whitespace-trimmed, compared exactly), or `fallback` when
  /// absent: `p.choice("scan.mode", {"sweep", "instant"}, "sweep")`. A present value that is
  /// not in `allowed` throws naming the attribute and listing the allowed values.
  virtual std::string choice(std::string_view path, std::initializer_list<std::string_view> allowed,
                             std::string_view fallback) const = 0;

  /// An integer from `min` to `max` (inclusive), or `fallback` when absent, as an `int`. A
  /// value outside throws naming the attribute: the checked way to read a count, so that no
  /// 64-bit value is truncated into a narrower type.
  int integer_in(std::string_view path, int fallback, int min, int max) const {
    const std::int64_t v = integer(path, fallback);
    if (v < min || v > max)
      throw Error(ErrorKind::scene, where(path),
                  "must be an integer from " + std::to_string(min) + " to " + std::to_string(max) +
                      ", got " + std::to_string(v));
    return static_cast<int>(v);
  }
};

}  // namespace s2sim
