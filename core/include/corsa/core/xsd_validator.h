#pragma once

// Validation of an XML document against an XSD, for the subset of XSD 1.0 that Corsa's own
// schemas use: a global root element; named complexTypes with element-only content given by
// nested sequence/choice groups (minOccurs/maxOccurs) and attributes (direct or through
// attributeGroup refs, use="required", default); named simpleTypes restricting xs:string,
// xs:double, xs:int or xs:boolean by min/max (in|ex)clusive, enumeration and pattern facets.
// Anything else in a schema is our bug and throws std::logic_error when the schema is read.
// Errors in the instance document throw corsa::InputError located at the offending line.
//
// Used for Corsa's own formats: sensor rigs (sensors) and suite manifests (suite). tinyxml2 reads
// the documents inside; no tinyxml2 type shows here.

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace corsa {

/// An element of a document that passed validation; attributes include the schema's defaults.
struct ValidatedElement {
  std::string name;
  int line = 0;
  std::string path;  ///< e.g. "SensorRig/Lidar"
  std::map<std::string, std::string> attributes;
  std::vector<ValidatedElement> children;

  /// The attribute's value (present or defaulted), nullptr when neither.
  const std::string* find(const std::string& attribute) const {
    const auto it = attributes.find(attribute);
    return it == attributes.end() ? nullptr : &it->second;
  }
};

class XsdSchema {
 public:
  /// Reads a schema (throws std::logic_error for a malformed or unsupported schema).
  explicit XsdSchema(std::string_view xsd_text);
  ~XsdSchema();
  XsdSchema(XsdSchema&&) noexcept;
  XsdSchema& operator=(XsdSchema&&) noexcept;

  /// Parses and validates `xml`; `file` names it in diagnostics. Throws corsa::InputError.
  ValidatedElement validate(std::string_view xml, const std::string& file) const;

  struct Definitions;  ///< the parsed schema (xsd_validator.cpp)

 private:
  std::unique_ptr<Definitions> defs_;
};

}  // namespace corsa
