// Attributes written twice in one start tag (xml_attributes.h).

#include "xml_attributes.h"

#include <optional>
#include <string_view>

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

class AttributeScanner {
 public:
  explicit AttributeScanner(std::string& text) : text_(text) {}

  std::vector<RepeatedAttribute> run() {
    while (pos_ < text_.size()) {
      const size_t lt = text_.find('<', pos_);
      if (lt == std::string::npos) break;
      advance_to(lt);
      bool scanned = true;
      if (starts("<!--")) {
        scanned = skip_past("-->");
      } else if (starts("<![CDATA[")) {
        scanned = skip_past("]]>");
      } else if (starts("<?")) {
        scanned = skip_past("?>");
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
  bool starts(std::string_view prefix) const {
    return std::string_view(text_).substr(pos_, prefix.size()) == prefix;
  }

  void advance_to(size_t to) {
    for (; pos_ < to && pos_ < text_.size(); ++pos_) {
      if (text_[pos_] == '\n') ++line_;
    }
  }

  bool skip_past(std::string_view end) {
    const size_t found = text_.find(end, pos_);
    if (found == std::string::npos) return false;
    advance_to(found + end.size());
    return true;
  }

  void skip_blanks() {
    while (pos_ < text_.size() && is_blank(text_[pos_])) advance_to(pos_ + 1);
  }

  // name = "value" or name = 'value', from pos_; nothing when the text is not one.
  std::optional<AttributeSpan> attribute() {
    AttributeSpan span{};
    span.begin = pos_;
    size_t end = pos_;
    while (end < text_.size() && !ends_attribute_name(text_[end])) ++end;
    if (end == pos_) return std::nullopt;
    span.name = std::string_view(text_).substr(pos_, end - pos_);
    advance_to(end);
    skip_blanks();
    if (pos_ >= text_.size() || text_[pos_] != '=') return std::nullopt;
    advance_to(pos_ + 1);
    skip_blanks();
    if (pos_ >= text_.size() || (text_[pos_] != '"' && text_[pos_] != '\'')) return std::nullopt;
    const size_t close = text_.find(text_[pos_], pos_ + 1);
    if (close == std::string::npos) return std::nullopt;
    span.value = std::string_view(text_).substr(pos_ + 1, close - pos_ - 1);
    advance_to(close + 1);
    span.end = pos_;
    return span;
  }

  // Blanks out text_[begin, end) except its line breaks.
  void blank(size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      if (text_[i] != '\n' && text_[i] != '\r') text_[i] = ' ';
    }
  }

  bool start_tag() {
    advance_to(pos_ + 1);
    size_t end = pos_;
    while (end < text_.size() && !ends_attribute_name(text_[end])) ++end;
    const std::string element = text_.substr(pos_, end - pos_);
    advance_to(end);
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

  std::string& text_;
  size_t pos_ = 0;
  int line_ = 1;
  std::vector<RepeatedAttribute> found_;
};

}  // namespace

std::vector<RepeatedAttribute> blank_repeated_attributes(std::string& text) {
  return AttributeScanner(text).run();
}

}  // namespace corsa::xosc
