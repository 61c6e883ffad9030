#pragma once

// Values, expressions and names from a scenario file as error messages quote them.

#include <cstddef>
#include <string>
#include <string_view>

#include "corsa/core/strings.h"

namespace corsa::xosc {

/// Most bytes of a value, expression or name from the file quoted in a message.
inline constexpr size_t kMaxEchoBytes = 200;

/// `text` from the file as a message quotes it: clipped to kMaxEchoBytes (a parameter value may
/// be megabytes long, and was once printed whole).
inline std::string echo(std::string_view text) { return clip(text, kMaxEchoBytes); }

}  // namespace corsa::xosc
