#pragma once
/// \file
/// `s2sim::Params` over a scene element: what a component (sensor, plugin instance) reads its
/// parameters through. Numbers are SimTwo expressions evaluated with the constants in scope
/// where the element stands; every error names file, element path and attribute (for an
/// attribute inherited from a `<default>`, the element it is written in).

#include <s2sim/kernel/scene.hpp>
#include <s2sim/params.hpp>

#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace s2sim::scene {

class ElementParams final : public Params {
 public:
  explicit ElementParams(ParamSource source);

  bool has(std::string_view path) const override;
  bool has_element(std::string_view path) const override;
  double number(std::string_view path, Range range = {}) const override;
  double number(std::string_view path, double fallback, Range range = {}) const override;
  std::int64_t integer(std::string_view path) const override;
  std::int64_t integer(std::string_view path, std::int64_t fallback) const override;
  bool boolean(std::string_view path, bool fallback) const override;
  std::string text(std::string_view path) const override;
  std::string text(std::string_view path, std::string_view fallback) const override;
  Vec3 vec3(std::string_view element_path, Vec3 fallback = {}) const override;
  std::string location() const override;
  Location where(std::string_view path) const override;
  std::string choice(std::string_view path, std::initializer_list<std::string_view> allowed,
                     std::string_view fallback) const override;

  const ParamSource& source() const { return source_; }

  /// Whether a getter (has() included) asked for attribute `attribute` of `element` (the
  /// component's element or one of its children), present or not.
  bool asked(const Element* element, const std::string& attribute) const {
    return asked_.count({element->path, attribute}) != 0;
  }
  /// The attribute names asked for on `element`, present or not: what a misspelt attribute
  /// was probably meant to be.
  std::vector<std::string> asked_on(const Element* element) const;

 private:
  /// An attribute path resolved: its element (nullptr when absent), the path that element
  /// has or would have, and the attribute name.
  struct Target {
    const Element* element = nullptr;
    std::string element_path;
    std::string attribute;
    const std::string* value = nullptr;  ///< raw text, nullptr when absent
  };
  Target resolve(std::string_view path) const;
  /// The element at a dotted element path ("" = the component's own), or nullptr.
  const Element* find_element(std::string_view path, std::string* element_path) const;
  [[noreturn]] void fail(const Target& t, const std::string& message) const;
  double evaluate(const Target& t) const;
  std::int64_t to_integer(const Target& t) const;
  void check(const Target& t, double v, const Range& range) const;

  ParamSource source_;
  ConstantTable empty_;  ///< used when the source has no constants
  /// Every (element path, attribute) a getter resolved, to warn about attributes nobody
  /// reads. Paths, not pointers: an ElementParams may be moved after a getter ran.
  mutable std::set<std::pair<std::string, std::string>> asked_;
};

}  // namespace s2sim::scene
