#include "xml_writer.h"

#include "corsa/core/strings.h"

namespace corsa::xodr::detail {

void XmlWriter::indent() { out_.append(2 * stack_.size(), ' '); }

XmlWriter& XmlWriter::open(std::string_view name) {
  indent();
  out_ += '<';
  out_ += name;
  pending_ = name;
  return *this;
}

XmlWriter& XmlWriter::attr(std::string_view name, std::string_view value) {
  out_ += ' ';
  out_ += name;
  out_ += "=\"";
  for (const char c : value) {
    switch (c) {
      case '&':
        out_ += "&amp;";
        break;
      case '<':
        out_ += "&lt;";
        break;
      case '>':
        out_ += "&gt;";
        break;
      case '"':
        out_ += "&quot;";
        break;
      case '\n':
        out_ += "&#10;";
        break;
      default:
        out_ += c;
    }
  }
  out_ += '"';
  return *this;
}

XmlWriter& XmlWriter::attr(std::string_view name, double value) {
  // Shortest text that reads back to the same double; -0 is written as 0.
  return attr(name, corsa::format_double(value == 0.0 ? 0.0 : value));
}

XmlWriter& XmlWriter::attr(std::string_view name, int value) {
  return attr(name, std::to_string(value));
}

void XmlWriter::children() {
  out_ += ">\n";
  stack_.push_back(pending_);
}

void XmlWriter::end_empty() { out_ += "/>\n"; }

void XmlWriter::close() {
  const std::string name = stack_.back();
  stack_.pop_back();
  indent();
  out_ += "</" + name + ">\n";
}

void XmlWriter::cdata_element(std::string_view name, std::string_view text) {
  indent();
  out_ += '<';
  out_ += name;
  out_ += "><![CDATA[";
  // "]]>" cannot appear inside CDATA: split it across two sections.
  size_t start = 0;
  while (true) {
    const size_t end = text.find("]]>", start);
    if (end == std::string_view::npos) {
      out_ += text.substr(start);
      break;
    }
    out_ += text.substr(start, end - start + 2);
    out_ += "]]><![CDATA[";
    start = end + 2;
  }
  out_ += "]]></";
  out_ += name;
  out_ += ">\n";
}

}  // namespace corsa::xodr::detail
