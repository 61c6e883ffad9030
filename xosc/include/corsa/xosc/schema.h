#pragma once

// What the loader knows of the OpenSCENARIO 1.3 schema: element names, and for each element kind
// its allowed children and attributes. docs/osc-coverage.md is checked against this list.

#include <span>
#include <string_view>

namespace corsa::xosc {

/// Coverage of an element by Corsa.
enum class Support { kParsed, kNotYet };

struct ElementInfo {
  std::string_view name;  ///< XML element name, e.g. "SpeedAction"
  Support support;
};

/// Every element name of OpenSCENARIO 1.3 that the loader accepts, sorted by name, with whether
/// it is parsed into the model.
std::span<const ElementInfo> known_elements();

}  // namespace corsa::xosc
