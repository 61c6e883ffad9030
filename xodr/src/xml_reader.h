#pragma once

// Attribute access with located errors for the OpenDRIVE parser. Private to corsa_xodr (the
// public headers never expose the XML layer).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/xodr/model.h"
#include "xml_dom.h"

namespace corsa::xodr::detail {

using XMLElement = XmlElement;

/// Iterates the child elements of an element: `for (const XMLElement* c : children(e))`.
class ChildRange {
 public:
  class Iterator {
   public:
    explicit Iterator(const XMLElement* e) : e_(e) {}
    const XMLElement* operator*() const { return e_; }
    Iterator& operator++() {
      e_ = e_->next_sibling();
      return *this;
    }
    bool operator!=(const Iterator& other) const { return e_ != other.e_; }

   private:
    const XMLElement* e_;
  };
  explicit ChildRange(const XMLElement* parent) : first_(parent->first_child()) {}
  Iterator begin() const { return Iterator(first_); }
  Iterator end() const { return Iterator(nullptr); }

 private:
  const XMLElement* first_;
};
inline ChildRange children(const XMLElement* e) { return ChildRange(e); }

inline bool named(const XMLElement* e, std::string_view name) { return e->name() == name; }

/// The file being read and where its warnings go.
class XmlReader {
 public:
  XmlReader(std::string file, corsa::Diagnostics& diagnostics)
      : file_(std::move(file)), diagnostics_(diagnostics) {}

  const std::string& file() const { return file_; }

  /// Throws InputError located at `e`.
  [[noreturn]] void fail(const XMLElement* e, const std::string& message) const;
  /// Warns at `e`, once per `key`.
  void warn_once(const std::string& key, const XMLElement* e, const std::string& message) const;
  /// Warns once per (parent, child name) that a child element is not understood.
  void unknown_child(const XMLElement* parent, const XMLElement* child) const;
  /// A rule broken in a way whose meaning is clear: warns `message (read as read_as)` at `e` and
  /// records it (MapData::lenient_readings), so that a strict reader can refuse the map.
  void lenient(const XMLElement* e, const std::string& message, const std::string& read_as) const;
  /// The lenient readings recorded so far, handed over (parse_document moves them into MapData).
  std::vector<LenientReading> take_lenient_readings() const;

  /// Required number: missing, empty, text, NaN or infinite -> error.
  double number(const XMLElement* e, const char* name) const;
  /// Optional number: missing -> fallback; present but not a finite number -> error.
  double number_or(const XMLElement* e, const char* name, double fallback) const;
  std::optional<double> optional_number(const XMLElement* e, const char* name) const;
  /// Required number that must be >= 0.
  double non_negative(const XMLElement* e, const char* name) const;
  double non_negative_or(const XMLElement* e, const char* name, double fallback) const;
  int integer(const XMLElement* e, const char* name) const;
  /// Required / optional string attributes.
  std::string text(const XMLElement* e, const char* name) const;
  std::string text_or(const XMLElement* e, const char* name, const char* fallback) const;

 private:
  std::string file_;
  corsa::Diagnostics& diagnostics_;
  /// A record of what was read, filled while parsing through the const reader.
  mutable std::vector<LenientReading> lenient_readings_;
};

/// "OpenDRIVE/road/planView/geometry" for an element.
std::string element_path(const XMLElement* e);

}  // namespace corsa::xodr::detail
