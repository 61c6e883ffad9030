// FileHeader, Properties, File, Range, ParameterAssignments and parameter scopes.

#include "parsers.h"

namespace corsa::xosc {

bool deprecated_attribute(ParseContext& ctx, const Element* element, const char* name,
                          std::initializer_list<const char*> replacements) {
  if (element->Attribute(name) == nullptr) return false;
  std::string instead;
  bool clash = false;
  for (const char* replacement : replacements) {
    instead += (instead.empty() ? "" : " or ") + std::string(replacement);
    const bool is_element = replacement[0] >= 'A' && replacement[0] <= 'Z';
    const bool present = is_element ? element->FirstChildElement(replacement) != nullptr
                                    : element->Attribute(replacement) != nullptr;
    if (present) {
      // The file says the same thing twice, possibly two different things: which one is meant
      // is not clear (the ASAM OpenSCENARIO API checker rejects it too).
      ctx.attribute_error(element, name,
                          "attribute '" + std::string(name) +
                              "' is deprecated and must not be used together with " +
                              (is_element ? "element <" + std::string(replacement) + ">"
                                          : "attribute '" + std::string(replacement) + "'"));
      clash = true;
    }
  }
  if (!clash) {
    ctx.deprecated(element, std::string("attribute ") + element->Name() + "." + name, instead);
  }
  return true;
}

namespace {

// A revision number (unsignedShort). esmini's speed-profile writes revMinor="1+" ("1 or later"):
// its leading number says the revision the file was written for, and the rest is a note. Text
// that does not start with a digit stays an error.
int read_revision(ParseContext& ctx, const Element* element, const char* name) {
  const char* raw = element->Attribute(name);
  if (raw != nullptr) {
    const std::string_view text(raw);
    size_t digits = 0;
    while (digits < text.size() && digits < 5 && text[digits] >= '0' && text[digits] <= '9') {
      ++digits;
    }
    if (digits > 0 && digits < text.size() && text[digits] != '.') {
      const std::string number(text.substr(0, digits));
      ctx.lenient(element,
                  "attribute " + std::string(name) + ": '" + clip(std::string(text)) +
                      "' is not an unsignedShort",
                  number + ", its leading number");
      return std::stoi(number);
    }
  }
  return static_cast<int>(ctx.req_int(element, name, ParameterType::kUnsignedShort));
}

}  // namespace

FileHeader parse_file_header(ParseContext& ctx, const Element* element) {
  Children kids(ctx, element, "FileHeader");
  FileHeader header;
  header.source = ctx.source(element);
  header.rev_major = read_revision(ctx, element, "revMajor");
  header.rev_minor = read_revision(ctx, element, "revMinor");
  // date, description and author are required by the XSD; tools often leave them out, which
  // costs nothing here, so a missing one is only a warning.
  for (const char* name : {"date", "description", "author"}) {
    if (element->Attribute(name) == nullptr) {
      ctx.warn_once(element, std::string("header:") + name,
                    std::string("<FileHeader> has no ") + name + " attribute");
    }
  }
  header.date = ctx.opt_str(element, "date").value_or("");
  header.description = ctx.opt_str(element, "description").value_or("");
  header.author = ctx.opt_str(element, "author").value_or("");
  if (const Element* license = kids.opt("License")) {
    Children(ctx, license, "License");
    header.license =
        License{ctx.req_str(license, "name"), ctx.opt_str(license, "resource"),
                ctx.opt_str(license, "spdxId"), element_text(license), ctx.source(license)};
  }
  if (const Element* properties = kids.opt("Properties")) {
    header.properties = parse_properties(ctx, properties);
  }
  const std::string version =
      std::to_string(header.rev_major) + "." + std::to_string(header.rev_minor);
  if (header.rev_major < 1) {
    // Pre-1.0 drafts (0.9) wrote the 1.0 forms.
    ctx.lenient(element, "OpenSCENARIO " + version + " is older than 1.0",
                "1.3 with the deprecated 1.0 forms accepted");
  } else if (header.rev_major > 1 || header.rev_minor > 3) {
    ctx.warn_once(element, "version",
                  "OpenSCENARIO " + version + " is newer than 1.3; reading it as 1.3");
  }
  return header;
}

Properties parse_properties(ParseContext& ctx, const Element* element) {
  Children kids(ctx, element, "Properties");
  Properties properties;
  properties.source = ctx.source(element);
  for (const Element* property : kids.all("Property")) {
    Children(ctx, property, "Property");
    properties.properties.push_back(
        {ctx.req_str(property, "name"), ctx.req_str(property, "value"), ctx.source(property)});
  }
  for (const Element* file : kids.all("File")) {
    properties.files.push_back(parse_file(ctx, file));
  }
  for (const Element* custom : kids.all("CustomContent")) {
    Children(ctx, custom, "CustomContent");
    properties.custom_content.push_back(element_text(custom));
  }
  return properties;
}

File parse_file(ParseContext& ctx, const Element* element) {
  Children(ctx, element, "File");
  return File{ctx.req_str(element, "filepath"), ctx.source(element)};
}

Range parse_range(ParseContext& ctx, const Element* element) {
  Children(ctx, element, "Range");
  Range range{ctx.req_double(element, "lowerLimit"), ctx.req_double(element, "upperLimit"),
              ctx.source(element)};
  if (range.lower_limit > range.upper_limit) {
    ctx.fail(element, "range lowerLimit is above upperLimit");
  }
  return range;
}

std::vector<ParameterAssignment> parse_parameter_assignments(ParseContext& ctx,
                                                             const Element* element) {
  std::vector<ParameterAssignment> assignments;
  if (element == nullptr) {
    return assignments;
  }
  Children kids(ctx, element, "ParameterAssignments");
  for (const Element* assignment : kids.all("ParameterAssignment")) {
    Children(ctx, assignment, "ParameterAssignment");
    std::string name = ctx.parameter_name(assignment, "parameterRef");
    assignments.push_back(
        {std::move(name), ctx.req_str(assignment, "value"), ctx.source(assignment)});
  }
  return assignments;
}

std::vector<ParameterDeclaration> open_scope(ParseContext& ctx, Children& kids,
                                             const EntryScope& scope) {
  static const std::vector<ParameterAssignment> kNone;
  return ctx.push_scope(kids.opt("ParameterDeclarations"),
                        scope.assignments == nullptr ? kNone : *scope.assignments, scope.isolated,
                        scope.owner);
}

}  // namespace corsa::xosc
