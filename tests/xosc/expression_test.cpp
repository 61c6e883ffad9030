#include "corsa/xosc/expression.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <numbers>
#include <string>

using corsa::xosc::evaluate_expression;
using corsa::xosc::ExpressionError;
using corsa::xosc::ExprValue;

namespace {

const std::map<std::string, ExprValue, std::less<>> kParameters = {
    {"a", ExprValue::of(1.0)},
    {"b", ExprValue::of(3.0)},
    {"speed", ExprValue::of(12.5)},
    {"flag", ExprValue::of_bool(true)},
};

ExprValue eval(const std::string& text) {
  return evaluate_expression(text, [](std::string_view name) -> std::optional<ExprValue> {
    const auto found = kParameters.find(name);
    if (found == kParameters.end()) return std::nullopt;
    return found->second;
  });
}

struct NumberCase {
  const char* text;
  double expected;
};

struct BoolCase {
  const char* text;
  bool expected;
};

struct ErrorCase {
  const char* text;
  const char* message;
  size_t column;
};

}  // namespace

TEST_CASE("arithmetic follows the OpenSCENARIO precedence and associativity", "[xosc][expr]") {
  const NumberCase cases[] = {
      {"1 + 2 * 3", 7.0}, {"(1 + 2) * 3", 9.0},   {"8 - 3 - 2", 3.0}, {"16 / 4 / 2", 2.0},
      {"2 * 3 % 4", 2.0}, {"10 / 4", 2.5},        {"7 % 3", 1.0},     {"-7 % 3", -1.0},
      {"7.5 % 2", 1.5},   {"-2 * 3", -6.0},       {"-(2 + 3)", -5.0}, {"--2", 2.0},
      {"2 * -3", -6.0},   {"1.5e2", 150.0},       {".5 + 1", 1.5},    {"$a + $b * 2", 7.0},
      {"-$speed", -12.5}, {"($a + $b) / 2", 2.0}, {"2 - -2", 4.0},    {"  4   *2 ", 8.0},
      {"1 - 2 + 3", 2.0},
  };
  for (const auto& c : cases) {
    INFO(c.text);
    const ExprValue value = eval(c.text);
    CHECK_FALSE(value.is_bool);
    CHECK(value.number == c.expected);
  }
}

TEST_CASE("functions round, floor, ceil, sqrt, pow, min, max and friends evaluate",
          "[xosc][expr]") {
  const NumberCase cases[] = {
      {"round(2.5)", 3.0},
      {"round(-2.5)", -3.0},
      {"round(2.4)", 2.0},
      {"floor(-1.5)", -2.0},
      {"ceil(1.2)", 2.0},
      {"sqrt(16)", 4.0},
      {"pow(2, 10)", 1024.0},
      {"pow(2, -1)", 0.5},
      {"pow(-2, 3)", -8.0},
      {"min(3, -1)", -1.0},
      {"max(3, -1)", 3.0},
      {"abs(-4)", 4.0},
      {"sign(-3)", -1.0},
      {"sign(0)", 0.0},
      {"sin(0)", 0.0},
      {"cos(0)", 1.0},
      {"2 * floor(3.7) + 1", 7.0},
      {"max(min($a, $b), 0)", 1.0},
  };
  for (const auto& c : cases) {
    INFO(c.text);
    CHECK(eval(c.text).number == c.expected);
  }
  // Non-integral powers and the inverse trigonometric functions are accurate to a few ulp.
  CHECK(eval("pow(4, 0.5)").number == Approx(2.0).epsilon(1e-15));
  CHECK(eval("atan(1)").number == Approx(std::numbers::pi / 4).epsilon(1e-15));
  CHECK(eval("asin(1)").number == Approx(std::numbers::pi / 2).epsilon(1e-15));
  CHECK(eval("acos(0.5)").number == Approx(std::numbers::pi / 3).epsilon(1e-14));
  CHECK(eval("tan(0.5)").number == Approx(0.5463024898437905).epsilon(1e-14));
  CHECK(eval("atan(-1e300)").number == Approx(-std::numbers::pi / 2).epsilon(1e-15));
}

TEST_CASE("comparisons and not/and/or bind below arithmetic, in that order", "[xosc][expr]") {
  const BoolCase cases[] = {
      {"1 < 2", true},
      {"2 <= 2", true},
      {"3 == 3", true},
      {"3 != 3", false},
      {"2 > 3", false},
      {"3 >= 3", true},
      {"1 + 1 == 2 and 3 > 2", true},
      {"not 1 > 2", true},
      {"true or false and false", true},
      {"not true or true", true},
      {"not (true or true)", false},
      {"not not true", true},
      {"$flag and $a == 1", true},
      {"true == false", false},
      {"(1 < 2) == true", true},
      {"false or $b > $a * 2", true},
  };
  for (const auto& c : cases) {
    INFO(c.text);
    const ExprValue value = eval(c.text);
    CHECK(value.is_bool);
    CHECK(value.boolean == c.expected);
  }
}

TEST_CASE("pi is a constant only for a caller that accepts it", "[xosc][expr]") {
  const corsa::xosc::ParameterLookup none = [](std::string_view) { return std::nullopt; };
  std::string told;
  const corsa::xosc::ConstantNote note = [&](std::string_view name, double value) {
    told += std::string(name) + "=" + std::to_string(value) + ";";
  };
  CHECK(evaluate_expression("pi / 2 + pi", none, note).number ==
        std::numbers::pi / 2 + std::numbers::pi);
  CHECK(told == "pi=3.141593;pi=3.141593;");
  CHECK_THROWS_WITH(evaluate_expression("pi", none), Catch::Contains("unknown function or "
                                                                     "keyword 'pi'"));
  CHECK_THROWS_WITH(evaluate_expression("pi(1)", none, note),
                    Catch::Contains("unknown function or keyword 'pi'"));
  CHECK_THROWS_WITH(evaluate_expression("e", none, note),
                    Catch::Contains("unknown function or keyword 'e'"));
}

TEST_CASE("bad expressions fail with a message and the column of the problem", "[xosc][expr]") {
  const ErrorCase cases[] = {
      {"1 / 0", "division by zero", 3},
      {"1 % 0", "modulo by zero", 3},
      {"sqrt(-1)", "sqrt of a negative number", 1},
      {"$undefined + 1", "undefined parameter '$undefined'", 1},
      {"1 +", "expression ends too early", 4},
      {"(1 + 2", "expected ')'", 7},
      {"foo(1)", "unknown function or keyword 'foo'", 1},
      {"1 < 2 < 3", "comparisons cannot be chained", 7},
      {"true + 1", "'+' needs numbers", 6},
      {"1 and true", "'and' needs booleans", 3},
      {"not 1", "'not' needs booleans", 1},
      {"1e308 * 10", "overflow", 7},
      {"2 $a", "unexpected '$a'", 3},
      {"1 # 2", "unexpected character '#'", 3},
      {"pow(0, -1)", "pow(0, negative)", 1},
      {"pow(-8, 0.5)", "non-integer power", 1},
      {"asin(2)", "outside [-1, 1]", 1},
      {"pow(1)", "expected ','", 6},
      {"", "expression ends too early", 1},
      {"1.2.3", "bad number", 1},
      {"$", "expected a parameter name", 1},
  };
  for (const auto& c : cases) {
    INFO(c.text);
    try {
      eval(c.text);
      FAIL("no error");
    } catch (const ExpressionError& error) {
      CHECK_THAT(error.what(), Catch::Contains(c.message));
      CHECK(error.column() == c.column);
    }
  }
}

TEST_CASE("deeply nested input is rejected instead of overflowing the stack", "[xosc][expr]") {
  const std::string deep = std::string(5000, '(') + "1" + std::string(5000, ')');
  CHECK_THROWS_WITH(eval(deep), Catch::Contains("nested too deeply"));
  const std::string minus = std::string(5000, '-') + "1";
  CHECK_THROWS_WITH(eval(minus), Catch::Contains("nested too deeply"));
  const std::string ok = std::string(50, '(') + "1" + std::string(50, ')');
  CHECK(eval(ok).number == 1.0);
}
