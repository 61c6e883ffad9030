#pragma once

// What tinyxml2's parse errors mean, in words, for every reader of XML built on it (OpenSCENARIO,
// sensor rigs, suite manifests): tinyxml2's own ErrorStr() reads "Error=XML_ERROR_... ErrorID=13
// (0xd) Line number=0", which tells a user nothing.

#include <string>

namespace corsa {

/// Words for a tinyxml2::XMLError value, e.g. "mismatched closing tag". The value is passed as an
/// int so that no tinyxml2 type shows in core's public headers.
std::string xml_error_words(int tinyxml2_error);

}  // namespace corsa
