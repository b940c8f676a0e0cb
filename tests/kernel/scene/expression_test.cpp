// Tests of SimTwo's expression language (simtwo-format.md §2.3) and of ConstantTable (§2.1).

#include "scene/expression.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace s2sim::scene {
namespace {

using ::testing::HasSubstr;

double eval(std::string_view text) {
  return evaluate(text, ConstantTable{});
}

struct Failure {
  bool thrown = false;
  std::string message;
  std::size_t column = 0;
};

Failure failure_of(std::string_view text, const ConstantTable& constants = ConstantTable{}) {
  Failure f;
  try {
    const double v = evaluate(text, constants);
    ADD_FAILURE() << "'" << text << "' evaluated to " << v << " instead of failing";
  } catch (const ExpressionError& e) {
    f.thrown = true;
    f.message = e.what();
    f.column = e.column();
  }
  return f;
}

// Asserts that `text` fails at `column` with a message containing `substring`, and that the
// message repeats the column.
#define EXPECT_EXPR_ERROR(text, col, substring)                                                    \
  do {                                                                                             \
    const Failure f_ = failure_of(text);                                                           \
    EXPECT_TRUE(f_.thrown) << (text);                                                              \
    EXPECT_EQ(f_.column, std::size_t{col}) << (text) << ": " << f_.message;                        \
    EXPECT_THAT(f_.message, HasSubstr(substring)) << (text);                                       \
    EXPECT_THAT(f_.message, HasSubstr(std::string("at column ") + std::to_string(col))) << (text); \
  } while (0)

// ---------------------------------------------------------------------------------------------
// Numbers and whitespace

TEST(Expression, Numbers) {
  EXPECT_DOUBLE_EQ(eval("0"), 0);
  EXPECT_DOUBLE_EQ(eval("42"), 42);
  EXPECT_DOUBLE_EQ(eval("007"), 7);
  EXPECT_DOUBLE_EQ(eval("3.25"), 3.25);
  EXPECT_DOUBLE_EQ(eval(".5"), 0.5);
  EXPECT_DOUBLE_EQ(eval("1e-3"), 0.001);
  EXPECT_DOUBLE_EQ(eval("1E+2"), 100);
  EXPECT_DOUBLE_EQ(eval("1e2"), 100);
  EXPECT_DOUBLE_EQ(eval("2.5e2"), 250);
  EXPECT_DOUBLE_EQ(eval(".5E1"), 5);
  EXPECT_DOUBLE_EQ(eval("0.22+0.5"), 0.72);
}

TEST(Expression, TinyNumbersUnderflowToZero) {
  EXPECT_EQ(eval("1e-400"), 0);
  EXPECT_EQ(eval("0.000001e-320"), 0);
}

TEST(Expression, Whitespace) {
  EXPECT_DOUBLE_EQ(eval(" \t1 +\t2 "), 3);
  EXPECT_DOUBLE_EQ(eval("\t\t7\t"), 7);
  EXPECT_DOUBLE_EQ(eval("sqrt ( 4 )"), 2);
  EXPECT_DOUBLE_EQ(eval("max( 1 , 2 )"), 2);
}

// ---------------------------------------------------------------------------------------------
// Arithmetic, signs, precedence, associativity

TEST(Expression, Arithmetic) {
  EXPECT_DOUBLE_EQ(eval("2+3"), 5);
  EXPECT_DOUBLE_EQ(eval("2-3"), -1);
  EXPECT_DOUBLE_EQ(eval("2*3"), 6);
  EXPECT_DOUBLE_EQ(eval("3/4"), 0.75);
}

TEST(Expression, Precedence) {
  EXPECT_DOUBLE_EQ(eval("2+3*4"), 14);
  EXPECT_DOUBLE_EQ(eval("2*3+4"), 10);
  EXPECT_DOUBLE_EQ(eval("(2+3)*4"), 20);
  EXPECT_DOUBLE_EQ(eval("2+12/4"), 5);
  EXPECT_DOUBLE_EQ(eval("((((1))))"), 1);
  EXPECT_DOUBLE_EQ(eval("2*(3+(4-1))*2"), 24);
}

TEST(Expression, LeftAssociative) {
  EXPECT_DOUBLE_EQ(eval("10-4-3"), 3);
  EXPECT_DOUBLE_EQ(eval("1-2+3"), 2);
  EXPECT_DOUBLE_EQ(eval("64/4/2"), 8);
  EXPECT_DOUBLE_EQ(eval("8/4*2"), 4);
}

TEST(Expression, UnarySigns) {
  EXPECT_DOUBLE_EQ(eval("+ 0.01"), 0.01);
  EXPECT_DOUBLE_EQ(eval("-3"), -3);
  EXPECT_DOUBLE_EQ(eval("- 3"), -3);
  EXPECT_DOUBLE_EQ(eval("+3"), 3);
  EXPECT_DOUBLE_EQ(eval("2*-3"), -6);
  EXPECT_DOUBLE_EQ(eval("2/-4"), -0.5);
  EXPECT_DOUBLE_EQ(eval("-2*3"), -6);
  EXPECT_DOUBLE_EQ(eval("2--3"), 5);
  EXPECT_DOUBLE_EQ(eval("2-+3"), -1);
  EXPECT_DOUBLE_EQ(eval("-(-2)"), 2);
  EXPECT_DOUBLE_EQ(eval("-sqrt(4)"), -2);
  EXPECT_DOUBLE_EQ(eval("-.5"), -0.5);
}

TEST(Expression, SamplesFromShippedScenes) {
  ConstantTable t;
  t.set("x_n", 2);
  t.set("claw_gap", 0.1);
  t.set("claw_width", 0.02);
  EXPECT_DOUBLE_EQ(evaluate("2.14 * x_n", t), 4.28);
  EXPECT_DOUBLE_EQ(evaluate("+ 0.01", t), 0.01);
  EXPECT_DOUBLE_EQ(evaluate("(-claw_gap/2 - claw_width/2) * -sqrt(3)/2", t),
                   0.06 * std::sqrt(3.0) / 2);
}

// ---------------------------------------------------------------------------------------------
// Comparisons and logical operators

TEST(Expression, Comparisons) {
  EXPECT_EQ(eval("1<2"), 1);
  EXPECT_EQ(eval("2<1"), 0);
  EXPECT_EQ(eval("1<1"), 0);
  EXPECT_EQ(eval("2>1"), 1);
  EXPECT_EQ(eval("1>2"), 0);
  EXPECT_EQ(eval("1=1"), 1);
  EXPECT_EQ(eval("1=2"), 0);
  EXPECT_EQ(eval("1<=1"), 1);
  EXPECT_EQ(eval("0<=1"), 1);
  EXPECT_EQ(eval("2<=1"), 0);
  EXPECT_EQ(eval("1>=1"), 1);
  EXPECT_EQ(eval("2>=1"), 1);
  EXPECT_EQ(eval("0>=1"), 0);
  EXPECT_EQ(eval("1<>2"), 1);
  EXPECT_EQ(eval("1<>1"), 0);
  EXPECT_EQ(eval("1 < 2"), 1);
  EXPECT_EQ(eval("-1 < -0.5"), 1);
}

TEST(Expression, ComparisonsBindLooserThanArithmetic) {
  EXPECT_EQ(eval("1+1=2"), 1);
  EXPECT_EQ(eval("2*3>5"), 1);
  EXPECT_EQ(eval("1<2+0"), 1);
  EXPECT_EQ(eval("(1<2)*5"), 5);
  // Left-associative: (3>2)>1 is 1>1.
  EXPECT_EQ(eval("3>2>1"), 0);
  EXPECT_EQ(eval("1<2=1"), 1);
}

TEST(Expression, LogicalTruthTables) {
  EXPECT_EQ(eval("0 .and. 0"), 0);
  EXPECT_EQ(eval("0 .and. 1"), 0);
  EXPECT_EQ(eval("1 .and. 0"), 0);
  EXPECT_EQ(eval("1 .and. 1"), 1);
  EXPECT_EQ(eval("0 .or. 0"), 0);
  EXPECT_EQ(eval("0 .or. 1"), 1);
  EXPECT_EQ(eval("1 .or. 0"), 1);
  EXPECT_EQ(eval("1 .or. 1"), 1);
  EXPECT_EQ(eval("0 .xor. 0"), 0);
  EXPECT_EQ(eval("0 .xor. 1"), 1);
  EXPECT_EQ(eval("1 .xor. 0"), 1);
  EXPECT_EQ(eval("1 .xor. 1"), 0);
}

TEST(Expression, LogicalTreatsNonZeroAsTrue) {
  EXPECT_EQ(eval("2 .and. -0.5"), 1);
  EXPECT_EQ(eval("-3 .xor. 7"), 0);
  EXPECT_EQ(eval("0.001 .or. 0"), 1);
  EXPECT_EQ(eval("5 .and. 0"), 0);
}

TEST(Expression, LogicalSpellings) {
  EXPECT_EQ(eval("1 .AND. 1"), 1);
  EXPECT_EQ(eval("1 .Or. 0"), 1);
  EXPECT_EQ(eval("1 .XOR. 1"), 0);
  EXPECT_EQ(eval("1.and.1"), 1);  // the number stops before ".and."
  EXPECT_EQ(eval("1.5.and.0"), 0);
  EXPECT_EQ(eval("1 .and 1"), 1);  // SimTwo's own form: no closing dot
  EXPECT_EQ(eval("0 .or 1"), 1);
  EXPECT_EQ(eval("(1).and.(0)"), 0);
  // The closing dot belongs to the operator only when it touches the keyword.
  EXPECT_EQ(eval("1 .and.5 - 5"), 0);   // 1 and (5-5)
  EXPECT_EQ(eval("1 .and .5 - 5"), 1);  // 1 and (0.5-5)
  EXPECT_EQ(eval("1 .and..5"), 1);
}

TEST(Expression, LogicalPrecedenceAndAssociativity) {
  EXPECT_EQ(eval("1 < 2 .and. 3 < 2"), 0);
  EXPECT_EQ(eval("1 < 2 .or. 3 < 2"), 1);
  EXPECT_EQ(eval("1+1 .and. 0*5"), 0);
  // One level, left to right: (1 or 0) and 0.
  EXPECT_EQ(eval("1 .or. 0 .and. 0"), 0);
  EXPECT_EQ(eval("0 .and. 0 .or. 1"), 1);
  EXPECT_EQ(eval("1 .xor. 1 .xor. 1"), 1);
  EXPECT_EQ(eval("not(1 .and. 0)"), 1);
  EXPECT_EQ(eval("max(1 .and. 0, 2<3)"), 1);
}

// ---------------------------------------------------------------------------------------------
// Functions

TEST(Expression, Constants) {
  EXPECT_DOUBLE_EQ(eval("pi()"), kPi);
  EXPECT_DOUBLE_EQ(eval("e()"), std::numbers::e);
  EXPECT_DOUBLE_EQ(eval("2*pi()"), 2 * kPi);
}

TEST(Expression, PowersAndRoots) {
  EXPECT_DOUBLE_EQ(eval("sqrt(16)"), 4);
  EXPECT_DOUBLE_EQ(eval("sqrt(0)"), 0);
  EXPECT_DOUBLE_EQ(eval("sqrt(2)"), std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(eval("sqr(-3)"), 9);
  EXPECT_DOUBLE_EQ(eval("sqr(0.5)"), 0.25);
  EXPECT_DOUBLE_EQ(eval("pow(2,10)"), 1024);
  EXPECT_DOUBLE_EQ(eval("pow(2,-1)"), 0.5);
  EXPECT_DOUBLE_EQ(eval("pow(9,0.5)"), 3);
  EXPECT_DOUBLE_EQ(eval("pow(-2,3)"), -8);
  EXPECT_DOUBLE_EQ(eval("pow(0,0)"), 1);
  EXPECT_DOUBLE_EQ(eval("dist2d(3,4)"), 5);
  EXPECT_DOUBLE_EQ(eval("dist2d(-3,-4)"), 5);
  EXPECT_DOUBLE_EQ(eval("exp(0)"), 1);
  EXPECT_DOUBLE_EQ(eval("exp(1)"), std::numbers::e);
  EXPECT_DOUBLE_EQ(eval("ln(e())"), 1);
  EXPECT_DOUBLE_EQ(eval("ln(1)"), 0);
  EXPECT_DOUBLE_EQ(eval("log10(1000)"), 3);
  EXPECT_DOUBLE_EQ(eval("log10(0.01)"), -2);
}

TEST(Expression, Trigonometry) {
  EXPECT_NEAR(eval("sin(0)"), 0, 1e-15);
  EXPECT_DOUBLE_EQ(eval("sin(pi()/2)"), 1);
  EXPECT_DOUBLE_EQ(eval("sin(-pi()/6)"), -0.5);
  EXPECT_DOUBLE_EQ(eval("cos(0)"), 1);
  EXPECT_DOUBLE_EQ(eval("cos(pi())"), -1);
  EXPECT_DOUBLE_EQ(eval("tan(pi()/4)"), 1);
  EXPECT_NEAR(eval("tan(0)"), 0, 1e-15);
  EXPECT_DOUBLE_EQ(eval("atan(1)"), kPi / 4);
  EXPECT_DOUBLE_EQ(eval("atan(-1)"), -kPi / 4);
  EXPECT_DOUBLE_EQ(eval("arcsin(1)"), kPi / 2);
  EXPECT_DOUBLE_EQ(eval("arcsin(-0.5)"), -kPi / 6);
  EXPECT_DOUBLE_EQ(eval("arccos(0)"), kPi / 2);
  EXPECT_DOUBLE_EQ(eval("arccos(1)"), 0);
  EXPECT_DOUBLE_EQ(eval("arccos(-1)"), kPi);
  EXPECT_DOUBLE_EQ(eval("deg(pi())"), 180);
  EXPECT_DOUBLE_EQ(eval("deg(-pi()/2)"), -90);
  EXPECT_DOUBLE_EQ(eval("rad(180)"), kPi);
  EXPECT_DOUBLE_EQ(eval("rad(90)"), kPi / 2);
  EXPECT_DOUBLE_EQ(eval("deg(rad(37))"), 37);
}

TEST(Expression, LogicAndSelection) {
  EXPECT_EQ(eval("not(0)"), 1);
  EXPECT_EQ(eval("not(3)"), 0);
  EXPECT_EQ(eval("not(-0.1)"), 0);
  EXPECT_EQ(eval("not(not(5))"), 1);
  EXPECT_EQ(eval("max(2,3)"), 3);
  EXPECT_EQ(eval("max(3,2)"), 3);
  EXPECT_EQ(eval("max(-1,-2)"), -1);
  EXPECT_EQ(eval("min(2,3)"), 2);
  EXPECT_EQ(eval("min(3,2)"), 2);
  EXPECT_EQ(eval("min(-1,-2)"), -2);
}

TEST(Expression, Rounding) {
  EXPECT_EQ(eval("int(2.4)"), 2);
  EXPECT_EQ(eval("int(2.6)"), 3);
  EXPECT_EQ(eval("int(-2.4)"), -2);
  EXPECT_EQ(eval("int(-2.6)"), -3);
  // Ties round half away from zero (Delphi's Round would give 2 and -2).
  EXPECT_EQ(eval("int(2.5)"), 3);
  EXPECT_EQ(eval("int(-2.5)"), -3);
  EXPECT_EQ(eval("int(0.5)"), 1);
  EXPECT_EQ(eval("int(3.5)"), 4);
  EXPECT_EQ(eval("int(7)"), 7);
  EXPECT_DOUBLE_EQ(eval("frac(2.75)"), 0.75);
  EXPECT_DOUBLE_EQ(eval("frac(-2.75)"), -0.75);  // x - trunc(x) keeps the sign
  EXPECT_EQ(eval("frac(3)"), 0);
  EXPECT_EQ(eval("abs(-2.5)"), 2.5);
  EXPECT_EQ(eval("abs(2.5)"), 2.5);
  EXPECT_EQ(eval("abs(0)"), 0);
  EXPECT_EQ(eval("sign(-3)"), -1);
  EXPECT_EQ(eval("sign(0)"), 0);
  EXPECT_EQ(eval("sign(0.2)"), 1);
}

TEST(Expression, NestedCallsAndExpressionArguments) {
  EXPECT_DOUBLE_EQ(eval("max(min(1,2), sqrt(pow(3,2)))"), 3);
  EXPECT_DOUBLE_EQ(eval("pow(2, 1+2)"), 8);
  EXPECT_DOUBLE_EQ(eval("sqrt(sqr(-5))"), 5);
  EXPECT_DOUBLE_EQ(eval("dist2d(sin(0.3), cos(0.3))"), 1);
  EXPECT_DOUBLE_EQ(eval("1 + max(1,2) * 3"), 7);
}

TEST(Expression, NamesAreCaseInsensitive) {
  ConstantTable t;
  t.set("x_n", 2);
  t.set("Belt_Length", 1.5);
  EXPECT_EQ(evaluate("SQRT(4)", t), 2);
  EXPECT_DOUBLE_EQ(evaluate("Pi()", t), kPi);
  EXPECT_DOUBLE_EQ(evaluate("PI()", t), kPi);
  EXPECT_EQ(evaluate("MaX(1,2)", t), 2);
  EXPECT_EQ(evaluate("Dist2D(3,4)", t), 5);
  EXPECT_EQ(evaluate("X_N", t), 2);
  EXPECT_EQ(evaluate("x_N", t), 2);
  EXPECT_EQ(evaluate("belt_length", t), 1.5);
  EXPECT_EQ(evaluate("BELT_LENGTH*2", t), 3);
}

TEST(Expression, NamesWithDigitsAndUnderscores) {
  ConstantTable t;
  t.set("a1", 1);
  t.set("b_2_", 2);
  t.set("e1", 10);  // not an exponent: names start with a letter
  EXPECT_EQ(evaluate("a1 + b_2_", t), 3);
  EXPECT_EQ(evaluate("e1", t), 10);
  EXPECT_EQ(evaluate("2*e1", t), 20);
}

// ---------------------------------------------------------------------------------------------
// Errors: every kind, with its column

TEST(ExpressionErrors, Empty) {
  EXPECT_EXPR_ERROR("", 1, "empty expression");
  EXPECT_EXPR_ERROR("   ", 1, "empty expression");
  EXPECT_EXPR_ERROR("\t", 1, "empty expression");
}

TEST(ExpressionErrors, UnexpectedCharacter) {
  EXPECT_EXPR_ERROR("1 + #", 5, "unexpected '#'");
  EXPECT_EXPR_ERROR("#", 1, "unexpected '#'");
  EXPECT_EXPR_ERROR("2^3", 2, "unexpected '^'");  // no power operator
  EXPECT_EXPR_ERROR("_x", 1, "unexpected '_'");
  EXPECT_EXPR_ERROR("1,2", 2, "unexpected ','");
  EXPECT_EXPR_ERROR("1 = = 2", 5, "unexpected '='");
  EXPECT_EXPR_ERROR("1\n", 2, "control byte 0x0A");
  EXPECT_EXPR_ERROR(
      "2\xC3\x97"
      "3",
      2, "non-ASCII byte 0xC3");
  EXPECT_EXPR_ERROR(std::string_view("1+\0", 3), 3, "control byte 0x00");
  EXPECT_EXPR_ERROR(".", 1, "unexpected '.'");
}

TEST(ExpressionErrors, MoreThanOneSign) {
  EXPECT_EXPR_ERROR("--1", 2, "unexpected '-'");
  EXPECT_EXPR_ERROR("2*+-1", 4, "only one sign");
}

TEST(ExpressionErrors, UnexpectedEnd) {
  EXPECT_EXPR_ERROR("1 +", 4, "unexpected end of expression");
  EXPECT_EXPR_ERROR("-", 2, "unexpected end of expression");
  EXPECT_EXPR_ERROR("2 *", 4, "expected a number, a name or '('");
  EXPECT_EXPR_ERROR("1 <", 4, "unexpected end");
  EXPECT_EXPR_ERROR("5 .and.", 8, "unexpected end");
}

TEST(ExpressionErrors, TrailingGarbage) {
  EXPECT_EXPR_ERROR("5 5", 3, "unexpected '5'");
  EXPECT_EXPR_ERROR("5 5", 3, "expected an operator or the end of the expression");
  EXPECT_EXPR_ERROR("2x", 2, "unexpected 'x'");
  EXPECT_EXPR_ERROR("1 .5", 3, "unexpected '.'");
  EXPECT_EXPR_ERROR("(1 2)", 4, "expected an operator or ')'");
}

TEST(ExpressionErrors, MalformedNumbers) {
  EXPECT_EXPR_ERROR("5.", 2, "digits required after the decimal point");
  EXPECT_EXPR_ERROR("(5.)", 3, "digits required after the decimal point");
  EXPECT_EXPR_ERROR("1 + 5. ", 6, "digits required after the decimal point");
  EXPECT_EXPR_ERROR("5.e3", 2, "digits required after the decimal point");
  EXPECT_EXPR_ERROR("1e", 2, "digits required in the exponent");
  EXPECT_EXPR_ERROR("1e+", 2, "digits required in the exponent");
  EXPECT_EXPR_ERROR("3 * 1Ex", 6, "digits required in the exponent");
  EXPECT_EXPR_ERROR("1.2.3", 4, "unexpected '.'");
  EXPECT_EXPR_ERROR("2 * 1e400", 5, "number too large");
  EXPECT_EXPR_ERROR(std::string(400, '9'), 1, "number too large");
}

TEST(ExpressionErrors, UnbalancedParentheses) {
  const Failure open = failure_of("(1+2");
  EXPECT_EQ(open.column, 5u);
  EXPECT_THAT(open.message, HasSubstr("unbalanced parentheses"));
  EXPECT_THAT(open.message, HasSubstr("missing ')' at column 5 (to close the '(' at column 1)"));
  EXPECT_EXPR_ERROR("2*((1+2)", 9, "(to close the '(' at column 3)");
  EXPECT_EXPR_ERROR("1+2)", 4, "unbalanced parentheses: unexpected ')'");
  EXPECT_EXPR_ERROR("(1))", 4, "unbalanced parentheses");
  EXPECT_EXPR_ERROR("sqrt(4", 7, "unbalanced parentheses: missing ')'");
  EXPECT_EXPR_ERROR("sqrt(4", 7, "(to close sqrt's '(')");
  EXPECT_EXPR_ERROR("max(1, (2)", 11, "unbalanced parentheses");
  EXPECT_EXPR_ERROR("()", 2, "unexpected ')'");
  EXPECT_EXPR_ERROR(")", 1, "unexpected ')'");
  EXPECT_EXPR_ERROR("max(1,)", 7, "unexpected ')'");
  EXPECT_EXPR_ERROR("max(1 2)", 7, "expected ',' or ')'");
}

TEST(ExpressionErrors, UnknownConstant) {
  EXPECT_EXPR_ERROR("belt_lenght", 1, "unknown constant 'belt_lenght'");
  const Failure f = failure_of("belt_lenght");
  EXPECT_EQ(f.message, "unknown constant 'belt_lenght' at column 1");
  EXPECT_EXPR_ERROR("2 * Belt_Lenght + 1", 5, "unknown constant 'Belt_Lenght'");
}

TEST(ExpressionErrors, BarePiAndEAreUnknownConstantsWithAHint) {
  EXPECT_EXPR_ERROR("pi", 1, "unknown constant 'pi'");
  EXPECT_EXPR_ERROR("pi", 1, "did you mean pi()?");
  EXPECT_EXPR_ERROR("2*PI/3", 3, "did you mean PI()?");
  EXPECT_EXPR_ERROR("1 + e", 5, "did you mean e()?");
  EXPECT_EXPR_ERROR("sqrt", 1, "'sqrt' is a function: write sqrt(...)");
  // A user constant named like a function is still a constant.
  ConstantTable t;
  t.set("pi", 3);
  EXPECT_EQ(evaluate("pi", t), 3);
  EXPECT_DOUBLE_EQ(evaluate("pi()", t), kPi);
}

TEST(ExpressionErrors, UnknownFunction) {
  EXPECT_EXPR_ERROR("foo(1)", 1, "unknown function 'foo'");
  EXPECT_EXPR_ERROR("1 + bar()", 5, "unknown function 'bar'");
  // SimTwo quirk 27: if() is not available.
  EXPECT_EXPR_ERROR("if(1,2,3)", 1, "unknown function 'if'");
  EXPECT_EXPR_ERROR("log(10)", 1, "unknown function 'log'");
  ConstantTable t;
  t.set("x", 2);
  const Failure f = failure_of("x(1)", t);
  EXPECT_EQ(f.column, 1u);
  EXPECT_THAT(f.message, HasSubstr("unknown function 'x'"));
  EXPECT_THAT(f.message, HasSubstr("is a constant"));
}

TEST(ExpressionErrors, WrongArgumentCount) {
  EXPECT_EXPR_ERROR("max(1)", 1, "function 'max' expects 2 arguments, got 1");
  EXPECT_EXPR_ERROR("sqrt(1,2)", 1, "function 'sqrt' expects 1 argument, got 2");
  EXPECT_EXPR_ERROR("sqrt()", 1, "function 'sqrt' expects 1 argument, got 0");
  EXPECT_EXPR_ERROR("pi(1)", 1, "function 'pi' expects 0 arguments, got 1");
  EXPECT_EXPR_ERROR("1 + MIN(1,2,3)", 5, "function 'MIN' expects 2 arguments, got 3");
  EXPECT_EXPR_ERROR("pow(2)", 1, "expects 2 arguments");
  EXPECT_EXPR_ERROR("dist2d(1,2,3,4,5)", 1, "got 5");
}

TEST(ExpressionErrors, DivisionByZero) {
  EXPECT_EXPR_ERROR("1/0", 2, "division by zero");
  EXPECT_EXPR_ERROR("3 + 1/(2-2)", 6, "division by zero");
  EXPECT_EXPR_ERROR("0/0", 2, "division by zero");
  EXPECT_EXPR_ERROR("1/-0", 2, "division by zero");
}

TEST(ExpressionErrors, NonFiniteFunctionResults) {
  EXPECT_EXPR_ERROR("sqrt(-1)", 1, "non-finite result of sqrt(-1)");
  EXPECT_EXPR_ERROR("sqrt(-1)", 1, "must be >= 0");
  EXPECT_EXPR_ERROR("2 + ln(0)", 5, "non-finite result of ln(0)");
  EXPECT_EXPR_ERROR("ln(-1)", 1, "must be > 0");
  EXPECT_EXPR_ERROR("log10(-1)", 1, "non-finite result of log10(-1)");
  EXPECT_EXPR_ERROR("arcsin(2)", 1, "non-finite result of arcsin(2)");
  EXPECT_EXPR_ERROR("arcsin(2)", 1, "[-1, 1]");
  EXPECT_EXPR_ERROR("arccos(-1.5)", 1, "non-finite result of arccos(-1.5)");
  EXPECT_EXPR_ERROR("pow(0,-1)", 1, "non-finite result of pow(0, -1)");
  EXPECT_EXPR_ERROR("pow(-8,1/3)", 1, "non-finite result of pow(");
  EXPECT_EXPR_ERROR("exp(1000)", 1, "non-finite result of exp(1000)");
  EXPECT_EXPR_ERROR("sqr(1e200)", 1, "non-finite result of sqr(1e+200)");
  EXPECT_EXPR_ERROR("deg(1e308)", 1, "non-finite result of deg(");
  EXPECT_EXPR_ERROR("dist2d(1.5e308,1.5e308)", 1, "non-finite result of dist2d(");
}

TEST(ExpressionErrors, ArithmeticOverflow) {
  EXPECT_EXPR_ERROR("1e200*1e200", 6, "non-finite result of '*'");
  EXPECT_EXPR_ERROR("1e308+1e308", 6, "non-finite result of '+'");
  EXPECT_EXPR_ERROR("-1e308-1e308", 7, "non-finite result of '-'");
  EXPECT_EXPR_ERROR("1e300/1e-300", 6, "non-finite result of '/'");
}

TEST(ExpressionErrors, NonFiniteConstant) {
  ConstantTable t;
  t.set("big", std::numeric_limits<double>::infinity());
  const Failure f = failure_of("1 + big", t);
  EXPECT_EQ(f.column, 5u);
  EXPECT_THAT(f.message, HasSubstr("constant 'big' is not finite"));
}

TEST(ExpressionErrors, UnknownLogicalOperator) {
  EXPECT_EXPR_ERROR("1 .nand. 2", 3, "unknown operator '.nand'");
  EXPECT_EXPR_ERROR("1 .andx. 2", 3, "unknown operator '.andx'");
  EXPECT_EXPR_ERROR("(1 .not. 2)", 4, "logical operators are .and. .or. .xor.");
}

TEST(ExpressionErrors, DeepNestingFailsCleanly) {
  const std::string ok = std::string(100, '(') + "1" + std::string(100, ')');
  EXPECT_EQ(eval(ok), 1);
  const std::string deep = std::string(100000, '(') + "1" + std::string(100000, ')');
  const Failure f = failure_of(deep);
  EXPECT_THAT(f.message, HasSubstr("nested too deeply"));
  const Failure signs = failure_of(std::string(100000, '-'));
  EXPECT_TRUE(signs.thrown);
  std::string calls;
  for (int i = 0; i < 50000; ++i)
    calls += "abs(";
  EXPECT_THAT(failure_of(calls + "1").message, HasSubstr("nested too deeply"));
}

TEST(ExpressionErrors, IsARuntimeError) {
  try {
    eval("1/0");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("division by zero"));
  }
}

// ---------------------------------------------------------------------------------------------
// ConstantTable (§2.1)

TEST(ConstantTable, SetDefinesAndOverwrites) {
  ConstantTable t;
  EXPECT_EQ(t.size(), 0u);
  EXPECT_FALSE(t.find("a").has_value());
  t.set("a", 1);
  EXPECT_EQ(t.find("a"), 1);
  t.set("a", 2);  // <const> overwrites
  EXPECT_EQ(t.find("a"), 2);
  EXPECT_EQ(t.size(), 1u);
}

TEST(ConstantTable, DefineIfAbsentOnlyDefinesNewNames) {
  ConstantTable t;
  EXPECT_TRUE(t.define_if_absent("belt_length", 1.5));
  EXPECT_EQ(t.find("belt_length"), 1.5);
  EXPECT_FALSE(t.define_if_absent("belt_length", 3));  // <arg> keeps the pre-set value
  EXPECT_EQ(t.find("belt_length"), 1.5);
  t.set("belt_length", 2);  // a later <const> still overwrites
  EXPECT_EQ(t.find("belt_length"), 2);
  EXPECT_EQ(t.size(), 1u);
}

TEST(ConstantTable, PresetConstOverridesArg) {
  // default/scene.xml pre-setting default/Belt.xml's <arg name='belt_length'>.
  ConstantTable t;
  t.set("BELT_LENGTH", 0.8);
  EXPECT_FALSE(t.define_if_absent("belt_length", 1.5));
  EXPECT_EQ(evaluate("belt_length", t), 0.8);
}

TEST(ConstantTable, NamesAreCaseInsensitiveAndStoredUpperCase) {
  ConstantTable t;
  t.set("Claw_Gap", 0.1);
  EXPECT_EQ(t.find("claw_gap"), 0.1);
  EXPECT_EQ(t.find("CLAW_GAP"), 0.1);
  EXPECT_EQ(t.find("cLaW_gAp"), 0.1);
  t.set("CLAW_gap", 0.2);
  EXPECT_EQ(t.size(), 1u);
  EXPECT_EQ(t.find("claw_gap"), 0.2);
  EXPECT_FALSE(t.define_if_absent("claw_GAP", 9));
  ASSERT_EQ(t.entries().size(), 1u);
  EXPECT_EQ(t.entries()[0].first, "CLAW_GAP");
  EXPECT_EQ(t.entries()[0].second, 0.2);
}

TEST(ConstantTable, KeepsDefinitionOrder) {
  ConstantTable t;
  t.set("b", 1);
  t.define_if_absent("a", 2);
  t.set("c", 3);
  t.set("b", 4);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t.entries()[0].first, "B");
  EXPECT_EQ(t.entries()[1].first, "A");
  EXPECT_EQ(t.entries()[2].first, "C");
  EXPECT_EQ(t.entries()[0].second, 4);
}

TEST(ConstantTable, HoldsAtLeast256Constants) {
  ConstantTable t;
  for (int i = 0; i < 300; ++i) {
    std::string name = "c";
    name += std::to_string(i);
    t.set(name, i);
  }
  EXPECT_EQ(t.size(), 300u);
  EXPECT_EQ(t.find("C299"), 299);
  EXPECT_EQ(evaluate("c0 + c255 + C299", t), 554);
}

TEST(ConstantTable, CopiesAreIndependent) {
  // Robot files evaluate against a copy of the global table (§2.2).
  ConstantTable global;
  global.set("x", 1);
  ConstantTable local = global;
  local.set("x", 2);
  local.set("y", 3);
  EXPECT_EQ(global.find("x"), 1);
  EXPECT_FALSE(global.find("y").has_value());
  EXPECT_EQ(local.find("x"), 2);
}

// ---------------------------------------------------------------------------------------------
// Fuzz: evaluate returns a finite double or throws ExpressionError with a sane column.

void check_never_crashes(const std::string& text, const ConstantTable& t, int& ok, int& errors) {
  try {
    const double v = evaluate(text, t);
    EXPECT_TRUE(std::isfinite(v)) << "'" << text << "' -> " << v;
    ++ok;
  } catch (const ExpressionError& e) {
    ++errors;
    EXPECT_GE(e.column(), 1u) << text;
    EXPECT_LE(e.column(), text.size() + 1) << text;
    EXPECT_THAT(e.what(), HasSubstr(std::string("at column ") + std::to_string(e.column())))
        << text;
  } catch (...) {
    ADD_FAILURE() << "'" << text << "' threw something other than ExpressionError";
  }
}

TEST(ExpressionFuzz, RandomCharacters) {
  ConstantTable t;
  t.set("x", 0.5);
  t.set("ab", -2);
  const std::string alphabet = "0123456789.eE+-*/()<>=, \tabxyzpisqrtmno_#";
  std::mt19937 rng(12345);
  std::uniform_int_distribution<std::size_t> len(0, 24);
  std::uniform_int_distribution<std::size_t> pick(0, alphabet.size() - 1);
  std::uniform_int_distribution<int> byte(0, 255);
  int ok = 0, errors = 0;
  for (int i = 0; i < 4000; ++i) {
    std::string s;
    const std::size_t n = len(rng);
    for (std::size_t k = 0; k < n; ++k)
      s += (i % 10 == 9) ? static_cast<char>(byte(rng)) : alphabet[pick(rng)];
    check_never_crashes(s, t, ok, errors);
  }
  EXPECT_EQ(ok + errors, 4000);
}

TEST(ExpressionFuzz, RandomTokens) {
  ConstantTable t;
  t.set("x", 0.5);
  t.set("y", -3);
  const std::vector<std::string> tokens = {
      "1",    "0",       "2.5",   ".5",    "1e3",     "1e-3", "5.",    "x",    "y",    "pi",
      "pi()", "e()",     "sqrt(", "sqr(",  "pow(",    "max(", "min(",  "int(", "ln(",  "log10(",
      "sin(", "arcsin(", "exp(",  "frac(", "dist2d(", "not(", "sign(", "abs(", "deg(", "foo(",
      "(",    ")",       ")",     ",",     "+",       "-",    "*",     "/",    "<",    ">",
      "=",    "<=",      ">=",    "<>",    ".and.",   ".or.", ".xor.", ".and", " ",    "\t"};
  std::mt19937 rng(777);
  std::uniform_int_distribution<std::size_t> len(1, 16);
  std::uniform_int_distribution<std::size_t> pick(0, tokens.size() - 1);
  int ok = 0, errors = 0;
  for (int i = 0; i < 6000; ++i) {
    std::string s;
    const std::size_t n = len(rng);
    for (std::size_t k = 0; k < n; ++k)
      s += tokens[pick(rng)];
    check_never_crashes(s, t, ok, errors);
  }
  EXPECT_EQ(ok + errors, 6000);
  EXPECT_GT(ok, 100);  // the fuzz must reach evaluation, not only syntax errors
}

TEST(ExpressionFuzz, GeneratedValidExpressionsEvaluate) {
  // Grammar-driven generation: only known names, balanced parentheses, correct arities.
  ConstantTable t;
  t.set("x", 0.5);
  std::mt19937 rng(4242);
  const std::vector<std::string> binary = {"+",  "-",  "*",  "/",       "<",      ">",      "=",
                                           "<=", ">=", "<>", " .and. ", " .or. ", " .xor. "};
  const std::vector<std::string> unary = {"sin", "cos", "atan", "abs", "sign", "frac",
                                          "int", "not", "sqr",  "deg", "rad"};
  const std::vector<std::string> pairs = {"max", "min", "dist2d"};
  std::function<std::string(int)> gen = [&](int depth) -> std::string {
    const int choice = depth > 4 ? static_cast<int>(rng() % 3) : static_cast<int>(rng() % 8);
    switch (choice) {
      case 0:
        return std::to_string(rng() % 100);
      case 1:
        return "x";
      case 2:
        return "pi()";
      case 3:
        return "(" + gen(depth + 1) + ")";
      case 4:
        return "-" + gen(depth + 1);
      case 5:
        return unary[rng() % unary.size()] + "(" + gen(depth + 1) + ")";
      case 6:
        return pairs[rng() % pairs.size()] + "(" + gen(depth + 1) + ", " + gen(depth + 1) + ")";
      default:
        return "(" + gen(depth + 1) + binary[rng() % binary.size()] + gen(depth + 1) + ")";
    }
  };
  int ok = 0, errors = 0;
  for (int i = 0; i < 3000; ++i) {
    const std::string s = gen(0);
    check_never_crashes(s, t, ok, errors);
  }
  // Only division by zero or overflow may fail here.
  EXPECT_GT(ok, 2500);
}

}  // namespace
}  // namespace s2sim::scene
