// Typed parameter values: parsing per OpenSCENARIO parameter type (XSD built-in types) and the
// comparisons of ParameterCondition / VariableCondition / ValueConstraint.

#include <limits>

#include "corsa/core/strings.h"
#include "corsa/xosc/parameters.h"

namespace corsa::xosc {
namespace {

bool digits(std::string_view text, size_t from, size_t count) {
  if (from + count > text.size()) {
    return false;
  }
  for (size_t i = from; i < from + count; ++i) {
    if (text[i] < '0' || text[i] > '9') {
      return false;
    }
  }
  return true;
}

// xsd:dateTime: YYYY-MM-DDThh:mm:ss[.fraction][Z|(+|-)hh:mm].
bool is_date_time(std::string_view text) {
  if (!digits(text, 0, 4) || text.size() < 19 || text[4] != '-' || !digits(text, 5, 2) ||
      text[7] != '-' || !digits(text, 8, 2) || text[10] != 'T' || !digits(text, 11, 2) ||
      text[13] != ':' || !digits(text, 14, 2) || text[16] != ':' || !digits(text, 17, 2)) {
    return false;
  }
  size_t i = 19;
  if (i < text.size() && text[i] == '.') {
    ++i;
    const size_t start = i;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9') {
      ++i;
    }
    if (i == start) {
      return false;
    }
  }
  if (i == text.size()) {
    return true;
  }
  if (text[i] == 'Z') {
    return i + 1 == text.size();
  }
  return (text[i] == '+' || text[i] == '-') && i + 6 == text.size() && digits(text, i + 1, 2) &&
         text[i + 3] == ':' && digits(text, i + 4, 2);
}

}  // namespace

std::string Value::text() const {
  if (const auto* b = std::get_if<bool>(&data)) {
    return *b ? "true" : "false";
  }
  if (const auto* i = std::get_if<int64_t>(&data)) {
    return std::to_string(*i);
  }
  if (const auto* d = std::get_if<double>(&data)) {
    return format_double(*d);
  }
  return std::get<std::string>(data);
}

std::optional<double> Value::number() const {
  if (const auto* b = std::get_if<bool>(&data)) {
    return *b ? 1.0 : 0.0;
  }
  if (const auto* i = std::get_if<int64_t>(&data)) {
    return static_cast<double>(*i);
  }
  if (const auto* d = std::get_if<double>(&data)) {
    return *d;
  }
  return std::nullopt;
}

std::optional<Value> parse_value(ParameterType type, std::string_view text) {
  const std::string_view trimmed = trim(text);
  switch (type) {
    case ParameterType::kBoolean:
      if (trimmed == "true" || trimmed == "1") return Value{type, true};
      if (trimmed == "false" || trimmed == "0") return Value{type, false};
      return std::nullopt;
    case ParameterType::kDouble: {
      const auto value = parse_double(trimmed);
      return value ? std::optional<Value>(Value{type, *value}) : std::nullopt;
    }
    case ParameterType::kInt:
    case ParameterType::kUnsignedInt:
    case ParameterType::kUnsignedShort: {
      const auto value = parse_int(trimmed);
      if (!value) return std::nullopt;
      // xsd:int is 32-bit signed, xsd:unsignedInt 32-bit, xsd:unsignedShort 16-bit.
      const int64_t lo = type == ParameterType::kInt ? std::numeric_limits<int32_t>::min() : 0;
      const int64_t hi = type == ParameterType::kInt           ? std::numeric_limits<int32_t>::max()
                         : type == ParameterType::kUnsignedInt ? int64_t{4294967295}
                                                               : int64_t{65535};
      if (*value < lo || *value > hi) return std::nullopt;
      return Value{type, *value};
    }
    case ParameterType::kDateTime:
      if (!is_date_time(trimmed)) return std::nullopt;
      return Value{type, std::string(trimmed)};
    case ParameterType::kString:
      return Value{type, std::string(text)};
  }
  return std::nullopt;
}

bool compare_values(const Value& left, Rule rule, const Value& right) {
  const auto l = left.number();
  const auto r = right.number();
  if (l && r) {
    switch (rule) {
      case Rule::kEqualTo:
        return *l == *r;
      case Rule::kNotEqualTo:
        return *l != *r;
      case Rule::kGreaterThan:
        return *l > *r;
      case Rule::kLessThan:
        return *l < *r;
      case Rule::kGreaterOrEqual:
        return *l >= *r;
      case Rule::kLessOrEqual:
        return *l <= *r;
    }
    return false;
  }
  const std::string a = left.text();
  const std::string b = right.text();
  // dateTime texts of one format order chronologically as strings; plain strings only compare
  // for (in)equality.
  const bool ordered = left.type == ParameterType::kDateTime;
  switch (rule) {
    case Rule::kEqualTo:
      return a == b;
    case Rule::kNotEqualTo:
      return a != b;
    case Rule::kGreaterThan:
      return ordered && a > b;
    case Rule::kLessThan:
      return ordered && a < b;
    case Rule::kGreaterOrEqual:
      return ordered && a >= b;
    case Rule::kLessOrEqual:
      return ordered && a <= b;
  }
  return false;
}

}  // namespace corsa::xosc
