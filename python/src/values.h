#pragma once

// OpenSCENARIO values (parameters, variables, UserDefinedValueCondition values) to and from
// Python: booleans as bool, the integer types as int, double as float, string and dateTime as
// str.

#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <string_view>

#include "corsa/xosc/parameters.h"

namespace corsa::python {

pybind11::object to_python(const xosc::Value& value);

/// A Python value as an OpenSCENARIO value; None is nothing. Throws pybind11::type_error naming
/// `what` for anything else.
std::optional<xosc::Value> from_python(const pybind11::handle& value, std::string_view what);

/// A Python value as parameter text for `--param NAME=VALUE`: bool as true/false, numbers in
/// their shortest round-trip text, str as it is. Throws pybind11::type_error naming `what`.
std::string parameter_text(const pybind11::handle& value, std::string_view what);

}  // namespace corsa::python
