#include "corsa/core/xml_errors.h"

#include <tinyxml2.h>

#include <algorithm>
#include <utility>

#include "corsa/core/strings.h"

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

namespace {

bool is_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '.' || c == ':' || static_cast<unsigned char>(c) >= 0x80;
}

}  // namespace

std::optional<uint32_t> xml_character_reference(std::string_view body) {
  const bool hex = body.starts_with('x') || body.starts_with('X');
  const std::string_view digits = body.substr(hex ? 1 : 0);
  if (digits.empty()) {
    return std::nullopt;
  }
  uint32_t code = 0;
  for (const char c : digits) {
    uint32_t digit = 0;
    if (c >= '0' && c <= '9') {
      digit = static_cast<uint32_t>(c - '0');
    } else if (hex && c >= 'a' && c <= 'f') {
      digit = static_cast<uint32_t>(c - 'a' + 10);
    } else if (hex && c >= 'A' && c <= 'F') {
      digit = static_cast<uint32_t>(c - 'A' + 10);
    } else {
      return std::nullopt;
    }
    code = code * (hex ? 16 : 10) + digit;
    if (code > 0x10FFFF) {
      return std::nullopt;  // stops before the digits could overflow
    }
  }
  const bool allowed = code == 0x9 || code == 0xA || code == 0xD ||
                       (code >= 0x20 && code <= 0xD7FF) || (code >= 0xE000 && code <= 0xFFFD) ||
                       code >= 0x10000;
  return allowed ? std::optional<uint32_t>(code) : std::nullopt;
}

std::string bad_character_reference_message(std::string_view body) {
  return "bad character reference '&#" + clip(body) +
         ";' (XML 1.0 §4.1, §2.2: plain digits naming a character other than NUL, a control "
         "character, a surrogate, U+FFFE or U+FFFF)";
}

std::optional<XmlTextProblem> find_undeclared_entity(std::string_view xml) {
  int line = 1;
  for (size_t i = 0; i < xml.size(); ++i) {
    // Only '<', '&' and line ends start anything looked at below: the rest is passed over at a
    // few instructions a character (a scenario's catalogs are read through here at every run).
    while (xml[i] != '<' && xml[i] != '&' && xml[i] != '\n') {
      if (++i == xml.size()) return std::nullopt;
    }
    // Comments, CDATA sections and processing instructions may hold any '&'.
    bool skipped = false;
    for (const auto& [open, close] : {std::pair<std::string_view, std::string_view>{"<!--", "-->"},
                                      {"<![CDATA[", "]]>"},
                                      {"<?", "?>"}}) {
      if (xml[i] == '<' && xml.substr(i, open.size()) == open) {
        const size_t found = xml.find(close, i + open.size());
        const size_t end = found == std::string_view::npos ? xml.size() : found + close.size();
        line += static_cast<int>(std::count(xml.begin() + static_cast<std::ptrdiff_t>(i),
                                            xml.begin() + static_cast<std::ptrdiff_t>(end), '\n'));
        i = end - 1;
        skipped = true;
        break;
      }
    }
    if (skipped) continue;
    if (xml[i] == '\n') {
      ++line;
    } else if (xml.substr(i, 9) == "<!DOCTYPE") {
      const size_t mark = xml.find_first_of("[>", i);
      if (mark != std::string_view::npos && xml[mark] == '[') {
        return XmlTextProblem{
            line,
            "a DOCTYPE with declarations is not read (no DTD entity is expanded); "
            "write the values out"};
      }
    } else if (xml[i] == '&' && i + 1 < xml.size() && xml[i + 1] == '#') {
      const size_t semi = xml.find(';', i + 2);
      const std::string_view body =
          xml.substr(i + 2, semi == std::string_view::npos ? std::string_view::npos : semi - i - 2);
      if (semi == std::string_view::npos || !xml_character_reference(body)) {
        return XmlTextProblem{line, bad_character_reference_message(body)};
      }
    } else if (xml[i] == '&') {
      size_t end = i + 1;
      while (end < xml.size() && end - i <= 64 && is_name_char(xml[end])) ++end;
      const std::string_view name = xml.substr(i + 1, end - i - 1);
      if (end < xml.size() && xml[end] == ';' && !name.empty() && name != "lt" && name != "gt" &&
          name != "amp" && name != "apos" && name != "quot") {
        return XmlTextProblem{line, "entity '&" + std::string(name) +
                                        ";' is not declared (XML 1.0 §4.1); Corsa's XML readers "
                                        "expand no DTD entities: write the value out"};
      }
    }
  }
  return std::nullopt;
}

}  // namespace corsa
