#include "xml_dom.h"

#include <algorithm>
#include <array>
#include <cstring>

#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"
#include "corsa/core/xml_errors.h"

namespace corsa::xodr::detail {

const std::string_view* XmlElement::attribute(std::string_view name) const {
  for (uint32_t i = attr_begin_; i < attr_end_; ++i) {
    if (document_->attributes_[i].name == name) {
      return &document_->attributes_[i].value;
    }
  }
  return nullptr;
}

const XmlElement* XmlElement::first_child() const {
  return first_child_ == UINT32_MAX ? nullptr : &document_->elements_[first_child_];
}
const XmlElement* XmlElement::next_sibling() const {
  return next_sibling_ == UINT32_MAX ? nullptr : &document_->elements_[next_sibling_];
}
const XmlElement* XmlElement::parent() const {
  return parent_ == UINT32_MAX ? nullptr : &document_->elements_[parent_];
}

namespace {

// Byte classes for the scanner (a table instead of chains of comparisons: start tags are the
// hot loop of a map load).
// Deepest element nesting accepted. OpenDRIVE files nest about 8 levels (OpenDRIVE/road/lanes/
// laneSection/right/lane/width) and user data a few more; 2 million nested elements once took
// 3.4 s and 237 MB before failing elsewhere.
constexpr size_t kMaxDepth = 256;

constexpr unsigned char kName = 0;
constexpr unsigned char kBlank = 1;
constexpr unsigned char kDelimiter = 2;
constexpr auto kClass = [] {
  std::array<unsigned char, 256> table{};
  for (const char c : {' ', '\t', '\n', '\r'}) {
    table[static_cast<unsigned char>(c)] = kBlank;
  }
  for (const char c : {'=', '>', '/', '<', '"', '\''}) {
    table[static_cast<unsigned char>(c)] = kDelimiter;
  }
  return table;
}();

}  // namespace

class XmlParser {
 public:
  XmlParser(XmlDocument& document, const std::string& file)
      : doc_(document),
        file_(file),
        begin_(document.text_.data()),
        p_(begin_),
        end_(begin_ + document.text_.size()),
        line_pos_(begin_) {}

  void run();

 private:
  [[noreturn]] void fail(const char* at, const std::string& message) {
    throw corsa::InputError(corsa::make_error(file_, line_at(at), "malformed XML: " + message));
  }
  /// 1-based line of `at` (positions are asked for in increasing order, so this is one pass).
  int line_at(const char* at) {
    at = std::min<const char*>(at, end_);
    if (at >= line_pos_) {
      // memchr hops from newline to newline much faster than a byte loop.
      const char* q = line_pos_;
      while (const void* hit = std::memchr(q, '\n', static_cast<size_t>(at - q))) {
        q = static_cast<const char*>(hit) + 1;
        ++line_;
      }
      line_pos_ = at;
      return line_;
    }
    return line_ - static_cast<int>(std::count(at, line_pos_, '\n'));
  }
  static bool blank(char c) { return kClass[static_cast<unsigned char>(c)] == kBlank; }
  static bool name_char(char c) { return kClass[static_cast<unsigned char>(c)] == kName; }
  void skip_blanks() {
    while (p_ < end_ && blank(*p_)) {
      ++p_;
    }
  }
  /// Moves past `terminator`, failing with `what` if the file ends first.
  void skip_past(std::string_view terminator, const char* what) {
    char* found = std::search(p_, end_, terminator.begin(), terminator.end());
    if (found == end_) {
      fail(p_, std::string("unterminated ") + what + " (truncated file?)");
    }
    p_ = found + terminator.size();
  }
  std::string_view read_name() {
    const char* start = p_;
    while (p_ < end_ && name_char(*p_)) {
      ++p_;
    }
    if (p_ == start) {
      fail(p_, "expected a name");
    }
    return std::string_view(start, static_cast<size_t>(p_ - start));
  }
  /// Decodes entities in place; returns the decoded view.
  std::string_view decode(char* start, char* stop);
  void start_tag();
  void check_unique_attributes(const char* tag, const XmlElement& element);
  void end_tag();
  void add_text(std::string_view text);
  void text_run(const char* stop);

  XmlDocument& doc_;
  const std::string& file_;
  char* begin_;
  char* p_;
  char* end_;
  const char* line_pos_;
  int line_ = 1;
  std::vector<uint32_t> stack_;
  bool root_done_ = false;
};

std::string_view XmlParser::decode(char* start, char* stop) {
  char* amp = static_cast<char*>(std::memchr(start, '&', static_cast<size_t>(stop - start)));
  if (amp == nullptr) {
    return std::string_view(start, static_cast<size_t>(stop - start));
  }
  char* out = amp;
  for (char* in = amp; in < stop;) {
    if (*in != '&') {
      *out++ = *in++;
      continue;
    }
    char* semi = static_cast<char*>(std::memchr(in, ';', static_cast<size_t>(stop - in)));
    if (semi == nullptr) {
      fail(in, "'&' without ';'");
    }
    const std::string_view entity(in + 1, static_cast<size_t>(semi - in - 1));
    unsigned long code = 0;
    if (entity == "lt") {
      code = '<';
    } else if (entity == "gt") {
      code = '>';
    } else if (entity == "amp") {
      code = '&';
    } else if (entity == "quot") {
      code = '"';
    } else if (entity == "apos") {
      code = '\'';
    } else if (entity.size() > 1 && entity[0] == '#') {
      const std::optional<uint32_t> referenced = corsa::xml_character_reference(entity.substr(1));
      if (!referenced) {
        fail(in, corsa::bad_character_reference_message(entity.substr(1)));
      }
      code = *referenced;
    } else {
      fail(in, "unknown entity '&" + clip(entity) + ";'");
    }
    // UTF-8 encode; never longer than the reference itself, so in-place is safe.
    if (code < 0x80) {
      *out++ = static_cast<char>(code);
    } else if (code < 0x800) {
      *out++ = static_cast<char>(0xC0 | (code >> 6));
      *out++ = static_cast<char>(0x80 | (code & 0x3F));
    } else if (code < 0x10000) {
      *out++ = static_cast<char>(0xE0 | (code >> 12));
      *out++ = static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      *out++ = static_cast<char>(0x80 | (code & 0x3F));
    } else {
      *out++ = static_cast<char>(0xF0 | (code >> 18));
      *out++ = static_cast<char>(0x80 | ((code >> 12) & 0x3F));
      *out++ = static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      *out++ = static_cast<char>(0x80 | (code & 0x3F));
    }
    in = semi + 1;
  }
  return std::string_view(start, static_cast<size_t>(out - start));
}

void XmlParser::add_text(std::string_view text) {
  XmlElement& e = doc_.elements_[stack_.back()];
  if (e.text_.empty()) {
    e.text_ = text;
    return;
  }
  if (e.last_child_ != UINT32_MAX) {
    return;  // mixed content (text after a child element): OpenDRIVE has none; keep the first
  }
  // Rare (text split by a comment or CDATA): join by moving the new part next to the old one.
  // Both live in the buffer in order and the gap only held a comment or CDATA markers, which
  // nothing refers to, so the move is safe.
  char* dest = const_cast<char*>(e.text_.data()) + e.text_.size();
  std::memmove(dest, text.data(), text.size());
  e.text_ = std::string_view(e.text_.data(), e.text_.size() + text.size());
}

void XmlParser::text_run(const char* stop) {
  const char* q = p_;
  while (q < stop && blank(*q)) {
    ++q;
  }
  if (q == stop) {
    p_ = const_cast<char*>(stop);
    return;
  }
  if (stack_.empty()) {
    fail(q, "text outside the root element");
  }
  add_text(decode(p_, const_cast<char*>(stop)));
  p_ = const_cast<char*>(stop);
}

// XML 1.0 §3.1 (well-formedness constraint "Unique Att Spec"): an attribute name appears at most
// once in a tag; otherwise which value a reader sees would depend on the reader.
void XmlParser::check_unique_attributes(const char* tag, const XmlElement& element) {
  const auto begin = doc_.attributes_.begin() + element.attr_begin_;
  const auto end = doc_.attributes_.begin() + element.attr_end_;
  const auto duplicate = [&](std::string_view name) {
    fail(tag, "attribute '" + clip(name) + "' appears twice in <" + clip(element.name_) + ">");
  };
  if (end - begin <= 32) {
    // The usual case (a handful of attributes): pairwise, no allocation.
    for (auto a = begin; a != end; ++a) {
      for (auto b = a + 1; b != end; ++b) {
        if (a->name == b->name) {
          duplicate(a->name);
        }
      }
    }
    return;
  }
  std::vector<std::string_view> names;
  names.reserve(static_cast<size_t>(end - begin));
  for (auto a = begin; a != end; ++a) {
    names.push_back(a->name);
  }
  std::sort(names.begin(), names.end());
  const auto same = std::adjacent_find(names.begin(), names.end());
  if (same != names.end()) {
    duplicate(*same);
  }
}

void XmlParser::start_tag() {
  const char* tag = p_;
  ++p_;  // '<'
  if (root_done_ && stack_.empty()) {
    fail(tag, "a second root element");
  }
  const uint32_t index = static_cast<uint32_t>(doc_.elements_.size());
  XmlElement element;
  element.document_ = &doc_;
  element.name_ = read_name();
  element.line_ = line_at(tag);
  if (stack_.size() >= kMaxDepth) {
    fail(tag, "<" + clip(element.name_) + "> is nested deeper than " + std::to_string(kMaxDepth) +
                  " levels");
  }
  element.attr_begin_ = static_cast<uint32_t>(doc_.attributes_.size());
  while (true) {
    skip_blanks();
    if (p_ >= end_) {
      fail(tag, "unterminated start tag <" + clip(element.name_) + "> (truncated file?)");
    }
    if (*p_ == '>' || *p_ == '/') {
      break;
    }
    const std::string_view name = read_name();
    skip_blanks();
    if (p_ >= end_ || *p_ != '=') {
      fail(p_, "attribute '" + clip(name) + "' without '='");
    }
    ++p_;
    skip_blanks();
    if (p_ >= end_ || (*p_ != '"' && *p_ != '\'')) {
      fail(p_, "attribute '" + clip(name) + "' value must be quoted");
    }
    const char quote = *p_++;
    char* close = static_cast<char*>(std::memchr(p_, quote, static_cast<size_t>(end_ - p_)));
    if (close == nullptr) {
      fail(p_, "unterminated value of attribute '" + clip(name) + "'");
    }
    doc_.attributes_.push_back({name, decode(p_, close)});
    p_ = close + 1;
  }
  element.attr_end_ = static_cast<uint32_t>(doc_.attributes_.size());
  check_unique_attributes(tag, element);
  if (!stack_.empty()) {
    XmlElement& parent = doc_.elements_[stack_.back()];
    element.parent_ = stack_.back();
    if (parent.last_child_ == UINT32_MAX) {
      parent.first_child_ = index;
    } else {
      doc_.elements_[parent.last_child_].next_sibling_ = index;
    }
    parent.last_child_ = index;
  }
  doc_.elements_.push_back(element);
  if (*p_ == '/') {
    ++p_;
    if (p_ >= end_ || *p_ != '>') {
      fail(p_, "expected '>' after '/'");
    }
    ++p_;
    root_done_ = root_done_ || stack_.empty();
    return;
  }
  ++p_;  // '>'
  stack_.push_back(index);
}

void XmlParser::end_tag() {
  const char* tag = p_;
  p_ += 2;  // "</"
  const std::string_view name = read_name();
  skip_blanks();
  if (p_ >= end_ || *p_ != '>') {
    fail(tag, "unterminated end tag </" + clip(name) + ">");
  }
  ++p_;
  if (stack_.empty()) {
    fail(tag, "end tag </" + clip(name) + "> without a start tag");
  }
  const XmlElement& open = doc_.elements_[stack_.back()];
  if (open.name_ != name) {
    fail(tag, "end tag </" + clip(name) + "> does not match <" + clip(open.name_) +
                  "> opened on line " + std::to_string(open.line_));
  }
  stack_.pop_back();
  root_done_ = root_done_ || stack_.empty();
}

void XmlParser::run() {
  if (end_ - p_ >= 3 && std::memcmp(p_, "\xEF\xBB\xBF", 3) == 0) {
    p_ += 3;  // UTF-8 byte order mark
  }
  while (p_ < end_) {
    char* lt = static_cast<char*>(std::memchr(p_, '<', static_cast<size_t>(end_ - p_)));
    text_run(lt == nullptr ? end_ : lt);
    if (lt == nullptr) {
      break;
    }
    const std::string_view rest(p_, static_cast<size_t>(end_ - p_));
    if (rest.starts_with("<?")) {
      skip_past("?>", "processing instruction");
    } else if (rest.starts_with("<!--")) {
      skip_past("-->", "comment");
    } else if (rest.starts_with("<![CDATA[")) {
      if (stack_.empty()) {
        fail(p_, "CDATA outside the root element");
      }
      char* start = p_ + 9;
      p_ = start;
      skip_past("]]>", "CDATA section");
      add_text(std::string_view(start, static_cast<size_t>(p_ - 3 - start)));
    } else if (rest.starts_with("<!")) {
      // DOCTYPE (with an optional internal subset in brackets).
      const char* bracket = static_cast<const char*>(std::memchr(p_, '[', rest.size()));
      const char* close = static_cast<const char*>(std::memchr(p_, '>', rest.size()));
      if (bracket != nullptr && close != nullptr && bracket < close) {
        skip_past("]", "DOCTYPE");
      }
      skip_past(">", "DOCTYPE");
    } else if (rest.starts_with("</")) {
      end_tag();
    } else {
      start_tag();
    }
  }
  if (!stack_.empty()) {
    const XmlElement& open = doc_.elements_[stack_.back()];
    fail(end_, "the file ends inside <" + clip(open.name_) + "> opened on line " +
                   std::to_string(open.line_) + " (truncated file?)");
  }
  if (doc_.elements_.empty()) {
    fail(end_, "no root element (empty file?)");
  }
}

XmlDocument::XmlDocument(std::string text, const std::string& file) : text_(std::move(text)) {
  elements_.reserve(text_.size() / 64);
  attributes_.reserve(text_.size() / 24);
  XmlParser(*this, file).run();
}

}  // namespace corsa::xodr::detail
