#pragma once

// Minimal deterministic XML text builder for the OpenDRIVE writer (private to corsa_xodr):
// two-space indentation, attributes in the order given, numbers in shortest round-trip form.

#include <string>
#include <string_view>
#include <vector>

namespace corsa::xodr::detail {

class XmlWriter {
 public:
  XmlWriter() { out_ = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"; }

  /// Opens `<name`; attributes follow; then close_start() (children) or end_empty().
  XmlWriter& open(std::string_view name);
  XmlWriter& attr(std::string_view name, std::string_view value);
  XmlWriter& attr(std::string_view name, const char* value) {
    return attr(name, std::string_view(value));
  }
  XmlWriter& attr(std::string_view name, const std::string& value) {
    return attr(name, std::string_view(value));
  }
  XmlWriter& attr(std::string_view name, double value);
  XmlWriter& attr(std::string_view name, int value);
  /// Ends the start tag so that children can follow.
  void children();
  /// Ends an element without children (`/>`).
  void end_empty();
  /// Closes the innermost element opened with children().
  void close();
  /// An element with text content in a CDATA section.
  void cdata_element(std::string_view name, std::string_view text);

  const std::string& text() const { return out_; }

 private:
  void indent();
  std::string out_;
  std::vector<std::string> stack_;
  std::string pending_;
};

}  // namespace corsa::xodr::detail
