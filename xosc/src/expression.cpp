// Recursive-descent parser and evaluator for OpenSCENARIO `${...}` expressions (1.2+ §9.2).
// Precedence is documented in expression.h. The expression is evaluated while it is parsed (no
// tree is built): expressions in scenario files are short and evaluated once at load time.

#include "corsa/xosc/expression.h"

#include <cmath>
#include <numbers>
#include <string>

#include "corsa/core/det_math.h"
#include "corsa/core/strings.h"

namespace corsa::xosc {
namespace {

enum class Tok {
  kEnd,
  kNumber,
  kParam,
  kIdent,
  kPlus,
  kMinus,
  kStar,
  kSlash,
  kPercent,
  kLParen,
  kRParen,
  kComma,
  kEq,
  kNe,
  kLt,
  kLe,
  kGt,
  kGe
};

struct Token {
  Tok kind = Tok::kEnd;
  std::string_view text;
  size_t column = 1;  // 1-based
  double number = 0.0;
};

bool is_ident_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool is_ident_char(char c) { return is_ident_start(c) || (c >= '0' && c <= '9'); }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Deterministic arctangent from basic operations only: two half-angle reductions bring |x| below
// tan(pi/16) ~ 0.199, where the Taylor series converges to full precision in 14 terms.
double det_atan(double x) {
  if (std::isnan(x)) {
    return x;
  }
  const bool negative = x < 0.0;
  x = std::fabs(x);
  const bool inverted = x > 1.0;
  if (inverted) {
    x = 1.0 / x;
  }
  x = x / (1.0 + std::sqrt(1.0 + x * x));
  x = x / (1.0 + std::sqrt(1.0 + x * x));
  const double x2 = x * x;
  double power = x;
  double sum = 0.0;
  for (int k = 0; k < 16; ++k) {
    const double term = power / static_cast<double>(2 * k + 1);
    sum += (k % 2 == 0) ? term : -term;
    power *= x2;
  }
  double result = 4.0 * sum;
  if (inverted) {
    result = std::numbers::pi / 2.0 - result;
  }
  return negative ? -result : result;
}

class Parser {
 public:
  Parser(std::string_view text, const ParameterLookup& lookup, const ConstantNote& on_constant)
      : text_(text), lookup_(lookup), on_constant_(on_constant) {
    advance();
  }

  ExprValue parse_all() {
    ExprValue value = parse_or();
    if (current_.kind != Tok::kEnd) {
      fail("unexpected '" + std::string(current_.text) + "'", current_.column);
    }
    return value;
  }

 private:
  [[noreturn]] static void fail(const std::string& message, size_t column) {
    throw ExpressionError(message, column);
  }

  void advance() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' ||
                                   text_[pos_] == '\n' || text_[pos_] == '\r')) {
      ++pos_;
    }
    current_ = Token{};
    current_.column = pos_ + 1;
    if (pos_ >= text_.size()) {
      current_.kind = Tok::kEnd;
      current_.text = "end of expression";
      return;
    }
    const size_t start = pos_;
    const char c = text_[pos_];
    if (is_digit(c) || (c == '.' && pos_ + 1 < text_.size() && is_digit(text_[pos_ + 1]))) {
      lex_number(start);
      return;
    }
    if (c == '$') {
      ++pos_;
      if (pos_ >= text_.size() || !is_ident_start(text_[pos_])) {
        fail("expected a parameter name after '$'", start + 1);
      }
      while (pos_ < text_.size() && is_ident_char(text_[pos_])) {
        ++pos_;
      }
      current_.kind = Tok::kParam;
      current_.text = text_.substr(start, pos_ - start);
      return;
    }
    if (is_ident_start(c)) {
      while (pos_ < text_.size() && is_ident_char(text_[pos_])) {
        ++pos_;
      }
      current_.kind = Tok::kIdent;
      current_.text = text_.substr(start, pos_ - start);
      return;
    }
    lex_operator(start);
  }

  void lex_number(size_t start) {
    while (pos_ < text_.size() && is_digit(text_[pos_])) {
      ++pos_;
    }
    if (pos_ < text_.size() && text_[pos_] == '.') {
      ++pos_;
      while (pos_ < text_.size() && is_digit(text_[pos_])) {
        ++pos_;
      }
    }
    if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
      size_t p = pos_ + 1;
      if (p < text_.size() && (text_[p] == '+' || text_[p] == '-')) {
        ++p;
      }
      if (p < text_.size() && is_digit(text_[p])) {
        pos_ = p;
        while (pos_ < text_.size() && is_digit(text_[pos_])) {
          ++pos_;
        }
      }
    }
    if (pos_ < text_.size() && (is_ident_char(text_[pos_]) || text_[pos_] == '.')) {
      fail("bad number '" + std::string(text_.substr(start, pos_ - start + 1)) + "'", start + 1);
    }
    current_.kind = Tok::kNumber;
    current_.text = text_.substr(start, pos_ - start);
    const auto value = parse_double(current_.text);
    if (!value) {
      fail("number '" + std::string(current_.text) + "' is out of range", start + 1);
    }
    current_.number = *value;
  }

  void lex_operator(size_t start) {
    const char c = text_[pos_];
    const char next = pos_ + 1 < text_.size() ? text_[pos_ + 1] : '\0';
    auto set = [&](Tok kind, size_t length) {
      current_.kind = kind;
      current_.text = text_.substr(start, length);
      pos_ += length;
    };
    switch (c) {
      case '+':
        return set(Tok::kPlus, 1);
      case '-':
        return set(Tok::kMinus, 1);
      case '*':
        return set(Tok::kStar, 1);
      case '/':
        return set(Tok::kSlash, 1);
      case '%':
        return set(Tok::kPercent, 1);
      case '(':
        return set(Tok::kLParen, 1);
      case ')':
        return set(Tok::kRParen, 1);
      case ',':
        return set(Tok::kComma, 1);
      case '=':
        if (next == '=') return set(Tok::kEq, 2);
        break;
      case '!':
        if (next == '=') return set(Tok::kNe, 2);
        break;
      case '<':
        return next == '=' ? set(Tok::kLe, 2) : set(Tok::kLt, 1);
      case '>':
        return next == '=' ? set(Tok::kGe, 2) : set(Tok::kGt, 1);
      default:
        break;
    }
    fail("unexpected character '" + std::string(1, c) + "'", start + 1);
  }

  bool at_keyword(std::string_view word) const {
    return current_.kind == Tok::kIdent && current_.text == word;
  }

  void enter(size_t column) {
    if (++depth_ > kMaxExpressionDepth) {
      fail("expression nested too deeply", column);
    }
  }

  static double need_number(const ExprValue& value, std::string_view op, size_t column) {
    if (value.is_bool) {
      fail("'" + std::string(op) + "' needs numbers, got a boolean", column);
    }
    return value.number;
  }
  static bool need_bool(const ExprValue& value, std::string_view op, size_t column) {
    if (!value.is_bool) {
      fail("'" + std::string(op) + "' needs booleans, got a number", column);
    }
    return value.boolean;
  }
  static ExprValue checked(double value, size_t column) {
    if (std::isnan(value)) {
      fail("result is not a number", column);
    }
    if (std::isinf(value)) {
      fail("overflow: result exceeds the range of a double", column);
    }
    return ExprValue::of(value);
  }

  ExprValue parse_or() {
    ExprValue left = parse_and();
    while (at_keyword("or")) {
      const size_t column = current_.column;
      advance();
      const ExprValue right = parse_and();
      const bool l = need_bool(left, "or", column);
      const bool r = need_bool(right, "or", column);
      left = ExprValue::of_bool(l || r);
    }
    return left;
  }

  ExprValue parse_and() {
    ExprValue left = parse_not();
    while (at_keyword("and")) {
      const size_t column = current_.column;
      advance();
      const ExprValue right = parse_not();
      const bool l = need_bool(left, "and", column);
      const bool r = need_bool(right, "and", column);
      left = ExprValue::of_bool(l && r);
    }
    return left;
  }

  ExprValue parse_not() {
    if (at_keyword("not")) {
      const size_t column = current_.column;
      enter(column);
      advance();
      const ExprValue operand = parse_not();
      --depth_;
      return ExprValue::of_bool(!need_bool(operand, "not", column));
    }
    return parse_comparison();
  }

  ExprValue parse_comparison() {
    const ExprValue left = parse_sum();
    const Tok op = current_.kind;
    if (op != Tok::kEq && op != Tok::kNe && op != Tok::kLt && op != Tok::kLe && op != Tok::kGt &&
        op != Tok::kGe) {
      return left;
    }
    const size_t column = current_.column;
    const std::string op_text(current_.text);
    advance();
    const ExprValue right = parse_sum();
    bool result = false;
    if (left.is_bool || right.is_bool) {
      if (!(left.is_bool && right.is_bool) || (op != Tok::kEq && op != Tok::kNe)) {
        fail("'" + op_text + "' cannot compare these operands", column);
      }
      result = (left.boolean == right.boolean) == (op == Tok::kEq);
    } else {
      const double l = left.number;
      const double r = right.number;
      switch (op) {
        case Tok::kEq:
          result = l == r;
          break;
        case Tok::kNe:
          result = l != r;
          break;
        case Tok::kLt:
          result = l < r;
          break;
        case Tok::kLe:
          result = l <= r;
          break;
        case Tok::kGt:
          result = l > r;
          break;
        default:
          result = l >= r;
          break;
      }
    }
    const Tok after = current_.kind;
    if (after == Tok::kEq || after == Tok::kNe || after == Tok::kLt || after == Tok::kLe ||
        after == Tok::kGt || after == Tok::kGe) {
      fail("comparisons cannot be chained; use parentheses and 'and'", current_.column);
    }
    return ExprValue::of_bool(result);
  }

  ExprValue parse_sum() {
    ExprValue left = parse_product();
    while (current_.kind == Tok::kPlus || current_.kind == Tok::kMinus) {
      const bool plus = current_.kind == Tok::kPlus;
      const size_t column = current_.column;
      advance();
      const ExprValue right = parse_product();
      const double l = need_number(left, plus ? "+" : "-", column);
      const double r = need_number(right, plus ? "+" : "-", column);
      left = checked(plus ? l + r : l - r, column);
    }
    return left;
  }

  ExprValue parse_product() {
    ExprValue left = parse_unary();
    while (current_.kind == Tok::kStar || current_.kind == Tok::kSlash ||
           current_.kind == Tok::kPercent) {
      const Tok op = current_.kind;
      const std::string op_text(current_.text);
      const size_t column = current_.column;
      advance();
      const ExprValue right = parse_unary();
      const double l = need_number(left, op_text, column);
      const double r = need_number(right, op_text, column);
      if (op == Tok::kStar) {
        left = checked(l * r, column);
      } else if (r == 0.0) {
        fail(op == Tok::kSlash ? "division by zero" : "modulo by zero", column);
      } else {
        // % keeps the sign of the dividend, like C's fmod (exact for all doubles).
        left = checked(op == Tok::kSlash ? l / r : std::fmod(l, r), column);
      }
    }
    return left;
  }

  ExprValue parse_unary() {
    if (current_.kind == Tok::kMinus) {
      const size_t column = current_.column;
      enter(column);
      advance();
      const ExprValue operand = parse_unary();
      --depth_;
      return ExprValue::of(-need_number(operand, "-", column));
    }
    return parse_primary();
  }

  ExprValue parse_primary() {
    const Token token = current_;
    switch (token.kind) {
      case Tok::kNumber:
        advance();
        return ExprValue::of(token.number);
      case Tok::kParam: {
        advance();
        const std::string_view name = token.text.substr(1);
        std::optional<ExprValue> value = lookup_ ? lookup_(name) : std::nullopt;
        if (!value) {
          fail("undefined parameter '" + std::string(token.text) + "'", token.column);
        }
        return *value;
      }
      case Tok::kLParen: {
        enter(token.column);
        advance();
        const ExprValue inner = parse_or();
        expect(Tok::kRParen, "')'");
        --depth_;
        return inner;
      }
      case Tok::kIdent:
        if (token.text == "true" || token.text == "false") {
          advance();
          return ExprValue::of_bool(token.text == "true");
        }
        if (token.text == "pi" && on_constant_) {
          advance();
          if (current_.kind != Tok::kLParen) {
            on_constant_(token.text, std::numbers::pi);
            return ExprValue::of(std::numbers::pi);
          }
          fail("unknown function or keyword 'pi'", token.column);
        }
        return parse_call();
      case Tok::kEnd:
        fail("expression ends too early", token.column);
      default:
        fail("unexpected '" + std::string(token.text) + "'", token.column);
    }
  }

  void expect(Tok kind, const char* what) {
    if (current_.kind != kind) {
      fail(std::string("expected ") + what + ", got '" + std::string(current_.text) + "'",
           current_.column);
    }
    advance();
  }

  ExprValue parse_call() {
    const Token name = current_;
    const std::string function(name.text);
    const int arity = function == "pow" || function == "min" || function == "max" ? 2 : 1;
    static constexpr std::string_view kUnary[] = {"round", "floor", "ceil", "sqrt", "abs",  "sign",
                                                  "sin",   "cos",   "tan",  "asin", "acos", "atan"};
    bool known = arity == 2;
    for (const auto unary : kUnary) {
      known = known || unary == function;
    }
    if (!known) {
      fail("unknown function or keyword '" + function + "'", name.column);
    }
    advance();
    enter(name.column);
    expect(Tok::kLParen, "'(' after function name");
    const ExprValue a = parse_or();
    ExprValue b = ExprValue::of(0.0);
    if (arity == 2) {
      expect(Tok::kComma, "',' between the two arguments");
      b = parse_or();
    }
    expect(Tok::kRParen, "')'");
    --depth_;
    const double x = need_number(a, function, name.column);
    const double y = need_number(b, function, name.column);
    return checked(apply(function, x, y, name.column), name.column);
  }

  static double apply(const std::string& f, double x, double y, size_t column) {
    if (f == "round") return std::round(x);  // halves away from zero
    if (f == "floor") return std::floor(x);
    if (f == "ceil") return std::ceil(x);
    if (f == "abs") return std::fabs(x);
    if (f == "sign") return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0);
    if (f == "min") return x < y ? x : y;
    if (f == "max") return x > y ? x : y;
    if (f == "sqrt") {
      if (x < 0.0) fail("sqrt of a negative number", column);
      return std::sqrt(x);
    }
    if (f == "pow") return power(x, y, column);
    if (f == "sin" || f == "cos" || f == "tan") {
      if (std::fabs(x) > 1e6) fail(f + " argument too large (|x| > 1e6)", column);
      if (f == "sin") return det::sin(x);
      if (f == "cos") return det::cos(x);
      const double c = det::cos(x);
      if (c == 0.0) fail("tan is infinite here", column);
      return det::sin(x) / c;
    }
    if (f == "atan") return det_atan(x);
    if (x < -1.0 || x > 1.0) fail(f + " argument outside [-1, 1]", column);
    const double as = x == 1.0    ? std::numbers::pi / 2.0
                      : x == -1.0 ? -std::numbers::pi / 2.0
                                  : det_atan(x / std::sqrt(1.0 - x * x));
    return f == "asin" ? as : std::numbers::pi / 2.0 - as;
  }

  // pow from basic operations: exact repeated squaring for integral exponents, exp(y log x)
  // otherwise (corsa::det, identical on every platform).
  static double power(double x, double y, size_t column) {
    if (y == std::floor(y) && std::fabs(y) <= 4096.0) {
      if (x == 0.0 && y < 0.0) fail("pow(0, negative) is undefined", column);
      double result = 1.0;
      double base = x;
      auto n = static_cast<long long>(std::fabs(y));
      while (n > 0) {
        if (n & 1) result *= base;
        base *= base;
        n >>= 1;
      }
      return y < 0.0 ? 1.0 / result : result;
    }
    if (x < 0.0) fail("pow of a negative number to a non-integer power", column);
    if (x == 0.0) {
      if (y < 0.0) fail("pow(0, negative) is undefined", column);
      return 0.0;
    }
    return det::exp(y * det::log(x));
  }

  std::string_view text_;
  const ParameterLookup& lookup_;
  const ConstantNote& on_constant_;
  size_t pos_ = 0;
  int depth_ = 0;
  Token current_;
};

}  // namespace

ExprValue evaluate_expression(std::string_view text, const ParameterLookup& lookup,
                              const ConstantNote& on_constant) {
  Parser parser(text, lookup, on_constant);
  return parser.parse_all();
}

}  // namespace corsa::xosc
