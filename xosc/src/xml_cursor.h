#pragma once

// Internal: a position in XML text that counts lines, for the scanners that take a second look
// at XML (xml_nesting.cpp finds a badly closed element, xml_attributes.cpp an attribute written
// twice). Both walk the text from one '<' to the next and step over comments, CDATA sections and
// processing instructions the same way.

#include <cstddef>
#include <optional>
#include <string_view>

namespace corsa::xosc {

class XmlCursor {
 public:
  explicit XmlCursor(std::string_view text) : text_(text) {}

 protected:
  bool starts(std::string_view prefix) const { return text_.substr(pos_, prefix.size()) == prefix; }

  /// Moves to `to` (at most the end of the text), counting the line breaks passed.
  void advance_to(size_t to) {
    for (; pos_ < to && pos_ < text_.size(); ++pos_) {
      if (text_[pos_] == '\n') ++line_;
    }
  }

  /// Moves past the next `end`; false (not moved) when the text has none.
  bool skip_past(std::string_view end) {
    const size_t found = text_.find(end, pos_);
    if (found == std::string_view::npos) return false;
    advance_to(found + end.size());
    return true;
  }

  /// Moves to the next '<'; false when none is left.
  bool next_markup() {
    const size_t lt = text_.find('<', pos_);
    if (lt == std::string_view::npos) return false;
    advance_to(lt);
    return true;
  }

  /// At a comment, CDATA section or processing instruction: moves past it and says whether it
  /// was closed (false: it runs to the end of the text). Elsewhere: nothing, and no move.
  std::optional<bool> skip_comment_cdata_or_pi() {
    if (starts("<!--")) return skip_past("-->");
    if (starts("<![CDATA[")) return skip_past("]]>");
    if (starts("<?")) return skip_past("?>");
    return std::nullopt;
  }

  std::string_view text_;
  size_t pos_ = 0;
  int line_ = 1;
};

}  // namespace corsa::xosc
