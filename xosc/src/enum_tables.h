#pragma once

// Internal: the text <-> value tables of the OpenSCENARIO enumerations.

#include <span>
#include <string_view>

#include "corsa/xosc/enums.h"

namespace corsa::xosc {

template <class E>
struct EnumEntry {
  std::string_view name;
  E value;
  bool deprecated = false;       ///< a spelling 1.3 deprecates
  std::string_view replacement;  ///< the 1.3 spelling to use instead, if any
};

template <class E>
std::span<const EnumEntry<E>> enum_entries();
template <class E>
std::string_view enum_type_name();

#define CORSA_XOSC_DECLARE_TABLE(E)                \
  template <>                                      \
  std::span<const EnumEntry<E>> enum_entries<E>(); \
  template <>                                      \
  std::string_view enum_type_name<E>();
CORSA_XOSC_ENUMS(CORSA_XOSC_DECLARE_TABLE)
#undef CORSA_XOSC_DECLARE_TABLE

/// The entry spelled exactly `text` (OpenSCENARIO enumerations are case-sensitive), or null.
template <class E>
const EnumEntry<E>* find_enum(std::string_view text) {
  for (const auto& entry : enum_entries<E>()) {
    if (entry.name == text) {
      return &entry;
    }
  }
  return nullptr;
}

}  // namespace corsa::xosc
