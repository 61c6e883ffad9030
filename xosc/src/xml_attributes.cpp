// Attributes written twice in one start tag, and an XML declaration after comments
// (xml_attributes.h).

#include "xml_attributes.h"

#include <algorithm>
#include <optional>
#include <string_view>

#include "xml_cursor.h"

namespace corsa::xosc {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

bool ends_attribute_name(char c) { return is_blank(c) || c == '=' || c == '/' || c == '>'; }

struct AttributeSpan {
  std::string_view name;
  std::string_view value;
  size_t begin;  ///< first character of the name
  size_t end;    ///< one past the closing quote
};

// Start tags' names and attributes read from the cursor's position.
class AttributeCursor : protected XmlCursor {
 public:
  explicit AttributeCursor(std::string_view text) : XmlCursor(text) {}

 protected:
  void skip_blanks() {
    while (pos_ < text_.size() && is_blank(text_[pos_])) advance_to(pos_ + 1);
  }

  // At a start tag's '<': moves past its name and returns it.
  std::string_view tag_name() {
    advance_to(pos_ + 1);
    size_t end = pos_;
    while (end < text_.size() && !ends_attribute_name(text_[end])) ++end;
    const std::string_view name = text_.substr(pos_, end - pos_);
    advance_to(end);
    return name;
  }

  // name = "value" or name = 'value', from pos_; nothing when the text is not one.
  std::optional<AttributeSpan> attribute() {
    AttributeSpan span{};
    span.begin = pos_;
    size_t end = pos_;
    while (end < text_.size() && !ends_attribute_name(text_[end])) ++end;
    if (end == pos_) return std::nullopt;
    span.name = text_.substr(pos_, end - pos_);
    advance_to(end);
    skip_blanks();
    if (pos_ >= text_.size() || text_[pos_] != '=') return std::nullopt;
    advance_to(pos_ + 1);
    skip_blanks();
    if (pos_ >= text_.size() || (text_[pos_] != '"' && text_[pos_] != '\'')) return std::nullopt;
    const size_t close = text_.find(text_[pos_], pos_ + 1);
    if (close == std::string_view::npos) return std::nullopt;
    span.value = text_.substr(pos_ + 1, close - pos_ - 1);
    advance_to(close + 1);
    span.end = pos_;
    return span;
  }
};

// Reads through the cursor's view of the text and blanks repeats through `writable_`, the same
// characters (blanking keeps the length, so the view stays valid).
class AttributeScanner : private AttributeCursor {
 public:
  explicit AttributeScanner(std::string& text) : AttributeCursor(text), writable_(text) {}

  std::vector<RepeatedAttribute> run() {
    while (next_markup()) {
      bool scanned = true;
      if (const auto closed = skip_comment_cdata_or_pi()) {
        scanned = *closed;
      } else if (starts("<!") || starts("</")) {
        scanned = skip_past(">");
      } else {
        scanned = start_tag();
      }
      if (!scanned) break;
    }
    return std::move(found_);
  }

 private:
  // Blanks out the text's [begin, end) except its line breaks.
  void blank(size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      if (writable_[i] != '\n' && writable_[i] != '\r') writable_[i] = ' ';
    }
  }

  bool start_tag() {
    const std::string element(tag_name());
    std::vector<AttributeSpan> seen;
    for (;;) {
      skip_blanks();
      if (pos_ >= text_.size()) return false;
      if (text_[pos_] == '>' || starts("/>")) return skip_past(">");
      const int line = line_;
      const auto span = attribute();
      if (!span) return false;
      const AttributeSpan* first = nullptr;
      for (const auto& other : seen) {
        if (other.name == span->name) first = &other;
      }
      if (first == nullptr) {
        seen.push_back(*span);
        continue;
      }
      // Copied before blanking: the views point into the text.
      found_.push_back({line, element, std::string(span->name), std::string(first->value),
                        std::string(span->value)});
      blank(span->begin, span->end);
    }
  }

  std::string& writable_;
  std::vector<RepeatedAttribute> found_;
};

// Walks the start tags in document order to the one sought and reads its attributes' lines.
class AttributeLocator : private AttributeCursor {
 public:
  explicit AttributeLocator(std::string_view text) : AttributeCursor(text) {}

  std::optional<int> find(int tag_line, int ordinal, std::string_view name) {
    while (next_markup() && line_ <= tag_line) {
      if (const auto closed = skip_comment_cdata_or_pi()) {
        if (!*closed) return std::nullopt;
        continue;
      }
      if (starts("<!") || starts("</")) {
        if (!skip_past(">")) return std::nullopt;
        continue;
      }
      const bool sought = line_ == tag_line && ordinal-- == 0;
      (void)tag_name();
      for (;;) {
        skip_blanks();
        if (pos_ >= text_.size()) return std::nullopt;
        if (text_[pos_] == '>' || starts("/>")) {
          if (sought) return std::nullopt;
          break;
        }
        const int line = line_;
        const auto span = attribute();
        if (!span) return std::nullopt;
        if (sought && span->name == name) return line;
      }
    }
    return std::nullopt;
  }
};

}  // namespace

std::optional<int> attribute_line(std::string_view text, int tag_line, int ordinal,
                                  std::string_view name) {
  return AttributeLocator(text).find(tag_line, ordinal, name);
}

std::vector<RepeatedAttribute> blank_repeated_attributes(std::string& text) {
  return AttributeScanner(text).run();
}

int blank_late_declaration(std::string& text) {
  size_t at = 0;
  for (;;) {
    while (at < text.size() && is_blank(text[at])) {
      ++at;
    }
    if (text.compare(at, 4, "<!--") != 0) {
      break;
    }
    const size_t end = text.find("-->", at + 4);
    if (end == std::string::npos) {
      return 0;
    }
    at = end + 3;
  }
  const bool declaration =
      text.compare(at, 5, "<?xml") == 0 && at + 5 < text.size() && is_blank(text[at + 5]);
  if (at == 0 || !declaration) {
    return 0;
  }
  const size_t end = text.find("?>", at);
  if (end == std::string::npos) {
    return 0;
  }
  const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
  for (size_t i = at; i < end + 2; ++i) {
    if (text[i] != '\n') {
      text[i] = ' ';
    }
  }
  return line;
}

}  // namespace corsa::xosc
