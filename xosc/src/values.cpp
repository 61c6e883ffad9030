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

// Days since 1970-01-01 of a proleptic Gregorian date (H. Hinnant's days_from_civil).
int64_t days_from_civil(int64_t y, int64_t m, int64_t d) {
  y -= m <= 2 ? 1 : 0;
  const int64_t era = (y >= 0 ? y : y - 399) / 400;
  const int64_t yoe = y - era * 400;
  const int64_t doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

int number_at(std::string_view text, size_t from, size_t count) {
  int value = 0;
  for (size_t i = from; i < from + count; ++i) value = value * 10 + (text[i] - '0');
  return value;
}

}  // namespace

std::optional<double> date_time_instant(std::string_view text) {
  text = trim(text);
  if (!is_date_time(text)) return std::nullopt;
  const int64_t days =
      days_from_civil(number_at(text, 0, 4), number_at(text, 5, 2), number_at(text, 8, 2));
  double seconds = static_cast<double>(days) * 86400.0 + number_at(text, 11, 2) * 3600.0 +
                   number_at(text, 14, 2) * 60.0 + number_at(text, 17, 2);
  size_t i = 19;
  if (i < text.size() && text[i] == '.') {
    double scale = 0.1;
    for (++i; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i, scale /= 10.0) {
      seconds += (text[i] - '0') * scale;
    }
  }
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) {
    // The time is local to the zone: UTC = local - offset.
    const double offset = number_at(text, i + 1, 2) * 3600.0 + number_at(text, i + 4, 2) * 60.0;
    seconds += text[i] == '+' ? -offset : offset;
  }
  return seconds;
}

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
  if (left.type == ParameterType::kDateTime && right.type == ParameterType::kDateTime) {
    // Instants, whatever the time zones they are written in (xsd:dateTime).
    const auto a = date_time_instant(left.text());
    const auto b = date_time_instant(right.text());
    if (a && b) {
      return compare_values(Value{ParameterType::kDouble, *a}, rule,
                            Value{ParameterType::kDouble, *b});
    }
  }
  const std::string a = left.text();
  const std::string b = right.text();
  // Plain strings only compare for (in)equality (§9.1.3 allows no other rule on them).
  const bool ordered = false;
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
