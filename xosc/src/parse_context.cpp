#include "parse_context.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include "corsa/core/atomic_file.h"
#include "corsa/core/strings.h"
#include "corsa/core/xml_errors.h"
#include "corsa/xosc/expression.h"
#include "message_echo.h"
#include "schema_table.h"

namespace corsa::xosc {
namespace {

bool is_identifier(std::string_view text) {
  if (text.empty()) return false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const bool alpha = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
    if (!alpha && !(i > 0 && c >= '0' && c <= '9')) return false;
  }
  return true;
}

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

std::string type_name(ParameterType type) { return std::string(to_string(type)); }

}  // namespace

XmlFile parse_xml(std::string_view text, const std::filesystem::path& path) {
  XmlFile file;
  file.name = std::make_shared<const std::string>(path.string());
  file.directory = std::filesystem::absolute(path).parent_path();
  file.document = std::make_unique<tinyxml2::XMLDocument>();
  const tinyxml2::XMLError error = file.document->Parse(text.data(), text.size());
  if (error != tinyxml2::XML_SUCCESS) {
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
  return file;
}

XmlFile load_xml(const std::filesystem::path& path) { return parse_xml(read_file(path), path); }

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
  const char* raw = element->Attribute(name);
  if (raw == nullptr) {
    return std::nullopt;
  }
  return resolve(element, raw);
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
  return nullptr;
}

}  // namespace

std::optional<double> ParseContext::opt_double(const Element* element, const char* name) {
  const auto text = attr(element, name);
  if (!text) return std::nullopt;
  const auto value = parse_double(*text);
  if (!value) {
    fail(element, "attribute " + std::string(name) + ": '" + clip(*text) + "' is not a number");
  }
  if (const Magnitude* magnitude = magnitude_limit(element->Name(), name);
      magnitude != nullptr && std::fabs(*value) > magnitude->limit) {
    fail(element, "attribute " + std::string(name) + ": " + clip(*text) +
                      " is beyond physical sense (|value| <= " + format_double(magnitude->limit) +
                      " " + magnitude->unit + ")");
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
  const auto value = parse_value(type, *text);
  if (!value) {
    fail(element, "attribute " + std::string(name) + ": '" + clip(*text) + "' is not a valid " +
                      type_name(type));
  }
  return std::get<int64_t>(value->data);
}

int64_t ParseContext::req_int(const Element* element, const char* name, ParameterType type) {
  const auto value = opt_int(element, name, type);
  if (!value) missing(element, name);
  return *value;
}

std::optional<bool> ParseContext::opt_bool(const Element* element, const char* name) {
  const auto text = attr(element, name);
  if (!text) return std::nullopt;
  const auto value = parse_value(ParameterType::kBoolean, *text);
  if (!value) {
    fail(element,
         "attribute " + std::string(name) + ": '" + *text + "' is not a boolean (true or false)");
  }
  return std::get<bool>(value->data);
}

bool ParseContext::req_bool(const Element* element, const char* name) {
  const auto value = opt_bool(element, name);
  if (!value) missing(element, name);
  return *value;
}

std::string ParseContext::resolve(const Element* element, const std::string& text) {
  return resolve_in(element, text, scopes_.size());
}

// `upto` is one past the innermost scope visible to the text.
std::string ParseContext::resolve_in(const Element* element, const std::string& text, size_t upto) {
  if (text.size() < 2 || text[0] != '$') {
    return text;
  }
  if (text[1] == '{') {
    if (text.back() != '}') {
      fail(element, "bad expression '" + echo(text) + "': missing closing '}'");
    }
    const std::string_view body = std::string_view(text).substr(2, text.size() - 3);
    const ParameterLookup find = [&](std::string_view name) -> std::optional<ExprValue> {
      const Value* value = lookup(name, upto, element);
      if (value == nullptr) return std::nullopt;
      if (const auto* b = std::get_if<bool>(&value->data)) return ExprValue::of_bool(*b);
      const auto number = value->number();
      if (!number) {
        throw ExpressionError("parameter '$" + std::string(name) + "' of type " +
                                  type_name(value->type) + " cannot be used in an expression",
                              1);
      }
      return ExprValue::of(*number);
    };
    try {
      const ExprValue result = evaluate_expression(body, find);
      if (result.is_bool) return result.boolean ? "true" : "false";
      return format_double(result.number == 0.0 ? 0.0 : result.number);
    } catch (const ExpressionError& error) {
      fail(element, "bad expression '" + echo(text) + "': " + error.what() + " (column " +
                        std::to_string(error.column() + 2) + ")");
    }
  }
  const std::string_view name = std::string_view(text).substr(1);
  if (!is_identifier(name)) {
    return text;  // a string that merely starts with '$'
  }
  const Value* value = lookup(name, upto, element);
  if (value == nullptr) {
    fail(element, "undefined parameter '" + echo(text) + "'");
  }
  return value->text();
}

// --- parameters ---------------------------------------------------------------------------------

const Value* ParseContext::lookup(std::string_view name, size_t upto, const Element* from) {
  (void)from;
  if (upto == 0) return nullptr;
  const size_t barrier = scopes_[upto - 1].barrier;
  for (size_t k = upto; k-- > barrier;) {
    auto& entries = scopes_[k].entries;
    for (size_t i = 0; i < entries.size(); ++i) {
      if (entries[i].declaration.name == name) {
        // A declaration that uses its own name means the outer parameter of that name
        // (e.g. a story's V = ${$V + 10}); skip to the outer scopes.
        if (entries[i].state == Entry::State::kResolving && !resolving_.empty() &&
            resolving_.back() == name) {
          break;
        }
        resolve_entry(k, i);
        return &scopes_[k].entries[i].declaration.value;
      }
    }
  }
  return nullptr;
}

void ParseContext::resolve_entry(size_t scope, size_t index) {
  Entry* entry = &scopes_[scope].entries[index];
  if (entry->state == Entry::State::kDone) return;
  if (entry->state == Entry::State::kResolving) {
    std::string chain;
    bool in_cycle = false;
    for (const auto& name : resolving_) {
      in_cycle = in_cycle || name == entry->declaration.name;
      if (in_cycle) chain += name + " -> ";
    }
    fail(entry->element, "cyclic parameter use: " + chain + entry->declaration.name);
  }
  entry->state = Entry::State::kResolving;
  resolving_.push_back(entry->declaration.name);
  const Element* element = entry->element;
  const std::string text = entry->literal
                               ? entry->declaration.declared_text
                               : resolve_in(element, entry->declaration.declared_text, scope + 1);
  entry = &scopes_[scope].entries[index];  // resolving may not grow scopes, but stay safe
  const auto value = parse_value(entry->declaration.type, text);
  if (!value) {
    const Source& where = entry->value_source;
    throw InputError(make_error(where.file_name(), where.line,
                                "parameter '" + echo(entry->declaration.name) + "': '" +
                                    echo(text) + "' is not a valid " +
                                    type_name(entry->declaration.type)));
  }
  entry->declaration.value = *value;
  entry->state = Entry::State::kDone;
  resolving_.pop_back();
  check_constraints(*entry);
}

void ParseContext::check_constraints(Entry& entry) {
  auto& groups = entry.declaration.constraint_groups;
  if (groups.empty()) return;
  size_t flat = 0;
  bool any_group = false;
  for (auto& group : groups) {
    bool all = true;
    for (auto& constraint : group.constraints) {
      const Element* element = entry.constraint_elements[flat++];
      constraint.value = resolve(element, constraint.value);
      const auto bound = parse_value(entry.declaration.type, constraint.value);
      if (!bound) {
        fail(element, "constraint value '" + echo(constraint.value) + "' is not a valid " +
                          type_name(entry.declaration.type));
      }
      all = all && compare_values(entry.declaration.value, constraint.rule, *bound);
    }
    any_group = any_group || all;
  }
  if (!any_group) {
    const Source& where = entry.value_source;
    throw InputError(make_error(where.file_name(), where.line,
                                "parameter '" + echo(entry.declaration.name) + "' = '" +
                                    echo(entry.declaration.value.text()) +
                                    "' violates its value constraints"));
  }
}

std::vector<ParameterDeclaration> ParseContext::push_scope(
    const Element* declarations, const std::vector<ParameterAssignment>& overrides, bool isolated,
    std::string_view owner) {
  Scope scope;
  scope.barrier = isolated ? scopes_.size() : (scopes_.empty() ? 0 : scopes_.back().barrier);
  if (declarations != nullptr) {
    Children kids(*this, declarations, "ParameterDeclarations");
    for (const Element* element : kids.all("ParameterDeclaration")) {
      Children decl_kids(*this, element, "ParameterDeclaration");
      Entry entry;
      entry.element = element;
      const char* name = element->Attribute("name");
      if (name == nullptr) missing(element, "name");
      entry.declaration.name = name;
      for (const auto& other : scope.entries) {
        if (other.declaration.name == entry.declaration.name) {
          fail(element, "parameter '" + entry.declaration.name +
                            "' is declared twice (first at line " +
                            std::to_string(other.element->GetLineNum()) + ")");
        }
      }
      entry.declaration.type = req_enum<ParameterType>(element, "parameterType");
      const char* value = element->Attribute("value");
      if (value == nullptr) missing(element, "value");
      entry.declaration.declared_text = value;
      entry.declaration.source = source(element);
      entry.value_source = entry.declaration.source;
      for (const Element* group_element : decl_kids.all("ConstraintGroup")) {
        Children group_kids(*this, group_element, "ValueConstraintGroup");
        ValueConstraintGroup group;
        group.source = source(group_element);
        for (const Element* c : group_kids.at_least("ValueConstraint", 1)) {
          Children(*this, c, "ValueConstraint");
          const char* raw = c->Attribute("value");
          if (raw == nullptr) missing(c, "value");
          group.constraints.push_back({req_enum<Rule>(c, "rule"), raw, source(c)});
          entry.constraint_elements.push_back(c);
        }
        entry.declaration.constraint_groups.push_back(std::move(group));
      }
      scope.entries.push_back(std::move(entry));
    }
  }
  for (const auto& assignment : overrides) {
    bool found = false;
    for (auto& entry : scope.entries) {
      if (entry.declaration.name == assignment.parameter_ref) {
        entry.declaration.declared_text = assignment.value;
        entry.declaration.overridden = true;
        entry.literal = true;
        entry.value_source = assignment.source;
        found = true;
      }
    }
    if (!found) {
      throw InputError(make_error(
          assignment.source.file_name(), assignment.source.line,
          std::string(owner) + " declares no parameter '" + assignment.parameter_ref + "'"));
    }
  }
  scopes_.push_back(std::move(scope));
  const size_t index = scopes_.size() - 1;
  std::vector<ParameterDeclaration> resolved;
  for (size_t i = 0; i < scopes_[index].entries.size(); ++i) {
    resolve_entry(index, i);
    resolved.push_back(scopes_[index].entries[i].declaration);
  }
  return resolved;
}

void ParseContext::pop_scope() { scopes_.pop_back(); }

bool ParseContext::parameter_visible(const std::string& name) {
  return lookup(name, scopes_.size(), nullptr) != nullptr;
}

void ParseContext::use_entity(const Element* element, const std::string& name, std::string what) {
  if (record_entities) {
    entity_uses_.push_back({name, source(element), std::move(what)});
  }
}

void ParseContext::check_parameter_ref(const Element* element, const std::string& name) {
  if (record_entities && !global_parameters.contains(name) && !parameter_visible(name)) {
    fail(element, "undefined parameter '" + name + "'");
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
    fail(element, "undefined variable '" + name + "'");
  }
}

void ParseContext::check_monitor_ref(const Element* element, const std::string& name) {
  if (record_entities && !monitors.contains(name)) {
    fail(element, "undefined monitor '" + name + "'");
  }
}

// --- children -----------------------------------------------------------------------------------

Children::Children(ParseContext& context, const Element* element, std::string_view type)
    : context_(context), element_(element), type_(type) {
  const TypeRule* rule = find_type_rule(type);
  if (rule == nullptr) {
    context.fail(element, "internal: no schema rule for type " + std::string(type));
  }
  for (const Element* child = element->FirstChildElement(); child != nullptr;
       child = child->NextSiblingElement()) {
    if (!rule->allows_child(child->Name())) {
      std::string message =
          "unknown element <" + std::string(child->Name()) + "> in <" + element->Name() + ">";
      if (!rule->children.empty()) {
        message += " (expected ";
        for (size_t i = 0; i < rule->children.size(); ++i) {
          message += (i == 0                           ? ""
                      : i + 1 == rule->children.size() ? " or "
                                                       : ", ") +
                     std::string(rule->children[i]);
        }
        message += ")";
      }
      context.fail(child, std::move(message));
    }
  }
  for (const tinyxml2::XMLAttribute* a = element->FirstAttribute(); a != nullptr; a = a->Next()) {
    const std::string_view name = a->Name();
    if (!rule->allows_attribute(name) && name.substr(0, 5) != "xmlns" &&
        name.substr(0, 4) != "xsi:") {
      context.warn_once(element, "attribute:" + std::string(element->Name()) + "." + a->Name(),
                        "unknown attribute '" + std::string(a->Name()) + "' of <" +
                            element->Name() + "> ignored");
    }
  }
}

Children::~Children() {
  if (consumed_all_ || std::uncaught_exceptions() > 0) return;
  for (const Element* child = element_->FirstChildElement(); child != nullptr;
       child = child->NextSiblingElement()) {
    const std::string_view name = child->Name();
    if (std::find(consumed_.begin(), consumed_.end(), name) == consumed_.end()) {
      context_.warn_once(child, "unread:" + std::string(type_) + "." + std::string(name),
                         "<" + std::string(name) + "> in <" + element_->Name() +
                             "> is not supported yet; ignored");
    }
  }
}

void Children::consumed(std::string_view name) {
  if (std::find(consumed_.begin(), consumed_.end(), name) == consumed_.end()) {
    consumed_.push_back(name);
  }
}

const Element* Children::opt(const char* name) {
  consumed(name);
  const Element* first = element_->FirstChildElement(name);
  if (first != nullptr && first->NextSiblingElement(name) != nullptr) {
    context_.fail(first->NextSiblingElement(name),
                  "<" + std::string(element_->Name()) + "> may contain only one <" + name + ">");
  }
  return first;
}

const Element* Children::one(const char* name) {
  const Element* child = opt(name);
  if (child == nullptr) {
    context_.fail(element_, "<" + std::string(element_->Name()) + "> needs a <" + name + ">");
  }
  return child;
}

std::vector<const Element*> Children::all(const char* name) {
  consumed(name);
  std::vector<const Element*> result;
  for (const Element* child = element_->FirstChildElement(name); child != nullptr;
       child = child->NextSiblingElement(name)) {
    result.push_back(child);
  }
  return result;
}

std::vector<const Element*> Children::at_least(const char* name, size_t minimum) {
  auto result = all(name);
  if (result.size() < minimum) {
    context_.fail(element_, "<" + std::string(element_->Name()) + "> needs at least " +
                                std::to_string(minimum) + " <" + name + ">");
  }
  return result;
}

const Element* Children::choice() {
  consumed_all_ = true;
  const Element* child = element_->FirstChildElement();
  if (child == nullptr) {
    const TypeRule* rule = find_type_rule(type_);
    std::string options;
    for (size_t i = 0; i < rule->children.size(); ++i) {
      options += (i == 0 ? "" : ", ") + std::string(rule->children[i]);
    }
    context_.fail(element_, "<" + std::string(element_->Name()) + "> needs one of: " + options);
  }
  if (const Element* second = child->NextSiblingElement(); second != nullptr) {
    context_.fail(second, "<" + std::string(element_->Name()) + "> takes one child, found <" +
                              child->Name() + "> and <" + second->Name() + ">");
  }
  return child;
}

}  // namespace corsa::xosc
