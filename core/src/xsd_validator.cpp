#include "corsa/core/xsd_validator.h"

#include <tinyxml2.h>

#include <algorithm>
#include <regex>
#include <stdexcept>

#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"
#include "corsa/core/xml_errors.h"

namespace corsa {
namespace {

using tinyxml2::XMLElement;

constexpr int kUnbounded = -1;

struct SimpleType {
  std::string base = "string";  // string, double, int, boolean
  std::optional<double> min_inclusive, max_inclusive, min_exclusive, max_exclusive;
  std::vector<std::string> enumeration;
  std::string pattern_text;
  std::shared_ptr<std::regex> pattern;
};

struct AttributeDecl {
  std::string name;
  std::string type;  // "xs:double" or a named simpleType
  bool required = false;
  std::optional<std::string> default_value;
};

struct Particle {
  enum class Kind { kElement, kSequence, kChoice } kind = Kind::kElement;
  int min = 1;
  int max = 1;  // kUnbounded for "unbounded"
  std::string name;
  std::string type;
  std::vector<Particle> children;
};

struct ComplexType {
  std::vector<AttributeDecl> attributes;
  std::vector<std::string> attribute_groups;
  std::optional<Particle> content;
};

std::string local_name(const char* qualified) {
  const std::string_view text(qualified);
  const size_t colon = text.find(':');
  return std::string(colon == std::string_view::npos ? text : text.substr(colon + 1));
}

std::string required_attr(const XMLElement& e, const char* name) {
  const char* value = e.Attribute(name);
  if (value == nullptr) {
    throw std::logic_error(std::string("schema: <") + e.Name() + "> without '" + name + "'");
  }
  return value;
}

int occurs(const XMLElement& e, const char* name) {
  const char* value = e.Attribute(name);
  if (value == nullptr) {
    return 1;
  }
  if (std::string_view(value) == "unbounded") {
    return kUnbounded;
  }
  const auto n = parse_int(value);
  if (!n || *n < 0) {
    throw std::logic_error(std::string("schema: bad ") + name);
  }
  return static_cast<int>(*n);
}

AttributeDecl read_attribute(const XMLElement& e) {
  AttributeDecl a;
  a.name = required_attr(e, "name");
  a.type = required_attr(e, "type");
  const char* use = e.Attribute("use");
  a.required = use != nullptr && std::string_view(use) == "required";
  if (const char* d = e.Attribute("default")) {
    a.default_value = d;
  }
  return a;
}

Particle read_particle(const XMLElement& e) {
  Particle p;
  const std::string kind = local_name(e.Name());
  p.min = occurs(e, "minOccurs");
  p.max = occurs(e, "maxOccurs");
  if (kind == "element") {
    p.kind = Particle::Kind::kElement;
    p.name = required_attr(e, "name");
    p.type = required_attr(e, "type");
    return p;
  }
  if (kind != "sequence" && kind != "choice") {
    throw std::logic_error("schema: unsupported particle <" + kind + ">");
  }
  p.kind = kind == "sequence" ? Particle::Kind::kSequence : Particle::Kind::kChoice;
  for (const XMLElement* c = e.FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
    if (local_name(c->Name()) != "annotation") {
      p.children.push_back(read_particle(*c));
    }
  }
  return p;
}

ComplexType read_complex_type(const XMLElement& e) {
  ComplexType t;
  for (const XMLElement* c = e.FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
    const std::string kind = local_name(c->Name());
    if (kind == "attribute") {
      t.attributes.push_back(read_attribute(*c));
    } else if (kind == "attributeGroup") {
      t.attribute_groups.push_back(required_attr(*c, "ref"));
    } else if (kind == "sequence" || kind == "choice") {
      t.content = read_particle(*c);
    } else if (kind != "annotation") {
      throw std::logic_error("schema: unsupported <" + kind + "> in complexType");
    }
  }
  return t;
}

SimpleType read_simple_type(const XMLElement& e) {
  const XMLElement* r = e.FirstChildElement();
  while (r != nullptr && local_name(r->Name()) == "annotation") {
    r = r->NextSiblingElement();
  }
  if (r == nullptr || local_name(r->Name()) != "restriction") {
    throw std::logic_error("schema: simpleType without restriction");
  }
  SimpleType t;
  t.base = local_name(required_attr(*r, "base").c_str());
  for (const XMLElement* f = r->FirstChildElement(); f != nullptr; f = f->NextSiblingElement()) {
    const std::string facet = local_name(f->Name());
    const std::string value = required_attr(*f, "value");
    if (facet == "enumeration") {
      t.enumeration.push_back(value);
    } else if (facet == "pattern") {
      t.pattern_text = value;
      t.pattern = std::make_shared<std::regex>(value, std::regex::ECMAScript);
    } else {
      const auto number = parse_double(value);
      if (!number) {
        throw std::logic_error("schema: bad facet value " + value);
      }
      if (facet == "minInclusive") {
        t.min_inclusive = number;
      } else if (facet == "maxInclusive") {
        t.max_inclusive = number;
      } else if (facet == "minExclusive") {
        t.min_exclusive = number;
      } else if (facet == "maxExclusive") {
        t.max_exclusive = number;
      } else {
        throw std::logic_error("schema: unsupported facet " + facet);
      }
    }
  }
  return t;
}

}  // namespace

struct XsdSchema::Definitions {
  std::string root_name;
  std::string root_type;
  std::map<std::string, ComplexType> complex_types;
  std::map<std::string, SimpleType> simple_types;
  std::map<std::string, std::vector<AttributeDecl>> attribute_groups;

  const ComplexType& complex(const std::string& name) const {
    const auto it = complex_types.find(name);
    if (it == complex_types.end()) {
      throw std::logic_error("schema: unknown complexType " + name);
    }
    return it->second;
  }
  SimpleType simple(const std::string& name) const {
    if (name.rfind("xs:", 0) == 0) {
      SimpleType t;
      t.base = name.substr(3);
      return t;
    }
    const auto it = simple_types.find(name);
    if (it == simple_types.end()) {
      throw std::logic_error("schema: unknown simpleType " + name);
    }
    return it->second;
  }
  /// Every attribute a complex type declares, directly or through its groups, in order.
  std::vector<AttributeDecl> attributes_of(const ComplexType& t) const {
    std::vector<AttributeDecl> all;
    for (const auto& group : t.attribute_groups) {
      const auto it = attribute_groups.find(group);
      if (it == attribute_groups.end()) {
        throw std::logic_error("schema: unknown attributeGroup " + group);
      }
      all.insert(all.end(), it->second.begin(), it->second.end());
    }
    all.insert(all.end(), t.attributes.begin(), t.attributes.end());
    return all;
  }
};

XsdSchema::XsdSchema(std::string_view xsd_text) : defs_(std::make_unique<Definitions>()) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xsd_text.data(), xsd_text.size()) != tinyxml2::XML_SUCCESS) {
    throw std::logic_error(std::string("schema is not well-formed: ") + doc.ErrorStr());
  }
  const XMLElement* root = doc.RootElement();
  for (const XMLElement* e = root->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
    const std::string kind = local_name(e->Name());
    if (kind == "element") {
      defs_->root_name = required_attr(*e, "name");
      defs_->root_type = required_attr(*e, "type");
    } else if (kind == "complexType") {
      defs_->complex_types[required_attr(*e, "name")] = read_complex_type(*e);
    } else if (kind == "simpleType") {
      defs_->simple_types[required_attr(*e, "name")] = read_simple_type(*e);
    } else if (kind == "attributeGroup") {
      auto& group = defs_->attribute_groups[required_attr(*e, "name")];
      for (const XMLElement* a = e->FirstChildElement("xs:attribute"); a != nullptr;
           a = a->NextSiblingElement("xs:attribute")) {
        group.push_back(read_attribute(*a));
      }
    } else if (kind != "annotation") {
      throw std::logic_error("schema: unsupported top-level <" + kind + ">");
    }
  }
  if (defs_->root_name.empty()) {
    throw std::logic_error("schema: no global element");
  }
}

XsdSchema::~XsdSchema() = default;
XsdSchema::XsdSchema(XsdSchema&&) noexcept = default;
XsdSchema& XsdSchema::operator=(XsdSchema&&) noexcept = default;

}  // namespace corsa

// --- instance validation --------------------------------------------------------------------

namespace corsa {
namespace {

class InstanceValidator {
 public:
  InstanceValidator(const XsdSchema::Definitions& defs, const std::string& file)
      : defs_(defs), file_(file) {}

  ValidatedElement element(const XMLElement& e, const std::string& type, const std::string& path);

 private:
  [[noreturn]] void fail(const XMLElement& e, const std::string& path, std::string message) const {
    throw InputError(make_error(file_, e.GetLineNum(), std::move(message), path));
  }
  void check_value(const XMLElement& e, const std::string& path, const AttributeDecl& decl,
                   const std::string& value) const;
  void attributes(const XMLElement& e, const ComplexType& type, const std::string& path,
                  ValidatedElement& out) const;
  bool match(const Particle& p, const std::vector<const XMLElement*>& kids, size_t& pos,
             const std::string& path, ValidatedElement& out);
  static std::string expected(const Particle& p);

  const XsdSchema::Definitions& defs_;
  const std::string& file_;
};

void InstanceValidator::check_value(const XMLElement& e, const std::string& path,
                                    const AttributeDecl& decl, const std::string& value) const {
  const SimpleType type = defs_.simple(decl.type);
  const std::string what = "attribute '" + decl.name + "' of <" + e.Name() + ">";
  if (!type.enumeration.empty()) {
    for (const auto& allowed : type.enumeration) {
      if (value == allowed) {
        return;
      }
    }
    std::string list;
    for (const auto& allowed : type.enumeration) {
      list += (list.empty() ? "'" : ", '") + allowed + "'";
    }
    fail(e, path,
         what + " is '" + value + "'" + did_you_mean(value, type.enumeration) +
             "; expected one of " + list);
  }
  if (type.pattern && !std::regex_match(value, *type.pattern)) {
    fail(e, path, what + " '" + value + "' does not match the pattern " + type.pattern_text);
  }
  if (type.base == "boolean") {
    if (value != "true" && value != "false" && value != "1" && value != "0") {
      fail(e, path, what + " is '" + value + "'; expected true or false");
    }
    return;
  }
  if (type.base != "double" && type.base != "int") {
    return;
  }
  std::optional<double> number;
  if (type.base == "int") {
    const auto i = parse_int(value);
    if (!i) {
      fail(e, path, what + " is '" + value + "'; expected an integer");
    }
    number = static_cast<double>(*i);
  } else {
    number = parse_double(value);
    if (!number) {
      fail(e, path, what + " is '" + value + "'; expected a number");
    }
  }
  const double v = *number;
  if (type.min_inclusive && v < *type.min_inclusive) {
    fail(e, path,
         what + " is " + value + ", below the minimum " + format_double(*type.min_inclusive));
  }
  if (type.max_inclusive && v > *type.max_inclusive) {
    fail(e, path,
         what + " is " + value + ", above the maximum " + format_double(*type.max_inclusive));
  }
  if (type.min_exclusive && v <= *type.min_exclusive) {
    fail(e, path,
         what + " is " + value + "; it must be greater than " + format_double(*type.min_exclusive));
  }
  if (type.max_exclusive && v >= *type.max_exclusive) {
    fail(e, path,
         what + " is " + value + "; it must be less than " + format_double(*type.max_exclusive));
  }
}

void InstanceValidator::attributes(const XMLElement& e, const ComplexType& type,
                                   const std::string& path, ValidatedElement& out) const {
  const std::vector<AttributeDecl> decls = defs_.attributes_of(type);
  for (const tinyxml2::XMLAttribute* a = e.FirstAttribute(); a != nullptr; a = a->Next()) {
    const std::string name = a->Name();
    if (name == "xmlns" || name.rfind("xmlns:", 0) == 0 || name.rfind("xsi:", 0) == 0) {
      continue;
    }
    const AttributeDecl* decl = nullptr;
    for (const auto& d : decls) {
      if (d.name == name) {
        decl = &d;
      }
    }
    if (decl == nullptr) {
      std::vector<std::string> names;
      for (const auto& d : decls) {
        names.push_back(d.name);
      }
      fail(e, path,
           "unknown attribute '" + name + "' on <" + e.Name() + ">" + did_you_mean(name, names));
    }
    check_value(e, path, *decl, a->Value());
    out.attributes[name] = a->Value();
  }
  for (const auto& d : decls) {
    if (out.attributes.count(d.name) != 0) {
      continue;
    }
    if (d.required) {
      fail(e, path, "<" + std::string(e.Name()) + "> needs the attribute '" + d.name + "'");
    }
    if (d.default_value) {
      out.attributes[d.name] = *d.default_value;
    }
  }
}

std::string InstanceValidator::expected(const Particle& p) {
  if (p.kind == Particle::Kind::kElement) {
    return "<" + p.name + ">";
  }
  std::string list;
  for (const auto& c : p.children) {
    list += (list.empty() ? "" : ", ") + expected(c);
  }
  return list;
}

bool InstanceValidator::match(const Particle& p, const std::vector<const XMLElement*>& kids,
                              size_t& pos, const std::string& path, ValidatedElement& out) {
  int count = 0;
  bool matched_empty = false;  // a group whose particles may all be absent matched nothing
  while (p.max == kUnbounded || count < p.max) {
    const size_t before = pos;
    bool ok = false;
    if (p.kind == Particle::Kind::kElement) {
      ok = pos < kids.size() && p.name == kids[pos]->Name();
      if (ok) {
        out.children.push_back(element(*kids[pos], p.type, path + "/" + p.name));
        ++pos;
      }
    } else if (p.kind == Particle::Kind::kSequence) {
      ok = true;
      for (const auto& c : p.children) {
        if (!match(c, kids, pos, path, out)) {
          ok = false;
          break;
        }
      }
    } else {
      for (const auto& c : p.children) {
        const size_t at = pos;
        if (match(c, kids, pos, path, out)) {
          ok = true;
          if (pos > at) {
            break;
          }
        }
      }
    }
    if (!ok) {
      pos = before;
      break;
    }
    if (pos == before) {
      matched_empty = true;
      break;
    }
    ++count;
  }
  return count >= p.min || matched_empty;
}

ValidatedElement InstanceValidator::element(const XMLElement& e, const std::string& type_name,
                                            const std::string& path) {
  const ComplexType& type = defs_.complex(type_name);
  ValidatedElement out;
  out.name = e.Name();
  out.line = e.GetLineNum();
  out.path = path;
  attributes(e, type, path, out);
  if (const char* text = e.GetText(); text != nullptr && !trim(text).empty()) {
    fail(e, path, "<" + out.name + "> has text content; only child elements are allowed");
  }
  std::vector<const XMLElement*> kids;
  for (const XMLElement* c = e.FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
    kids.push_back(c);
  }
  size_t pos = 0;
  if (type.content) {
    if (!match(*type.content, kids, pos, path, out)) {
      fail(e, path, "<" + out.name + "> is missing " + expected(*type.content));
    }
  }
  if (pos < kids.size()) {
    const std::string allowed = type.content ? expected(*type.content) : std::string("none");
    fail(*kids[pos], path,
         "element <" + std::string(kids[pos]->Name()) + "> is not allowed in <" + out.name +
             "> here (allowed: " + allowed + ")");
  }
  return out;
}

}  // namespace

ValidatedElement XsdSchema::validate(std::string_view xml, const std::string& file) const {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) {
    // tinyxml2's ErrorStr() reads "Error=XML_ERROR_... ErrorID=13 (0xd) Line number=0": say what
    // is wrong in words instead, and line 1 for an empty document (tinyxml2 gives line 0).
    throw InputError(make_error(file, std::max(1, doc.ErrorLineNum()),
                                "not well-formed XML: " + xml_error_words(doc.ErrorID())));
  }
  if (const auto problem = find_undeclared_entity(xml)) {
    throw InputError(make_error(file, problem->line, problem->message));
  }
  const XMLElement* root = doc.RootElement();
  if (root == nullptr || defs_->root_name != root->Name()) {
    throw InputError(make_error(file, root ? root->GetLineNum() : 1,
                                "expected the root element <" + defs_->root_name + ">"));
  }
  InstanceValidator validator(*defs_, file);
  return validator.element(*root, defs_->root_type, defs_->root_name);
}

}  // namespace corsa
