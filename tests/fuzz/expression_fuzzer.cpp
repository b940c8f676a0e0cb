/// \file
/// libFuzzer target for SimTwo's expression language (kernel/src/scene/expression.hpp): any
/// text either evaluates to a finite number or throws ExpressionError naming a column inside
/// the text. Anything else (another exception, a crash, a non-finite result, a sanitizer
/// report) is a finding.

#include "scene/expression.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const s2sim::scene::ConstantTable constants = [] {
    s2sim::scene::ConstantTable t;
    t.set("A", 2);
    t.set("LONG_NAME", -1e300);
    return t;
  }();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const double v = s2sim::scene::evaluate(text, constants);
    if (!std::isfinite(v)) std::abort();
  } catch (const s2sim::scene::ExpressionError& e) {
    if (e.column() > text.size() + 1) std::abort();
  }
  return 0;
}
