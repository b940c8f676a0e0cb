#pragma once
/// \file
/// Reading attribute values of SimTwo elements: numbers are expressions evaluated with the
/// constants in scope, and every failure is an `s2sim::Error` naming file, element path and
/// attribute. Shared by the loader and `ElementParams`.

#include <s2sim/kernel/scene.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace s2sim::scene {

/// Evaluates `text` with `constants`; a failure becomes an Error at `where` with the message
/// "expression '<text>': <why> (column N)".
double evaluate_attribute(std::string_view text, const ConstantTable& constants,
                          const Location& where);

/// Shortest decimal text of `v` ("0.1", "-90", "1e-05"), for messages and generated IDs.
std::string format_number(double v);

/// Whitespace-trimmed copy.
std::string trim_copy(std::string_view s);

/// Parses SimTwo booleans (`1`/`true`/`0`/`false`, any case); nullopt for anything else.
std::optional<bool> parse_bool(std::string_view text);

/// Attribute reader of one file, bound to the constants in scope (which may change while
/// the file is read: `<defines>` blocks in between sections).
class Reader {
 public:
  Reader(std::string file, const ConstantTable& constants)
      : file_(std::move(file)), c_(&constants) {}

  const std::string& file() const { return file_; }
  const ConstantTable& constants() const { return *c_; }
  void rebind(const ConstantTable& constants) { c_ = &constants; }

  Location at(const Element& el, std::string_view attr = {}) const {
    return Location{file_, el.path, std::string(attr)};
  }
  [[noreturn]] void fail(const Element& el, std::string_view attr, const std::string& msg) const;

  bool has(const Element& el, std::string_view attr) const { return el.attribute(attr) != nullptr; }
  /// An expression attribute, or `fallback` when absent.
  double number(const Element& el, std::string_view attr, double fallback) const;
  std::optional<double> optional_number(const Element& el, std::string_view attr) const;
  /// A required expression attribute.
  double required_number(const Element& el, std::string_view attr) const;
  /// An integer attribute: Pascal `StrToInt` syntax (decimal or `$hex`) or an expression with
  /// an integral value.
  std::int64_t integer(const Element& el, std::string_view attr, std::int64_t fallback) const;
  /// An integer from `min` to `max` (inclusive), or `fallback` when absent, as an `int`: the
  /// checked way to read a count, never truncating a 64-bit value (a located error instead).
  int integer_in(const Element& el, std::string_view attr, int fallback, int min, int max) const;
  bool boolean(const Element& el, std::string_view attr, bool fallback) const;
  std::string text(const Element& el, std::string_view attr, std::string_view fallback) const;
  /// The `x`, `y`, `z` attributes, each defaulting to `fallback`'s component.
  Vec3 xyz(const Element& el, Vec3 fallback = {}) const;
  /// `color_rgb r g b` (0..255) into `color`, keeping its alpha.
  Color color_rgb(const Element& el, Color color) const;
  /// A Windows TColor hex attribute (`rgb24`, byte order BBGGRR), keeping `fallback`'s alpha.
  Color rgb24(const Element& el, std::string_view attr, Color fallback) const;

 private:
  std::string file_;
  const ConstantTable* c_;
};

/// A TColor value ($00BBGGRR) as a colour.
Color color_from_tcolor(std::uint32_t bgr);

}  // namespace s2sim::scene
