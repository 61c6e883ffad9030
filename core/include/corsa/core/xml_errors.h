#pragma once

// What tinyxml2's parse errors mean, in words, for every reader of XML built on it (OpenSCENARIO,
// sensor rigs, suite manifests): tinyxml2's own ErrorStr() reads "Error=XML_ERROR_... ErrorID=13
// (0xd) Line number=0", which tells a user nothing.

#include <optional>
#include <string>
#include <string_view>

namespace corsa {

/// A problem found in XML text before tinyxml2 reads it: its line and what it is.
struct XmlTextProblem {
  int line = 1;
  std::string message;
};

/// The first reference to an entity XML does not predefine (`&name;` other than lt, gt, amp,
/// apos and quot; character references are fine) outside comments, CDATA sections and
/// processing instructions, or a DOCTYPE with declarations (`[...]`): nothing when there is
/// none. tinyxml2 reads no DTD and keeps such a reference as text (XML 1.0 §4.1 requires it to
/// be declared), so the readers built on it refuse it instead of running with "&x;" as a value.
std::optional<XmlTextProblem> find_undeclared_entity(std::string_view xml);

/// Words for a tinyxml2::XMLError value, e.g. "mismatched closing tag". The value is passed as an
/// int so that no tinyxml2 type shows in core's public headers.
std::string xml_error_words(int tinyxml2_error);

}  // namespace corsa
