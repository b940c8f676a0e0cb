/// \file
/// SimTwo's expression language (simtwo-format.md §2.3): a recursive-descent parser that
/// evaluates while it parses. Every error is an ExpressionError carrying the 1-based column.
///
/// Decisions beyond the reference grammar:
/// * Logical operators are `.and.`, `.or.`, `.xor.` in any case. The closing dot is optional
///   (SimTwo itself only reads the leading one) and belongs to the operator only when it touches
///   the keyword: `1 .and.5` is `1 and 5`, `1 .and .5` is `1 and 0.5`.
/// * `int(x)` rounds half away from zero (`int(2.5)` = 3, `int(-2.5)` = -3). Delphi's Round,
///   which SimTwo uses, rounds half to even; the shipped samples never call int() (§2.3).
/// * Every intermediate value must be finite, so the error names the operation that failed.
/// * Nesting is limited (kMaxDepth) so hostile input cannot exhaust the stack.

#include "scene/expression.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace s2sim::scene {
namespace {

constexpr int kMaxDepth = 256;

bool is_letter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
bool is_name_char(char c) {
  return is_letter(c) || is_digit(c) || c == '_';
}
bool is_space(char c) {
  return c == ' ' || c == '\t';
}

char lower(char c) {
  return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (lower(a[i]) != lower(b[i])) return false;
  return true;
}

// Quotes a character for a message; control and non-ASCII bytes are shown as hex because
// printing them raw would garble the log line.
std::string describe(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u >= 0x20 && u < 0x7f) return std::string("'") + c + "'";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%s byte 0x%02X", u < 0x80 ? "control" : "non-ASCII",
                static_cast<unsigned>(u));
  return buf;
}

// Joins message parts (also avoids GCC 12's false -Wrestrict on `"literal" + std::string&&`).
template <typename... Parts>
std::string cat(const Parts&... parts) {
  std::string out;
  (out.append(std::string_view(parts)), ...);
  return out;
}

std::string format_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

enum class Logical { and_op, or_op, xor_op };

struct Function {
  std::string_view name;  // lower-case
  int arity;
  double (*apply)(const double* args);
  std::string_view domain;  // why a result may be non-finite, for the message
};

// clang-format off
constexpr std::array kFunctions = {
  Function{"pi", 0, [](const double*) { return std::numbers::pi; }, ""},
  Function{"e", 0, [](const double*) { return std::numbers::e; }, ""},
  Function{"sqrt", 1, [](const double* a) { return std::sqrt(a[0]); }, "the argument must be >= 0"},
  Function{"sqr", 1, [](const double* a) { return a[0] * a[0]; }, "overflow"},
  Function{"pow", 2, [](const double* a) { return std::pow(a[0], a[1]); },
           "negative base with a fractional exponent, zero to a negative power, or overflow"},
  Function{"dist2d", 2, [](const double* a) { return std::hypot(a[0], a[1]); }, "overflow"},
  Function{"sin", 1, [](const double* a) { return std::sin(a[0]); }, ""},
  Function{"cos", 1, [](const double* a) { return std::cos(a[0]); }, ""},
  Function{"tan", 1, [](const double* a) { return std::tan(a[0]); }, ""},
  Function{"atan", 1, [](const double* a) { return std::atan(a[0]); }, ""},
  Function{"arcsin", 1, [](const double* a) { return std::asin(a[0]); },
           "the argument must be in [-1, 1]"},
  Function{"arccos", 1, [](const double* a) { return std::acos(a[0]); },
           "the argument must be in [-1, 1]"},
  Function{"deg", 1, [](const double* a) { return a[0] * (180.0 / std::numbers::pi); }, "overflow"},
  Function{"rad", 1, [](const double* a) { return a[0] * (std::numbers::pi / 180.0); }, ""},
  Function{"not", 1, [](const double* a) { return a[0] == 0 ? 1.0 : 0.0; }, ""},
  Function{"max", 2, [](const double* a) { return a[0] > a[1] ? a[0] : a[1]; }, ""},
  Function{"min", 2, [](const double* a) { return a[0] < a[1] ? a[0] : a[1]; }, ""},
  // std::round: nearest, ties away from zero (see the file comment).
  Function{"int", 1, [](const double* a) { return std::round(a[0]); }, ""},
  Function{"abs", 1, [](const double* a) { return std::fabs(a[0]); }, ""},
  Function{"sign", 1, [](const double* a) { return a[0] > 0 ? 1.0 : (a[0] < 0 ? -1.0 : 0.0); }, ""},
  Function{"exp", 1, [](const double* a) { return std::exp(a[0]); }, "overflow"},
  Function{"frac", 1, [](const double* a) { return a[0] - std::trunc(a[0]); }, ""},
  Function{"ln", 1, [](const double* a) { return std::log(a[0]); }, "the argument must be > 0"},
  Function{"log10", 1, [](const double* a) { return std::log10(a[0]); },
           "the argument must be > 0"},
};
// clang-format on

const Function* find_function(std::string_view name) {
  for (const auto& f : kFunctions)
    if (iequals(f.name, name)) return &f;
  return nullptr;
}

std::string arguments(int n) {
  return std::to_string(n) + (n == 1 ? " argument" : " arguments");
}

class Parser {
 public:
  Parser(std::string_view text, const ConstantTable& constants)
      : text_(text), constants_(constants) {}

  double parse() {
    skip_space();
    if (at_end()) fail("empty expression", 0);
    const double value = expr();
    skip_space();
    if (!at_end()) fail_expected("an operator or the end of the expression");
    return value;
  }

 private:
  // Keeps recursion bounded: "((((...": every level passes through signed_factor().
  class DepthGuard {
   public:
    explicit DepthGuard(Parser& p) : p_(p) {
      if (++p_.depth_ > kMaxDepth)
        p_.fail(
            cat("expression nested too deeply (more than ", std::to_string(kMaxDepth), " levels)"),
            p_.pos_);
    }
    ~DepthGuard() { --p_.depth_; }
    DepthGuard(const DepthGuard&) = delete;
    DepthGuard& operator=(const DepthGuard&) = delete;

   private:
    Parser& p_;
  };

  bool at_end() const { return pos_ >= text_.size(); }
  char peek(std::size_t ahead = 0) const {
    return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0';
  }
  void skip_space() {
    while (!at_end() && is_space(text_[pos_]))
      ++pos_;
  }

  [[noreturn]] void fail(const std::string& message, std::size_t pos,
                         const std::string& hint = "") const {
    throw ExpressionError(cat(message, " at column ", std::to_string(pos + 1), hint), pos + 1);
  }

  // The current character cannot continue the expression: explain what is there.
  [[noreturn]] void fail_expected(const std::string& expected) const {
    if (at_end()) fail(cat("unexpected end of expression (expected ", expected, ")"), pos_);
    const char c = peek();
    if (c == ')') fail("unbalanced parentheses: unexpected ')'", pos_);
    if (c == '.' && is_letter(peek(1))) {
      std::size_t end = pos_ + 1;
      while (end < text_.size() && is_name_char(text_[end]))
        ++end;
      fail(cat("unknown operator '", text_.substr(pos_, end - pos_),
               "' (logical operators are .and. .or. .xor.)"),
           pos_);
    }
    fail(cat("unexpected ", describe(c), " (expected ", expected, ")"), pos_);
  }

  // A logical operator at `at` ('.' + and/or/xor as a whole word); returns its length with
  // the closing dot when that dot touches the keyword.
  std::optional<std::pair<Logical, std::size_t>> logical_at(std::size_t at) const {
    if (at >= text_.size() || text_[at] != '.') return std::nullopt;
    std::size_t end = at + 1;
    while (end < text_.size() && is_name_char(text_[end]))
      ++end;
    const std::string_view word = text_.substr(at + 1, end - at - 1);
    Logical op;
    if (iequals(word, "and")) {
      op = Logical::and_op;
    } else if (iequals(word, "or")) {
      op = Logical::or_op;
    } else if (iequals(word, "xor")) {
      op = Logical::xor_op;
    } else {
      return std::nullopt;
    }
    if (end < text_.size() && text_[end] == '.') ++end;
    return std::pair{op, end - at};
  }

  double checked(double value, std::size_t pos, const char* operation) const {
    if (!std::isfinite(value)) fail(cat("non-finite result of ", operation), pos);
    return value;
  }

  double expr() {
    double value = relation();
    for (;;) {
      skip_space();
      const auto op = logical_at(pos_);
      if (!op) return value;
      pos_ += op->second;
      const bool a = value != 0;
      const bool b = relation() != 0;
      switch (op->first) {
        case Logical::and_op:
          value = (a && b) ? 1 : 0;
          break;
        case Logical::or_op:
          value = (a || b) ? 1 : 0;
          break;
        case Logical::xor_op:
          value = (a != b) ? 1 : 0;
          break;
      }
    }
  }

  double relation() {
    double value = sum();
    for (;;) {
      skip_space();
      const char c = peek();
      const char n = peek(1);
      std::string_view op;
      if ((c == '<' && (n == '=' || n == '>')) || (c == '>' && n == '=')) {
        op = text_.substr(pos_, 2);
      } else if (c == '<' || c == '>' || c == '=') {
        op = text_.substr(pos_, 1);
      } else {
        return value;
      }
      pos_ += op.size();
      const double rhs = sum();
      bool r = false;
      if (op == "<") r = value < rhs;
      if (op == ">") r = value > rhs;
      if (op == "=") r = value == rhs;
      if (op == "<=") r = value <= rhs;
      if (op == ">=") r = value >= rhs;
      if (op == "<>") r = value != rhs;
      value = r ? 1 : 0;
    }
  }

  double sum() {
    double value = term();
    for (;;) {
      skip_space();
      const char c = peek();
      if (c != '+' && c != '-') return value;
      const std::size_t op_pos = pos_++;
      const double rhs = term();
      value = c == '+' ? checked(value + rhs, op_pos, "'+' (overflow)")
                       : checked(value - rhs, op_pos, "'-' (overflow)");
    }
  }

  double term() {
    double value = signed_factor();
    for (;;) {
      skip_space();
      const char c = peek();
      if (c != '*' && c != '/') return value;
      const std::size_t op_pos = pos_++;
      const double rhs = signed_factor();
      if (c == '*') {
        value = checked(value * rhs, op_pos, "'*' (overflow)");
      } else {
        if (rhs == 0) fail("division by zero", op_pos);
        value = checked(value / rhs, op_pos, "'/' (overflow)");
      }
    }
  }

  double signed_factor() {
    DepthGuard guard(*this);
    skip_space();
    const char c = peek();
    if (c == '+' || c == '-') ++pos_;
    const double value = factor();
    return c == '-' ? -value : value;
  }

  double factor() {
    skip_space();
    const char c = peek();
    if (is_digit(c) || (c == '.' && is_digit(peek(1)))) return number();
    if (is_letter(c)) return name();
    if (c == '(') {
      const std::size_t open = pos_++;
      const double value = expr();
      skip_space();
      if (at_end())
        fail("unbalanced parentheses: missing ')'", pos_,
             cat(" (to close the '(' at column ", std::to_string(open + 1), ")"));
      if (peek() != ')') fail_expected("an operator or ')'");
      ++pos_;
      return value;
    }
    if (c == '+' || c == '-')
      fail(cat("unexpected '", std::string(1, c), "' (only one sign)"), pos_);
    if (c == ')') fail("unexpected ')' (expected a number, a name or '(')", pos_);
    fail_expected("a number, a name or '('");
  }

  double number() {
    const std::size_t start = pos_;
    std::size_t int_digits = 0;  // significant integer digits, for the range message
    while (is_digit(peek())) {
      if (int_digits > 0 || peek() != '0') ++int_digits;
      ++pos_;
    }
    std::size_t frac_zeros = 0;  // leading zeros of the fraction
    if (peek() == '.' && !logical_at(pos_)) {
      if (!is_digit(peek(1))) fail("digits required after the decimal point", pos_);
      ++pos_;
      bool leading = true;
      while (is_digit(peek())) {
        if (leading && peek() == '0')
          ++frac_zeros;
        else
          leading = false;
        ++pos_;
      }
    }
    long long exponent = 0;
    if (peek() == 'e' || peek() == 'E') {
      const std::size_t e_pos = pos_++;
      bool negative = false;
      if (peek() == '+' || peek() == '-') negative = text_[pos_++] == '-';
      if (!is_digit(peek())) fail("digits required in the exponent", e_pos);
      while (is_digit(peek())) {
        if (exponent < 100000) exponent = exponent * 10 + (text_[pos_] - '0');
        ++pos_;
      }
      if (negative) exponent = -exponent;
    }
    double value = 0;
    const char* first = text_.data() + start;
    const char* last = text_.data() + pos_;
    const auto [ptr, ec] = std::from_chars(first, last, value, std::chars_format::general);
    if (ec == std::errc::result_out_of_range) {
      // Decide overflow vs underflow by the decimal magnitude; tiny values are just 0.
      const long long magnitude = (int_digits > 0 ? static_cast<long long>(int_digits)
                                                  : -static_cast<long long>(frac_zeros)) +
                                  exponent;
      if (magnitude < 0) return 0.0;
      fail("number too large", start);
    }
    if (ec != std::errc() || ptr != last) fail("malformed number", start);
    return value;
  }

  double name() {
    const std::size_t start = pos_;
    while (is_name_char(peek()))
      ++pos_;
    const std::string_view id = text_.substr(start, pos_ - start);
    const std::string quoted = cat("'", id, "'");
    skip_space();
    if (peek() == '(') return call(id, start);

    if (const auto value = constants_.find(id)) {
      if (!std::isfinite(*value)) fail(cat("constant ", quoted, " is not finite"), start);
      return *value;
    }
    std::string hint;
    if (const Function* f = find_function(id)) {
      // SimTwo quirk kept: pi and e are functions, never constants.
      hint = f->arity == 0 ? cat(" (did you mean ", id, "()?)")
                           : cat(" (", quoted, " is a function: write ", id, "(...))");
    }
    fail(cat("unknown constant ", quoted), start, hint);
  }

  double call(std::string_view id, std::size_t start) {
    const std::string quoted = cat("'", id, "'");
    const Function* f = find_function(id);
    if (!f) {
      std::string hint;
      if (iequals(id, "if"))
        hint = " (SimTwo has no usable if())";
      else if (constants_.find(id))
        hint = cat(" (", quoted, " is a constant)");
      fail(cat("unknown function ", quoted), start, hint);
    }
    ++pos_;  // '('
    std::array<double, 2> args{};
    int count = 0;
    skip_space();
    if (peek() == ')') {
      ++pos_;
    } else {
      for (;;) {
        const double value = expr();
        if (count < static_cast<int>(args.size())) args[count] = value;
        ++count;
        skip_space();
        if (peek() == ',') {
          ++pos_;
          continue;
        }
        if (peek() == ')') {
          ++pos_;
          break;
        }
        if (at_end())
          fail("unbalanced parentheses: missing ')'", pos_, cat(" (to close ", id, "'s '(')"));
        fail_expected("',' or ')'");
      }
    }
    if (count != f->arity)
      fail(cat("function ", quoted, " expects ", arguments(f->arity), ", got ",
               std::to_string(count)),
           start);
    const double value = f->apply(args.data());
    if (!std::isfinite(value)) {
      std::string call_text = cat(id, "(");
      for (int i = 0; i < count; ++i)
        call_text += cat(i ? ", " : "", format_number(args[i]));
      call_text += ")";
      fail(cat("non-finite result of ", call_text), start,
           f->domain.empty() ? "" : cat(" (", f->domain, ")"));
    }
    return value;
  }

  std::string_view text_;
  const ConstantTable& constants_;
  std::size_t pos_ = 0;
  int depth_ = 0;
};

}  // namespace

double evaluate(std::string_view text, const ConstantTable& constants) {
  return Parser(text, constants).parse();
}

}  // namespace s2sim::scene
