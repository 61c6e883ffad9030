#include "xml_reader.h"

#include <utility>
#include <vector>

#include "corsa/core/strings.h"

namespace corsa::xodr::detail {

std::string element_path(const XMLElement* e) {
  std::vector<std::string> names;
  for (const XMLElement* node = e; node != nullptr; node = node->parent()) {
    names.push_back(corsa::clip(node->name()));
  }
  std::string path;
  for (auto it = names.rbegin(); it != names.rend(); ++it) {
    if (!path.empty()) {
      path += '/';
    }
    path += *it;
  }
  return path;
}

namespace {

// Longest message passed on, a net under the quoting sites that clip what they quote (ids and
// values copied from the file can be megabytes long in a broken file).
constexpr size_t kMaxMessage = 1024;

std::string tag(const XMLElement* e) { return "<" + corsa::clip(e->name()) + ">"; }

}  // namespace

void XmlReader::fail(const XMLElement* e, const std::string& message) const {
  throw corsa::InputError(corsa::make_error(file_, e ? e->line() : 0,
                                            corsa::clip(message, kMaxMessage),
                                            e ? element_path(e) : std::string()));
}

void XmlReader::warn_once(const std::string& key, const XMLElement* e,
                          const std::string& message) const {
  diagnostics_.add_once(
      key, corsa::make_warning(file_, e ? e->line() : 0, corsa::clip(message, kMaxMessage),
                               e ? element_path(e) : std::string()));
}

void XmlReader::unknown_child(const XMLElement* parent, const XMLElement* child) const {
  const std::string key =
      "unknown:" + corsa::clip(parent->name()) + "/" + corsa::clip(child->name());
  warn_once(key, child,
            "unknown element " + tag(child) + " in " + tag(parent) +
                " ignored (further ones not reported)");
}

void XmlReader::lenient(const XMLElement* e, const std::string& message,
                        const std::string& read_as) const {
  LenientReading reading{e ? e->line() : 0, e ? element_path(e) : std::string(),
                         corsa::clip(message, kMaxMessage), corsa::clip(read_as, kMaxMessage)};
  diagnostics_.add(corsa::make_warning(
      file_, reading.line, reading.message + " (read as " + reading.read_as + ")", reading.path));
  lenient_readings_.push_back(std::move(reading));
}

std::vector<LenientReading> XmlReader::take_lenient_readings() const {
  return std::exchange(lenient_readings_, {});
}

double XmlReader::number(const XMLElement* e, const char* name) const {
  const std::string_view* value = e->attribute(name);
  if (value == nullptr) {
    fail(e, tag(e) + " needs attribute '" + name + "'");
  }
  const auto parsed = corsa::parse_double(*value);
  if (!parsed) {
    fail(e, std::string("attribute '") + name + "' of " + tag(e) +
                " must be a finite number, not '" + corsa::clip(*value) + "'");
  }
  return *parsed;
}

std::optional<double> XmlReader::optional_number(const XMLElement* e, const char* name) const {
  if (e->attribute(name) == nullptr) {
    return std::nullopt;
  }
  return number(e, name);
}

double XmlReader::number_or(const XMLElement* e, const char* name, double fallback) const {
  return e->attribute(name) == nullptr ? fallback : number(e, name);
}

double XmlReader::non_negative(const XMLElement* e, const char* name) const {
  const double value = number(e, name);
  if (value < 0.0) {
    fail(e, std::string("attribute '") + name + "' of " + tag(e) + " must not be negative, got " +
                corsa::clip(*e->attribute(name)));
  }
  return value;
}

double XmlReader::non_negative_or(const XMLElement* e, const char* name, double fallback) const {
  return e->attribute(name) == nullptr ? fallback : non_negative(e, name);
}

int XmlReader::integer(const XMLElement* e, const char* name) const {
  const std::string_view* value = e->attribute(name);
  if (value == nullptr) {
    fail(e, tag(e) + " needs attribute '" + name + "'");
  }
  const auto parsed = corsa::parse_int(*value);
  if (!parsed || *parsed < -1000000 || *parsed > 1000000) {
    fail(e, std::string("attribute '") + name + "' of " + tag(e) + " must be an integer, not '" +
                corsa::clip(*value) + "'");
  }
  return static_cast<int>(*parsed);
}

std::string XmlReader::text(const XMLElement* e, const char* name) const {
  const std::string_view* value = e->attribute(name);
  if (value == nullptr) {
    fail(e, tag(e) + " needs attribute '" + name + "'");
  }
  return std::string(*value);
}

std::string XmlReader::text_or(const XMLElement* e, const char* name, const char* fallback) const {
  const std::string_view* value = e->attribute(name);
  return value == nullptr ? std::string(fallback) : std::string(*value);
}

}  // namespace corsa::xodr::detail
