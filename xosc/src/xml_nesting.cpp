// A second look at XML that tinyxml2 refused: which element is not closed properly, and where it
// was opened. tinyxml2 reports only the line where it gave up ("mismatched element"); a user
// needs the tag and both lines to find the mistake.

#include "xml_nesting.h"

#include <vector>

#include "corsa/core/strings.h"
#include "xml_cursor.h"

namespace corsa::xosc {
namespace {

struct Open {
  std::string_view name;
  int line;
};

bool name_char(char c) {
  return !(c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '>' || c == '/' || c == '\0');
}

class Scanner : private XmlCursor {
 public:
  explicit Scanner(std::string_view text) : XmlCursor(text) {}

  std::optional<NestingError> run() {
    while (next_markup()) {
      if (const auto closed = skip_comment_cdata_or_pi()) {
        if (!*closed) return std::nullopt;
      } else if (starts("<!")) {
        if (!skip_declaration()) return std::nullopt;
      } else if (starts("</")) {
        if (auto error = closing()) return error;
      } else if (!opening()) {
        return std::nullopt;
      }
    }
    if (!stack_.empty()) {
      const Open& open = stack_.back();
      return NestingError{
          open.line, "<" + clip(open.name) + "> opened at line " + std::to_string(open.line) +
                         " is never closed (the file ends at line " + std::to_string(line_) + ")"};
    }
    return std::nullopt;
  }

 private:
  // <!DOCTYPE ...> with an optional [internal subset].
  bool skip_declaration() {
    int depth = 0;
    for (size_t i = pos_; i < text_.size(); ++i) {
      if (text_[i] == '[') ++depth;
      if (text_[i] == ']') --depth;
      if (text_[i] == '>' && depth <= 0) {
        advance_to(i + 1);
        return true;
      }
    }
    return false;
  }

  std::string_view read_name(size_t from) const {
    size_t end = from;
    while (end < text_.size() && name_char(text_[end])) ++end;
    return text_.substr(from, end - from);
  }

  // Finds the end of a start tag, skipping quoted attribute values (which may hold '>').
  bool opening() {
    const int line = line_;
    const std::string_view name = read_name(pos_ + 1);
    char quote = 0;
    for (size_t i = pos_ + 1; i < text_.size(); ++i) {
      const char c = text_[i];
      if (quote != 0) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '>') {
        const bool empty = text_[i - 1] == '/';
        advance_to(i + 1);
        if (!empty && !name.empty()) stack_.push_back({name, line});
        return true;
      }
    }
    return false;
  }

  std::optional<NestingError> closing() {
    const int line = line_;
    const std::string_view name = read_name(pos_ + 2);
    if (!skip_past(">")) {
      // An end tag cut off by the end of the file: nothing more to scan (the parser's own error
      // says where), as for an unterminated comment.
      pos_ = text_.size();
      stack_.clear();
      return std::nullopt;
    }
    if (stack_.empty()) {
      return NestingError{line, "</" + clip(name) + "> at line " + std::to_string(line) +
                                    " closes no open element"};
    }
    const Open open = stack_.back();
    stack_.pop_back();
    if (open.name != name) {
      return NestingError{line, "<" + clip(open.name) + "> opened at line " +
                                    std::to_string(open.line) + " is closed by </" + clip(name) +
                                    "> at line " + std::to_string(line)};
    }
    return std::nullopt;
  }

  std::vector<Open> stack_;
};

}  // namespace

std::optional<NestingError> find_nesting_error(std::string_view text) {
  return Scanner(text).run();
}

}  // namespace corsa::xosc
