#pragma once

// Internal: the per-type rules of the OpenSCENARIO schema (see schema.cpp).

#include <string_view>
#include <vector>

#include "corsa/xosc/schema.h"

namespace corsa::xosc {

struct TypeRule {
  std::string_view type;
  std::vector<std::string_view> children;
  std::vector<std::string_view> attributes;

  bool allows_child(std::string_view name) const;
  bool allows_attribute(std::string_view name) const;
};

/// The rule of an XSD complex type, or null when the type is not in the table (our bug).
const TypeRule* find_type_rule(std::string_view type);

}  // namespace corsa::xosc
