#pragma once

// A small, fast, read-only XML reader for OpenDRIVE files (private to corsa_xodr).
//
// Why not tinyxml2: its DOM alone takes ~22 ms on CARLA's 3.4 MB Town04 on our 2-core machine,
// against a budget of 12 ms for the whole parse. This reader parses in place (one pass, no
// per-node allocation: elements and attributes live in two flat vectors, names and values are
// views into the owned text) and covers the XML that map files use: the declaration, comments,
// processing instructions, DOCTYPE, CDATA, the five predefined entities and character
// references, single- or double-quoted attributes. Malformed input (a truncated file, a
// mismatched end tag, a missing quote) throws corsa::InputError with the line.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace corsa::xodr::detail {

class XmlDocument;

class XmlElement {
 public:
  std::string_view name() const { return name_; }
  int line() const { return line_; }
  /// The attribute's (entity-decoded) value, or nullptr when absent.
  const std::string_view* attribute(std::string_view name) const;
  /// Concatenated character data and CDATA directly inside the element (entity-decoded).
  std::string_view text() const { return text_; }
  const XmlElement* first_child() const;
  const XmlElement* next_sibling() const;
  const XmlElement* parent() const;

 private:
  friend class XmlDocument;
  friend class XmlParser;
  const XmlDocument* document_ = nullptr;
  std::string_view name_;
  std::string_view text_;
  uint32_t attr_begin_ = 0;
  uint32_t attr_end_ = 0;
  uint32_t parent_ = UINT32_MAX;
  uint32_t first_child_ = UINT32_MAX;
  uint32_t last_child_ = UINT32_MAX;
  uint32_t next_sibling_ = UINT32_MAX;
  int line_ = 0;
};

class XmlDocument {
 public:
  /// Parses `text` (taken over). `file` is used in error messages.
  XmlDocument(std::string text, const std::string& file);
  XmlDocument(const XmlDocument&) = delete;
  XmlDocument& operator=(const XmlDocument&) = delete;

  const XmlElement* root() const { return elements_.empty() ? nullptr : &elements_[0]; }

 private:
  friend class XmlElement;
  friend class XmlParser;
  struct Attribute {
    std::string_view name;
    std::string_view value;
  };
  std::string text_;
  std::vector<XmlElement> elements_;
  std::vector<Attribute> attributes_;
};

}  // namespace corsa::xodr::detail
