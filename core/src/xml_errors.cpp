#include "corsa/core/xml_errors.h"

#include <tinyxml2.h>

namespace corsa {

std::string xml_error_words(int tinyxml2_error) {
  const auto error = static_cast<tinyxml2::XMLError>(tinyxml2_error);
  switch (error) {
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT:
      return "empty document";
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT:
      return "mismatched closing tag";
    case tinyxml2::XML_ERROR_PARSING_ELEMENT:
      return "bad element (unclosed or mis-nested tag, truncated file?)";
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE:
      return "bad attribute";
    case tinyxml2::XML_ERROR_PARSING_TEXT:
      return "bad text";
    case tinyxml2::XML_ERROR_PARSING_CDATA:
      return "bad CDATA section";
    case tinyxml2::XML_ERROR_PARSING_COMMENT:
      return "bad comment";
    case tinyxml2::XML_ERROR_PARSING_DECLARATION:
      return "bad XML declaration";
    case tinyxml2::XML_ERROR_PARSING_UNKNOWN:
      return "bad markup";
    case tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED:
      return "elements nested too deeply (tinyxml2 reads at most " +
             std::to_string(TINYXML2_MAX_ELEMENT_DEPTH) + " levels)";
    default:
      return std::string("cannot parse (") + tinyxml2::XMLDocument::ErrorIDToName(error) + ")";
  }
}

}  // namespace corsa
