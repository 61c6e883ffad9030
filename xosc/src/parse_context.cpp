#include "parse_context.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>

#include "corsa/core/atomic_file.h"
#include "corsa/core/strings.h"
#include "corsa/core/xml_entities.h"
#include "corsa/core/xml_errors.h"
#include "corsa/xosc/expression.h"
#include "schema_table.h"
#include "xml_nesting.h"

namespace corsa::xosc {

std::string type_name(ParameterType type) { return std::string(to_string(type)); }

std::string element_path(const Element* element) {
  std::vector<std::string_view> names;
  for (const tinyxml2::XMLNode* node = element; node != nullptr && node->ToElement() != nullptr;
       node = node->Parent()) {
    names.emplace_back(node->ToElement()->Name());
  }
  std::string path;
  for (auto it = names.rbegin(); it != names.rend(); ++it) {
    path += (path.empty() ? "" : "/") + std::string(*it);
  }
  return path;
}

namespace {

// parse_xml on text it owns: the text kept in the XmlFile is then the caller's string moved, not
// a copy (a catalog file's text lives as long as the catalog cache).
XmlFile parse_owned_xml(std::string owned, const std::filesystem::path& path) {
  std::string_view text = owned;
  XmlFile file;
  file.name = std::make_shared<const std::string>(path.string());
  file.directory = std::filesystem::absolute(path).parent_path();
  std::string with_entities;  // the text with its DOCTYPE's internal entities expanded
  if (const auto problem = expand_internal_entities(text, with_entities)) {
    throw InputError(make_error(*file.name, problem->line, problem->message));
  }
  if (!with_entities.empty()) {
    text = with_entities;
  }
  file.document = std::make_unique<tinyxml2::XMLDocument>();
  tinyxml2::XMLError error = file.document->Parse(text.data(), text.size());
  std::string repaired;  // the text with the repairs made so far
  if (error == tinyxml2::XML_ERROR_PARSING_DECLARATION) {
    // An XML declaration after leading comments (esmini's two_plus_one_road): read again with
    // it blanked, as if it opened the file. Any other declaration error stays.
    repaired.assign(text);
    file.late_declaration_line = blank_late_declaration(repaired);
    if (file.late_declaration_line > 0) {
      file.document = std::make_unique<tinyxml2::XMLDocument>();
      error = file.document->Parse(repaired.data(), repaired.size());
    }
  }
  if (error == tinyxml2::XML_ERROR_PARSING_ATTRIBUTE) {
    // An attribute written twice (esmini's reader takes the first): read again without the
    // repeats, whose places are kept for the warnings. Any other attribute error stays.
    if (repaired.empty()) {
      repaired.assign(text);
    }
    file.repeated_attributes = blank_repeated_attributes(repaired);
    if (!file.repeated_attributes.empty()) {
      file.document = std::make_unique<tinyxml2::XMLDocument>();
      error = file.document->Parse(repaired.data(), repaired.size());
    }
  }
  if (error != tinyxml2::XML_SUCCESS) {
    if (error == tinyxml2::XML_ERROR_MISMATCHED_ELEMENT ||
        error == tinyxml2::XML_ERROR_PARSING_ELEMENT) {
      // Name the element and both lines: tinyxml2 only says where it gave up.
      if (const auto nesting = find_nesting_error(text)) {
        throw InputError(
            make_error(*file.name, nesting->line, "malformed XML: " + nesting->message));
      }
    }
    // tinyxml2 gives line 0 for an empty (or all-whitespace, NUL-led) document: say line 1.
    throw InputError(make_error(*file.name, std::max(1, file.document->ErrorLineNum()),
                                "malformed XML: " + xml_error_words(error)));
  }
  if (file.document->RootElement() == nullptr) {
    throw InputError(make_error(*file.name, 1, "malformed XML: no root element"));
  }
  if (const auto problem = find_undeclared_entity(text)) {
    throw InputError(make_error(*file.name, problem->line, problem->message));
  }
  std::string& kept = !repaired.empty() ? repaired : !with_entities.empty() ? with_entities : owned;
  file.text = std::make_shared<const std::string>(std::move(kept));
  return file;
}

}  // namespace

XmlFile parse_xml(std::string_view text, const std::filesystem::path& path) {
  return parse_owned_xml(std::string(text), path);
}

XmlFile load_xml(const std::filesystem::path& path) {
  return parse_owned_xml(read_file(path), path);
}

void warn_xml_repairs(ParseContext& ctx, const XmlFile& file) {
  if (file.late_declaration_line > 0) {
    ctx.lenient(Source{file.name, file.late_declaration_line},
                "XML declaration after comments (XML allows it only at the file's start)",
                "the file's own declaration");
  }
  for (const RepeatedAttribute& repeat : file.repeated_attributes) {
    ctx.lenient(Source{file.name, repeat.line},
                "attribute " + clip(repeat.attribute) + " written twice in <" +
                    clip(repeat.element) + ">: '" + clip(repeat.kept) + "', then '" +
                    clip(repeat.dropped) + "'",
                "its first value '" + clip(repeat.kept) + "', as esmini's XML reader takes it");
  }
  for (const XmlFile::MappingNote& note : file.mapping_notes) {
    if (note.read_as) {
      ctx.lenient(note.where, note.message, *note.read_as);
    } else {
      ctx.record(InputError(note.where.error(note.message)));
    }
  }
}

std::string element_text(const Element* element) {
  const char* text = element->GetText();
  return text == nullptr ? std::string() : std::string(text);
}

ParseContext::ParseContext(Diagnostics& diagnostics, const LoadOptions& options)
    : diagnostics_(diagnostics), options_(options) {}

Source ParseContext::source(const Element* element) const {
  return Source{file_.name, element == nullptr ? 0 : element->GetLineNum()};
}

void ParseContext::fail(const Element* element, std::string message) const {
  Diagnostic diagnostic =
      make_error(file_.name ? *file_.name : std::string(),
                 element == nullptr ? 0 : element->GetLineNum(), std::move(message));
  if (element != nullptr) {
    diagnostic.path = element_path(element);
  }
  throw InputError(std::move(diagnostic));
}

namespace {
/// Past this many errors a document is not worth reading on (a binary file, a broken generator).
constexpr size_t kMaxErrors = 500;
}  // namespace

void ParseContext::error(const Element* element, std::string message) {
  error_at_line(element, element == nullptr ? 0 : element->GetLineNum(), std::move(message));
}

void ParseContext::attribute_error(const Element* element, std::string_view name,
                                   std::string message) {
  error_at_line(element, attribute_line(element, name), std::move(message));
}

int ParseContext::attribute_line(const Element* element, std::string_view name) const {
  return defer_attribute_line(element, name).line();
}

int DeferredAttributeLine::line() const {
  return text ? xosc::attribute_line(*text, tag_line, ordinal, name).value_or(tag_line) : tag_line;
}

DeferredAttributeLine ParseContext::defer_attribute_line(const Element* element,
                                                         std::string_view name) const {
  const int line = element->GetLineNum();
  DeferredAttributeLine deferred{nullptr, line, 0, std::string(name)};
  if (!file_.text || element->GetDocument() != file_.document) return deferred;
  // Start tags open in document order, so those before this one on its line are the elements
  // met walking back in document order until a node opens on an earlier line.
  int ordinal = 0;
  const tinyxml2::XMLNode* node = element;
  for (;;) {
    if (const tinyxml2::XMLNode* previous = node->PreviousSibling()) {
      node = previous;
      while (node->LastChild() != nullptr) node = node->LastChild();
    } else {
      node = node->Parent();
    }
    if (node == nullptr || node->ToDocument() != nullptr || node->GetLineNum() < line) break;
    if (node->ToElement() != nullptr) ++ordinal;
  }
  deferred.text = file_.text;
  deferred.ordinal = ordinal;
  return deferred;
}

void ParseContext::error_at_line(const Element* element, int line, std::string message) {
  Diagnostic diagnostic =
      make_error(file_.name ? *file_.name : std::string(), line, std::move(message));
  if (element != nullptr) {
    diagnostic.path = element_path(element);
  }
  record(InputError(std::move(diagnostic)));
}

void ParseContext::record(const InputError& caught) {
  if (dynamic_cast<const RecordedError*>(&caught) != nullptr) return;
  for (const Diagnostic& diagnostic : caught.diagnostics()) {
    const bool seen = std::any_of(errors_.begin(), errors_.end(), [&](const Diagnostic& other) {
      return other.file == diagnostic.file && other.line == diagnostic.line &&
             other.message == diagnostic.message;
    });
    if (seen) continue;
    errors_.push_back(diagnostic);
    if (errors_.size() >= kMaxErrors) {
      errors_.push_back(
          make_error(diagnostic.file, diagnostic.line,
                     "too many errors (" + std::to_string(kMaxErrors) + "); not reading further"));
      throw TooManyErrors(errors_);
    }
  }
}

void ParseContext::throw_errors() const {
  if (errors_.empty()) return;
  if (outside_violations_.size() == errors_.size()) throw ConstraintViolation(errors_);
  throw InputError(errors_);
}

void ParseContext::lenient(const Element* element, std::string_view message,
                           std::string_view read_as) {
  lenient(source(element), message, read_as);
}

void ParseContext::lenient(const Source& where, std::string_view message,
                           std::string_view read_as) {
  if (options_.strict) {
    record(InputError(where.error(std::string(message) +
                                  " (an error under --strict; otherwise read as " +
                                  std::string(read_as) + ")")));
    return;
  }
  std::string text = std::string(message) + " (read as " + std::string(read_as) + ")";
  diagnostics_.add_once(
      "lenient:" + where.file_name() + ":" + std::to_string(where.line) + ":" + text,
      where.warning(text));
}

void ParseContext::warn_once(const Element* element, const std::string& key, std::string message) {
  diagnostics_.add_once(
      key, make_warning(file_.name ? *file_.name : std::string(),
                        element == nullptr ? 0 : element->GetLineNum(), std::move(message)));
}

void ParseContext::deprecated(const Element* element, std::string_view what,
                              std::string_view instead) {
  std::string message = std::string(what) + " is deprecated (an OpenSCENARIO 1.0/1.1 form)";
  if (!instead.empty()) {
    message += "; use " + std::string(instead);
  }
  warn_once(element, "deprecated:" + std::string(what), std::move(message));
}

ParseContext::FileState ParseContext::swap_file(FileState file) {
  std::swap(file, file_);
  return file;
}

// --- attributes ---------------------------------------------------------------------------------

std::optional<std::string> ParseContext::attr(const Element* element, const char* name) {
  failed_ = false;
  return resolved(element, name);
}

std::optional<std::string> ParseContext::resolved(const Element* element, const char* name) {
  const char* raw = element->Attribute(name);
  if (raw == nullptr) {
    // XML names are case-sensitive; esmini's two_plus_one_road writes freeSpace for freespace.
    const tinyxml2::XMLAttribute* other = element->FirstAttribute();
    while (other != nullptr && !iequals(other->Name(), name)) {
      other = other->Next();
    }
    if (other == nullptr) {
      return std::nullopt;
    }
    lenient(
        Source{file_.name, attribute_line(element, other->Name())},
        "attribute '" + clip(other->Name()) + "' of <" + element->Name() + "> misspells " + name,
        name);
    raw = other->Value();
  }
  try {
    return resolve(element, raw);
  } catch (const InputError& caught) {
    if (std::string_view(name) == "name" && raw[0] == '$' && raw[1] == '{') {
      // A name such as "${Ego} overtakes" is meant as text: names are not computed (§9.2).
      lenient(Source{file_.name, attribute_line(element, name)},
              "name '" + clip(raw) + "' is not an expression", "the literal name");
      return std::string(raw);
    }
    // Errors in the value (an unknown parameter, a bad expression) at the attribute's line.
    std::vector<Diagnostic> at_attribute = caught.diagnostics();
    const int line = attribute_line(element, name);
    for (Diagnostic& diagnostic : at_attribute) {
      if (diagnostic.line == element->GetLineNum() && file_.name &&
          diagnostic.file == *file_.name) {
        diagnostic.line = line;
      }
    }
    record(InputError(std::move(at_attribute)));
    failed_ = true;
    return std::string();
  }
}

void ParseContext::missing(const Element* element, const char* name) const {
  fail(element, std::string("<") + element->Name() + "> needs the attribute " + name);
}

std::string ParseContext::parameter_name(const Element* element, const char* name) const {
  const char* raw = element->Attribute(name);
  if (raw == nullptr) missing(element, name);
  std::string text = raw;
  if (!text.empty() && text[0] == '$') {
    text.erase(0, 1);
  }
  return text;
}

std::optional<Value> ParseContext::typed_value(const Element* element, ParameterType type,
                                               std::string_view text, std::string_view what) {
  if (auto value = parse_value(type, text)) return value;
  // An integer written with a zero fraction ("-5.0"), as some tools write every number: its
  // meaning is clear.
  const bool integer = type == ParameterType::kInt || type == ParameterType::kUnsignedInt ||
                       type == ParameterType::kUnsignedShort;
  const auto number = integer ? parse_double(text) : std::nullopt;
  if (number && std::isfinite(*number) && std::trunc(*number) == *number &&
      std::fabs(*number) < 1e15) {
    const std::string whole = std::to_string(static_cast<int64_t>(*number));
    if (auto value = parse_value(type, whole)) {
      lenient(element,
              std::string(what) + ": '" + clip(text) + "' is not an " + type_name(type) +
                  " (it has a decimal point)",
              whole);
      return value;
    }
  }
  return std::nullopt;
}

std::string ParseContext::req_str(const Element* element, const char* name) {
  auto value = attr(element, name);
  if (!value) missing(element, name);
  return std::move(*value);
}

std::optional<std::string> ParseContext::opt_str(const Element* element, const char* name) {
  return attr(element, name);
}

namespace {

/// Largest magnitude that makes physical sense for a numeric attribute, with its unit; nullptr
/// for attributes without one. OpenSCENARIO sets no bounds; these are far beyond any road
/// vehicle or map (docs/engine.md, "Bounds on values") and keep values such as 1e308 from
/// reaching the engine, where they overflow to inf and NaN.
struct Magnitude {
  double limit;
  const char* unit;
};
const Magnitude* magnitude_limit(std::string_view element, std::string_view attribute) {
  static constexpr Magnitude kSpeed{1e4, "m/s"};
  static constexpr Magnitude kLength{1e8, "m"};
  static constexpr Magnitude kTime{1e9, "s"};
  // Lane numbers (ids and steps across lanes): a lane section holds at most 128 lanes.
  static constexpr Magnitude kLanes{1e3, "lanes"};
  if (attribute == "maxSpeed" || attribute == "speed" || attribute == "velocity" ||
      (attribute == "value" &&
       (element == "AbsoluteTargetSpeed" || element == "RelativeTargetSpeed" ||
        element == "SpeedCondition" || element == "RelativeSpeedCondition"))) {
    return &kSpeed;
  }
  if (attribute == "x" || attribute == "y" || attribute == "z" || attribute == "s" ||
      attribute == "t" || attribute == "ds" || attribute == "dx" || attribute == "dy" ||
      attribute == "dz" || attribute == "distance" || attribute == "offset" ||
      attribute == "pathS" || attribute == "tolerance" ||
      (attribute == "value" &&
       (element == "DistanceCondition" || element == "RelativeDistanceCondition" ||
        element == "TraveledDistanceCondition"))) {
    return &kLength;
  }
  if (attribute == "time" || attribute == "duration" || attribute == "delay" ||
      attribute == "timeGap" || attribute == "startTime" || attribute == "stopTime" ||
      (attribute == "value" &&
       (element == "SimulationTimeCondition" || element == "StandStillCondition" ||
        element == "TimeHeadwayCondition" || element == "TimeToCollisionCondition"))) {
    return &kTime;
  }
  if (attribute == "dLane" || (attribute == "value" && element == "RelativeTargetLane") ||
      (attribute == "id" && element == "Lane") ||
      ((attribute == "from" || attribute == "to") && element == "RelativeLaneRange")) {
    return &kLanes;
  }
  return nullptr;
}

}  // namespace

std::optional<double> ParseContext::opt_double(const Element* element, const char* name) {
  const auto text = attr(element, name);
  if (!text) return std::nullopt;
  if (failed_) return 0.0;
  const auto value = parse_double(*text);
  if (!value) {
    attribute_error(element, name,
                    "attribute " + std::string(name) + ": '" + clip(*text) + "' is not a number");
    return 0.0;
  }
  if (const Magnitude* magnitude = magnitude_limit(element->Name(), name);
      magnitude != nullptr && std::fabs(*value) > magnitude->limit) {
    attribute_error(element, name,
                    "attribute " + std::string(name) + ": " + clip(*text) +
                        " is beyond physical sense (|value| <= " + format_double(magnitude->limit) +
                        " " + magnitude->unit + ")");
    return 0.0;
  }
  return value;
}

double ParseContext::req_double(const Element* element, const char* name) {
  const auto value = opt_double(element, name);
  if (!value) missing(element, name);
  return *value;
}

std::optional<int64_t> ParseContext::opt_int(const Element* element, const char* name,
                                             ParameterType type) {
  const auto text = attr(element, name);
  if (!text) return std::nullopt;
  if (failed_) return 0;
  const auto value = typed_value(element, type, *text, std::string("attribute ") + name);
  if (!value) {
    attribute_error(element, name,
                    "attribute " + std::string(name) + ": '" + clip(*text) + "' is not a valid " +
                        type_name(type));
    return 0;
  }
  const int64_t number = std::get<int64_t>(value->data);
  if (const Magnitude* magnitude = magnitude_limit(element->Name(), name);
      magnitude != nullptr && !(std::fabs(static_cast<double>(number)) <= magnitude->limit)) {
    error(element, "attribute " + std::string(name) + ": " + clip(*text) +
                       " is beyond physical sense (|value| <= " + format_double(magnitude->limit) +
                       " " + magnitude->unit + ")");
    return 0;
  }
  return number;
}

int64_t ParseContext::req_int(const Element* element, const char* name, ParameterType type) {
  const auto value = opt_int(element, name, type);
  if (!value) missing(element, name);
  return *value;
}

std::optional<bool> ParseContext::opt_bool(const Element* element, const char* name) {
  const auto text = attr(element, name);
  if (!text) return std::nullopt;
  if (failed_) return false;
  const auto value = parse_value(ParameterType::kBoolean, *text);
  if (!value) {
    // xsd:boolean is lower case; `False` / `TRUE` (some writers capitalise) can mean one thing.
    std::string lower = *text;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (lower == "true" || lower == "false") {
      // esmini's reader compares the text with `true` and `1`: anything else is false.
      const bool value = lower == "true" && !options_.esmini_booleans;
      lenient(Source{file_.name, attribute_line(element, name)},
              "attribute " + std::string(name) + ": '" + *text + "' is not lower case",
              value ? "true" : (options_.esmini_booleans ? "false, as esmini reads it" : "false"));
      return value;
    }
    attribute_error(element, name,
                    "attribute " + std::string(name) + ": '" + clip(*text) +
                        "' is not a boolean (true or false)");
    return false;
  }
  return std::get<bool>(value->data);
}

bool ParseContext::req_bool(const Element* element, const char* name) {
  const auto value = opt_bool(element, name);
  if (!value) missing(element, name);
  return *value;
}

void ParseContext::use_entity(const Element* element, const std::string& name, std::string what) {
  if (record_entities) {
    entity_uses_.push_back({name, source(element), std::move(what)});
  }
}

void ParseContext::check_parameter_ref(const Element* element, const std::string& name) {
  if (record_entities && !global_parameters.contains(name) && !parameter_visible(name)) {
    error(element, "undefined parameter '" + name + "'");
  }
}

void ParseContext::check_signal_controller(const Element* element, const std::string& controller,
                                           const std::string& phase) {
  if (!record_entities) return;
  const auto found = signal_controllers.find(controller);
  if (found == signal_controllers.end()) {
    warn_once(element, "signal-controller:" + controller,
              "traffic signal controller '" + controller +
                  "' is not declared in RoadNetwork/TrafficSignals");
    return;
  }
  if (std::find(found->second.begin(), found->second.end(), phase) == found->second.end()) {
    warn_once(element, "signal-phase:" + controller + "/" + phase,
              "traffic signal controller '" + controller + "' has no phase '" + phase + "'");
  }
}

void ParseContext::check_variable_ref(const Element* element, const std::string& name) {
  if (record_entities && !variables.contains(name)) {
    error(element, "undefined variable '" + name + "'");
  }
}

void ParseContext::check_monitor_ref(const Element* element, const std::string& name) {
  if (record_entities && !monitors.contains(name)) {
    error(element, "undefined monitor '" + name + "'");
  }
}

}  // namespace corsa::xosc
