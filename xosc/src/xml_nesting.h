#pragma once

// Internal: locates an element that is not closed properly in XML text.

#include <optional>
#include <string>
#include <string_view>

namespace corsa::xosc {

struct NestingError {
  int line;             ///< where the mistake shows (the wrong closing tag, or the opening tag)
  std::string message;  ///< names the tag and both lines
};

/// The first element closed by the wrong end tag (`<A> opened at line 3 is closed by </B> at
/// line 9`), never closed, or an end tag that closes nothing; nullopt when the nesting is
/// right (or the text is too broken to tell).
std::optional<NestingError> find_nesting_error(std::string_view text);

}  // namespace corsa::xosc
