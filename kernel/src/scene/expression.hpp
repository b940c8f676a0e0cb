#pragma once
/// \file
/// SimTwo's expression language (simtwo-format.md §2.3): numbers, constants, + - * /,
/// comparisons (result 1 or 0), dotted logical operators `.and.` `.or.` `.xor.`, unary signs,
/// parentheses and the function table (`pi()`, `sqrt(x)`, `pow(x,y)`, ...). Names are
/// case-insensitive.

#include <s2sim/kernel/scene.hpp>

#include <stdexcept>
#include <string>
#include <string_view>

namespace s2sim::scene {

/// A failed evaluation: `column` is the 1-based position in the expression text where the
/// problem was found; `what()` is the bare message (the caller adds file/element/attribute).
class ExpressionError : public std::runtime_error {
 public:
  ExpressionError(const std::string& message, std::size_t column)
      : std::runtime_error(message), column_(column) {}
  std::size_t column() const { return column_; }

 private:
  std::size_t column_;
};

/// Evaluates `text` with the given constants. Throws ExpressionError on a syntax error, an
/// unknown constant or function, a wrong argument count, or a non-finite result (division by
/// zero, sqrt of a negative number...).
double evaluate(std::string_view text, const ConstantTable& constants);

}  // namespace s2sim::scene
