#pragma once

// ParameterDeclarations (OpenSCENARIO 1.3 §9.1), VariableDeclarations (§9.3), MonitorDeclarations
// and ParameterAssignments. The loader resolves every `$name` and `${expr}` in attributes at load
// time; these declarations are kept so that ParameterCondition / ParameterSetAction /
// VariableCondition / VariableSetAction can work on the values at run time.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "corsa/xosc/common.h"
#include "corsa/xosc/enums.h"

namespace corsa::xosc {

/// A typed value of a parameter or variable. int, unsignedInt and unsignedShort are kept as
/// int64_t (range-checked on load); dateTime and string as text.
struct Value {
  ParameterType type = ParameterType::kString;
  std::variant<bool, int64_t, double, std::string> data;

  /// The value as OpenSCENARIO text ("true", "42", "3.5", the string itself).
  std::string text() const;
  /// Numeric value for int/double/boolean types (boolean: 0 or 1); nullopt otherwise.
  std::optional<double> number() const;
};

/// Parses `text` as a value of `type`. Returns nullopt when it is not one (e.g. "abc" for double,
/// "70000" for unsignedShort, "1.5" for int).
std::optional<Value> parse_value(ParameterType type, std::string_view text);

/// Seconds since 1970-01-01T00:00:00Z of an xsd:dateTime text (a time without zone is taken as
/// UTC); nullopt when it is not one.
std::optional<double> date_time_instant(std::string_view text);

/// Compares two values with `rule` as ParameterCondition / VariableCondition / ValueConstraint do:
/// numerically for numeric and boolean types, as instants (time zones applied) for dateTime,
/// textually (equalTo / notEqualTo only, else false) for strings.
bool compare_values(const Value& left, Rule rule, const Value& right);

/// ValueConstraint: the parameter's value must satisfy `rule value` (§9.1.3).
struct ValueConstraint {
  Rule rule = Rule::kEqualTo;
  std::string value;
  Source source;
};

/// ValueConstraintGroup: all constraints of a group must hold; at least one group must hold.
struct ValueConstraintGroup {
  std::vector<ValueConstraint> constraints;
  Source source;
};

struct ParameterDeclaration {
  std::string name;
  ParameterType type = ParameterType::kString;
  /// The effective value: the declared one (with its own `$`/`${}` references resolved), or the
  /// one given from outside (LoadOptions::parameters) or by a catalog ParameterAssignment.
  Value value;
  /// The text of the value attribute exactly as written in the file.
  std::string declared_text;
  bool overridden = false;  ///< value came from outside the declaration
  std::vector<ValueConstraintGroup> constraint_groups;
  Source source;
};

struct VariableDeclaration {
  std::string name;
  ParameterType type = ParameterType::kString;
  Value value;  ///< initial value
  Source source;
};

/// MonitorDeclaration (1.3): a named boolean set by SetMonitorAction.
struct MonitorDeclaration {
  std::string name;
  bool value = false;
  Source source;
};

/// ParameterAssignment of a CatalogReference or ParameterValueSet. `value` is resolved in the
/// referencing scope, so it holds no `$` references.
struct ParameterAssignment {
  std::string parameter_ref;
  std::string value;
  Source source;
};

}  // namespace corsa::xosc
