#pragma once

// What tinyxml2's parse errors mean, in words, for every reader of XML built on it (OpenSCENARIO,
// sensor rigs, suite manifests): tinyxml2's own ErrorStr() reads "Error=XML_ERROR_... ErrorID=13
// (0xd) Line number=0", which tells a user nothing.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace corsa {

/// A problem found in XML text before tinyxml2 reads it: its line and what it is.
struct XmlTextProblem {
  int line = 1;
  std::string message;
};

/// The code point a character reference names, from its body between "&#" and ";" ("65",
/// "x41"), when XML 1.0 allows it: decimal or hexadecimal digits and nothing else (§4.1 [66]: no
/// sign or blank) naming a Char (§2.2 [2]: tab, line feed, carriage return, U+0020-U+D7FF,
/// U+E000-U+FFFD or U+10000-U+10FFFF; never NUL, another control character, a surrogate, which
/// UTF-8 cannot encode, U+FFFE or U+FFFF). Nothing otherwise.
std::optional<uint32_t> xml_character_reference(std::string_view body);

/// The message for a character reference (body as for xml_character_reference, clipped) that
/// XML 1.0 does not allow.
std::string bad_character_reference_message(std::string_view body);

/// The first reference to an entity XML does not predefine (`&name;` other than lt, gt, amp,
/// apos and quot), the first character reference xml_character_reference refuses, both outside
/// comments, CDATA sections and processing instructions, or a DOCTYPE with declarations
/// (`[...]`): nothing when there is none. tinyxml2 reads no DTD and keeps such an entity
/// reference as text (XML 1.0 §4.1 requires it to be declared), keeps "&#-1;" too, writes a
/// surrogate as bytes no UTF-8 reader accepts and ends a value at "&#0;", so the readers built
/// on it refuse them instead of running with such a value.
std::optional<XmlTextProblem> find_undeclared_entity(std::string_view xml);

/// Words for a tinyxml2::XMLError value, e.g. "mismatched closing tag". The value is passed as an
/// int so that no tinyxml2 type shows in core's public headers.
std::string xml_error_words(int tinyxml2_error);

}  // namespace corsa
