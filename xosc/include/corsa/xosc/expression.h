#pragma once

// OpenSCENARIO expressions `${...}` (1.2+, §9.2): numbers, booleans, `$parameter` references,
// arithmetic, comparisons, logic and functions, evaluated in double precision with errors for
// division by zero, overflow and domain errors. Precedence, highest first:
//
//   1  ( )  literals  $param  function calls: round floor ceil sqrt pow min max abs sign
//           sin cos tan asin acos atan
//   2  unary -
//   3  *  /  %
//   4  +  -
//   5  ==  !=  <  <=  >  >=   (non-associative)
//   6  not
//   7  and
//   8  or
//
// Binary operators of one level associate to the left. `true` and `false` are boolean literals.
// Arithmetic needs numbers, not/and/or need booleans. Deterministic: the functions use only
// correctly rounded operations (corsa/core/det_math.h), never the platform's libm.

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace corsa::xosc {

/// Result of an expression: a number or a boolean.
struct ExprValue {
  bool is_bool = false;
  double number = 0.0;
  bool boolean = false;

  static ExprValue of(double value) { return {false, value, false}; }
  static ExprValue of_bool(bool value) { return {true, 0.0, value}; }
};

/// A bad expression: `column` is the 1-based offset in the text given to evaluate_expression.
class ExpressionError : public std::runtime_error {
 public:
  ExpressionError(const std::string& message, size_t column)
      : std::runtime_error(message), column_(column) {}
  size_t column() const { return column_; }

 private:
  size_t column_;
};

/// Looks up a parameter by name (without the `$`): its value, or nullopt when undefined (then the
/// expression fails with "undefined parameter"). It may itself throw ExpressionError, e.g. for a
/// string parameter used in arithmetic.
using ParameterLookup = std::function<std::optional<ExprValue>(std::string_view name)>;

/// Told of each named constant an expression uses outside the standard's grammar, with its value.
/// Only `pi` is known (esmini's expressions have it, and its examples use it: `${pi/2}`); without
/// a ConstantNote `pi` is an unknown keyword, as §9.2 has no constants.
using ConstantNote = std::function<void(std::string_view name, double value)>;

/// Evaluates the text between `${` and `}` (without them). Throws ExpressionError.
ExprValue evaluate_expression(std::string_view text, const ParameterLookup& lookup,
                              const ConstantNote& on_constant = {});

/// Maximum nesting depth of parentheses and unary operators (deeper input is rejected rather
/// than overflowing the stack).
inline constexpr int kMaxExpressionDepth = 200;

}  // namespace corsa::xosc
