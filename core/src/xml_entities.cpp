#include "corsa/core/xml_entities.h"

#include <algorithm>
#include <map>

#include "corsa/core/strings.h"

namespace corsa {

namespace {

constexpr size_t kMaxEntityGrowthBytes = size_t{16} << 20;

bool is_xml_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

bool is_entity_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '.' || c == ':' || static_cast<unsigned char>(c) >= 0x80;
}

int lines_before(std::string_view xml, size_t at) {
  return 1 + static_cast<int>(
                 std::count(xml.begin(), xml.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

// The length of the comment, CDATA section or processing instruction starting at `at`, 0 when
// none starts there (npos-terminated ones run to the end).
size_t skipped_markup_length(std::string_view xml, size_t at) {
  for (const auto& [open, close] : {std::pair<std::string_view, std::string_view>{"<!--", "-->"},
                                    {"<![CDATA[", "]]>"},
                                    {"<?", "?>"}}) {
    if (xml.substr(at, open.size()) == open) {
      const size_t found = xml.find(close, at + open.size());
      return (found == std::string_view::npos ? xml.size() : found + close.size()) - at;
    }
  }
  return 0;
}

// Where the DOCTYPE starts: the first markup that is no comment or processing instruction.
std::optional<size_t> find_doctype(std::string_view xml) {
  for (size_t i = 0; i < xml.size(); ++i) {
    if (xml[i] != '<') continue;
    if (const size_t skip = skipped_markup_length(xml, i); skip > 0) {
      i += skip - 1;
      continue;
    }
    if (xml.substr(i, 9) == "<!DOCTYPE") return i;
    return std::nullopt;  // the root element: no DOCTYPE before it
  }
  return std::nullopt;
}

// Where the declaration starting at `at` ends (one past its '>'), quoted text skipped.
size_t declaration_end(std::string_view xml, size_t at) {
  char quote = 0;
  for (size_t i = at; i < xml.size(); ++i) {
    if (quote != 0) {
      if (xml[i] == quote) quote = 0;
    } else if (xml[i] == '"' || xml[i] == '\'') {
      quote = xml[i];
    } else if (xml[i] == '>') {
      return i + 1;
    }
  }
  return std::string_view::npos;
}

// Where the DOCTYPE starting at `at` opens its internal subset ('[') or ends ('>'), quoted
// literals (its system and public ids) skipped; npos when neither comes.
size_t doctype_subset_or_end(std::string_view xml, size_t at) {
  char quote = 0;
  for (size_t i = at; i < xml.size(); ++i) {
    if (quote != 0) {
      if (xml[i] == quote) quote = 0;
    } else if (xml[i] == '"' || xml[i] == '\'') {
      quote = xml[i];
    } else if (xml[i] == '[' || xml[i] == '>') {
      return i;
    }
  }
  return std::string_view::npos;
}

// The value XML 1.0 (section 4.6) lets a declaration of a predefined entity give it: its
// character's reference (lt and amp doubly escaped); nullopt for any other name.
std::optional<std::string_view> predefined_entity_value(std::string_view name) {
  if (name == "lt") return "&#38;#60;";
  if (name == "gt") return "&#62;";
  if (name == "amp") return "&#38;#38;";
  if (name == "apos") return "&#39;";
  if (name == "quot") return "&#34;";
  return std::nullopt;
}

struct EntitySubset {
  std::map<std::string, std::string, std::less<>> values;
  size_t end = 0;  // one past the subset's ']'
};

// Reads one `<!ENTITY ...>` at `at` into `subset`; a problem when it is not an internal general
// entity with a plain value.
std::optional<XmlTextProblem> read_entity_declaration(std::string_view xml, size_t at, size_t& next,
                                                      EntitySubset& subset) {
  const auto problem = [&](const std::string& what) {
    return XmlTextProblem{lines_before(xml, at), what +
                                                     " (Corsa expands only internal entities "
                                                     "with plain values: write the value out)"};
  };
  size_t i = at + 8;
  while (i < xml.size() && is_xml_space(xml[i])) ++i;
  if (i < xml.size() && xml[i] == '%') return problem("a parameter entity is not read");
  const size_t name_start = i;
  while (i < xml.size() && is_entity_name_char(xml[i])) ++i;
  const std::string name(xml.substr(name_start, i - name_start));
  while (i < xml.size() && is_xml_space(xml[i])) ++i;
  if (name.empty() || i >= xml.size()) return problem("a bad <!ENTITY> declaration");
  if (xml[i] != '"' && xml[i] != '\'') {
    return problem("the external entity '" + clip(name) + "' is not read");
  }
  const size_t value_end = xml.find(xml[i], i + 1);
  if (value_end == std::string_view::npos) return problem("a bad <!ENTITY> declaration");
  const std::string_view value = xml.substr(i + 1, value_end - i - 1);
  const auto predefined = predefined_entity_value(name);
  if (predefined && value != *predefined) {
    return XmlTextProblem{lines_before(xml, at),
                          "the predefined entity '" + name + "' may be declared only as \"" +
                              std::string(*predefined) +
                              "\" (XML 1.0 section 4.6), not with another value"};
  }
  if (!predefined && value.find_first_of("&%<") != std::string_view::npos) {
    return problem("the value of entity '" + clip(name) + "' holds a reference or markup");
  }
  i = value_end + 1;
  while (i < xml.size() && is_xml_space(xml[i])) ++i;
  if (i >= xml.size() || xml[i] != '>') return problem("a bad <!ENTITY> declaration");
  // The first declaration binds; a predefined entity declared as XML allows keeps its meaning.
  if (!predefined) subset.values.emplace(name, std::string(value));
  next = i + 1;
  return std::nullopt;
}

std::optional<XmlTextProblem> read_internal_subset(std::string_view xml, size_t open,
                                                   EntitySubset& subset) {
  size_t i = open + 1;
  while (i < xml.size()) {
    if (is_xml_space(xml[i])) {
      ++i;
    } else if (xml[i] == ']') {
      subset.end = i + 1;
      return std::nullopt;
    } else if (const size_t skip = skipped_markup_length(xml, i); skip > 0) {
      i += skip;
    } else if (xml.substr(i, 8) == "<!ENTITY") {
      if (auto problem = read_entity_declaration(xml, i, i, subset)) return problem;
    } else if (xml.substr(i, 9) == "<!ELEMENT" || xml.substr(i, 10) == "<!NOTATION") {
      i = declaration_end(xml, i);
    } else {
      return XmlTextProblem{lines_before(xml, i),
                            "a DOCTYPE declaration other than <!ENTITY>, <!ELEMENT> or "
                            "<!NOTATION> is not read (an <!ATTLIST> would add attribute "
                            "defaults; a parameter entity reference is not expanded)"};
    }
  }
  return XmlTextProblem{lines_before(xml, open), "the DOCTYPE's internal subset is not closed"};
}

void append_entity_value(std::string_view value, std::string& out) {
  for (const char c : value) {
    switch (c) {
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      case '\n':
        out += "&#10;";
        break;
      case '\r':
        out += "&#13;";
        break;
      case '\t':
        out += "&#9;";
        break;
      default:
        out += c;
    }
  }
}

}  // namespace

std::optional<XmlTextProblem> expand_internal_entities(std::string_view xml,
                                                       std::string& expanded) {
  expanded.clear();
  const auto doctype = find_doctype(xml);
  if (!doctype) return std::nullopt;
  const size_t mark = doctype_subset_or_end(xml, *doctype);
  if (mark == std::string_view::npos || xml[mark] != '[') return std::nullopt;
  EntitySubset subset;
  if (auto problem = read_internal_subset(xml, mark, subset)) return problem;

  expanded.reserve(xml.size());
  expanded.append(xml.substr(0, mark));
  for (size_t i = mark; i < subset.end; ++i) expanded += xml[i] == '\n' ? '\n' : ' ';
  for (size_t i = subset.end; i < xml.size(); ++i) {
    if (const size_t skip = skipped_markup_length(xml, i); skip > 0) {
      expanded.append(xml.substr(i, skip));
      i += skip - 1;
      continue;
    }
    if (xml[i] == '&') {
      size_t end = i + 1;
      while (end < xml.size() && is_entity_name_char(xml[end])) ++end;
      if (end < xml.size() && xml[end] == ';') {
        const auto entity = subset.values.find(xml.substr(i + 1, end - i - 1));
        if (entity != subset.values.end()) {
          append_entity_value(entity->second, expanded);
          if (expanded.size() > xml.size() + kMaxEntityGrowthBytes) {
            expanded.clear();
            return XmlTextProblem{lines_before(xml, i),
                                  "entity expansion grows the file by more than 16 MiB"};
          }
          i = end;
          continue;
        }
      }
    }
    expanded += xml[i];
  }
  return std::nullopt;
}

}  // namespace corsa
