// Parameter scopes of one load (§9.1): declarations, `$name` and `${expression}` resolution,
// value constraints. Errors are recorded (ParseContext::error) so that every bad declaration of
// a file is reported in one pass. A declaration whose value cannot be read is marked in error:
// each use of it is an error at the use (the use's attribute is not read, so its type is not
// reported as well).

#include <algorithm>
#include <cmath>

#include "corsa/core/strings.h"
#include "corsa/xosc/expression.h"
#include "parse_context.h"

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

Value neutral_value(ParameterType type) {
  switch (type) {
    case ParameterType::kBoolean:
      return Value{type, false};
    case ParameterType::kDouble:
      return Value{type, 0.0};
    case ParameterType::kInt:
    case ParameterType::kUnsignedInt:
    case ParameterType::kUnsignedShort:
      return Value{type, int64_t{0}};
    case ParameterType::kDateTime:
      return Value{type, std::string("1970-01-01T00:00:00Z")};
    case ParameterType::kString:
      break;
  }
  return Value{type, std::string()};
}

bool is_ordering(Rule rule) { return rule != Rule::kEqualTo && rule != Rule::kNotEqualTo; }

// Where the value of a parameter was written, for the message at a use of it: the line, and the
// file when it is another one than the use's; an option (--param) by its name.
std::string value_place(const Source& where, const std::string& use_file) {
  if (where.line <= 0) return "by " + where.file_name();
  std::string place = "at line " + std::to_string(where.line);
  if (where.file_name() != use_file) place += " of " + where.file_name();
  return place;
}

}  // namespace

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
      fail(element, "bad expression '" + clip(text) + "': missing closing '}'");
    }
    const std::string_view body = std::string_view(text).substr(2, text.size() - 3);
    const ParameterLookup find = [&](std::string_view name) -> std::optional<ExprValue> {
      const Entry* entry = lookup(name, upto, element);
      if (entry == nullptr) return std::nullopt;
      if (entry->in_error) fail(element, unusable_message(*entry));
      const Value* value = &entry->declaration.value;
      if (const auto* b = std::get_if<bool>(&value->data)) return ExprValue::of_bool(*b);
      if (const auto number = value->number()) return ExprValue::of(*number);
      // A string parameter holding a number (ASAM's own ALKS scenarios declare lane ids as
      // strings and compute with them): §9.2 allows numbers only, the intent is clear.
      const auto number = value->type == ParameterType::kString
                              ? parse_double(std::get<std::string>(value->data))
                              : std::nullopt;
      if (!number || !std::isfinite(*number)) {
        throw ExpressionError("parameter '$" + std::string(name) + "' of type " +
                                  type_name(value->type) + " cannot be used in an expression",
                              1);
      }
      lenient(element,
              "string parameter '$" + std::string(name) + "' = '" +
                  clip(std::get<std::string>(value->data)) + "' used in an expression",
              "the number " + format_double(*number));
      return ExprValue::of(*number);
    };
    // esmini's expressions know the constant pi (its trajectory_speed test: h="${pi/2}"); the
    // standard's grammar has none, the meaning is clear.
    const ConstantNote constant = [&](std::string_view name, double value) {
      lenient(element, "constant '" + std::string(name) + "' in expression '" + clip(text) + "'",
              format_double(value));
    };
    try {
      const ExprValue result = evaluate_expression(body, find, constant);
      if (result.is_bool) return result.boolean ? "true" : "false";
      return format_double(result.number == 0.0 ? 0.0 : result.number);
    } catch (const ExpressionError& error) {
      fail(element, "bad expression '" + clip(text) + "': " + error.what() + " (column " +
                        std::to_string(error.column() + 2) + ")");
    }
  }
  const std::string_view name = std::string_view(text).substr(1);
  if (!is_identifier(name)) {
    return text;  // a string that merely starts with '$'
  }
  const Entry* entry = lookup(name, upto, element);
  if (entry == nullptr) {
    fail(element, "undefined parameter '" + clip(text) + "'");
  }
  if (entry->in_error) fail(element, unusable_message(*entry));
  return entry->declaration.value.text();
}

std::string ParseContext::unusable_message(const Entry& entry) const {
  const std::string use_file = file_.name ? *file_.name : std::string();
  const std::string whose =
      entry.declaration.overridden ? "the value assigned to it " : "its declaration ";
  return "parameter '" + entry.declaration.name + "' used here has no valid value: " + whose +
         value_place(entry.value_source, use_file) + " is in error";
}

const ParseContext::Entry* ParseContext::lookup(std::string_view name, size_t upto,
                                                const Element* from) {
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
        return &scopes_[k].entries[i];
      }
    }
  }
  if (barrier == 0 || from == nullptr) return nullptr;
  // §9.4: a catalog entry sees only its own declarations. esmini's catalogs use parameters that
  // only the scenario declares (its HWManeuvers use $AccRate), which esmini resolves in the
  // scenario's global scope: one parameter of that name, so the meaning is clear.
  auto& globals = scopes_[0].entries;
  for (size_t i = 0; i < globals.size(); ++i) {
    if (globals[i].declaration.name != name) continue;
    resolve_entry(0, i);
    const Entry& global = scopes_[0].entries[i];
    lenient(from, "parameter '$" + std::string(name) + "' is not declared in its catalog entry",
            "the scenario's global parameter, '" + clip(global.declaration.value.text()) + "'");
    return &global;
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
    error(entry->element, "cyclic parameter use: " + chain + entry->declaration.name);
    return;  // the neutral value stands in
  }
  entry->state = Entry::State::kResolving;
  resolving_.push_back(entry->declaration.name);
  const Element* element = entry->element;
  std::optional<std::string> text;
  if (entry->literal) {
    text = entry->declaration.declared_text;
  } else {
    try {
      text = resolve_in(element, entry->declaration.declared_text, scope + 1);
    } catch (const InputError& caught) {
      record(caught);
    }
  }
  entry = &scopes_[scope].entries[index];  // resolving may not grow scopes, but stay safe
  std::optional<Value> value;
  if (text) {
    const std::string what = "parameter '" + entry->declaration.name + "'";
    value = typed_value(element, entry->declaration.type, *text, what);
    if (!value) {
      const Source& where = entry->value_source;
      record(InputError(make_error(
          where.file_name(), where.line,
          what + ": '" + clip(*text) + "' is not a valid " + type_name(entry->declaration.type))));
    }
  }
  if (value) entry->declaration.value = *value;
  entry->in_error = !value;
  entry->state = Entry::State::kDone;
  resolving_.pop_back();
  if (value) check_constraints(*entry);
}

void ParseContext::check_constraints(Entry& entry) {
  auto& groups = entry.declaration.constraint_groups;
  if (groups.empty()) return;
  const ParameterType type = entry.declaration.type;
  const std::string what = "parameter '" + entry.declaration.name + "'";
  size_t flat = 0;
  bool any_group = false;
  for (auto& group : groups) {
    bool all = true;
    for (auto& constraint : group.constraints) {
      const Element* element = entry.constraint_elements[flat++];
      try {
        constraint.value = resolve(element, constraint.value);
      } catch (const InputError& caught) {
        record(caught);
        all = false;
        continue;
      }
      const auto bound = typed_value(element, type, constraint.value, "constraint value");
      if (!bound) {
        error(element, "constraint value '" + clip(constraint.value) + "' of " + what +
                           " is not a valid " + type_name(type));
        all = false;
        continue;
      }
      // §9.1.3: a string parameter's constraints use equalTo or notEqualTo only. An ordering
      // rule between two numbers written as strings (ASAM's ALKS lane ids) means the numbers.
      if (type == ParameterType::kString && is_ordering(constraint.rule)) {
        const auto left = parse_double(entry.declaration.value.text());
        const auto right = parse_double(constraint.value);
        if (left && right) {
          lenient(element, "rule " + std::string(to_string(constraint.rule)) + " on string " + what,
                  "a comparison of the numbers " + format_double(*left) + " and " +
                      format_double(*right));
          all = all && compare_values(Value{ParameterType::kDouble, *left}, constraint.rule,
                                      Value{ParameterType::kDouble, *right});
          continue;
        }
      }
      all = all && compare_values(entry.declaration.value, constraint.rule, *bound);
    }
    any_group = any_group || all;
  }
  if (!any_group) {
    const Source& where = entry.value_source;
    const size_t before = errors_.size();
    record(InputError(make_error(where.file_name(), where.line,
                                 what + " = '" + clip(entry.declaration.value.text()) +
                                     "' violates its value constraints")));
    if (entry.declaration.overridden && errors_.size() > before) {
      outside_violations_.push_back(errors_.size() - 1);
    }
  }
}

ParseContext::Entry ParseContext::read_declaration(const Element* element) {
  Children decl_kids(*this, element, "ParameterDeclaration");
  Entry entry;
  entry.element = element;
  const char* name = element->Attribute("name");
  if (name == nullptr) missing(element, "name");
  entry.declaration.name = name;
  if (entry.declaration.name.size() > 1 && entry.declaration.name[0] == '$') {
    // OpenSCENARIO 1.0 examples declare "$owner" and use "$owner": the name is "owner".
    lenient(element, "parameter name '" + clip(entry.declaration.name) + "' starts with '$'",
            "'" + clip(entry.declaration.name.substr(1)) + "'");
    entry.declaration.name.erase(0, 1);
  }
  entry.declaration.type = req_enum<ParameterType>(element, "parameterType");
  entry.declaration.value = neutral_value(entry.declaration.type);
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
  return entry;
}

std::vector<ParameterDeclaration> ParseContext::push_scope(
    const Element* declarations, const std::vector<ParameterAssignment>& overrides, bool isolated,
    std::string_view owner) {
  Scope scope;
  scope.barrier = isolated ? scopes_.size() : (scopes_.empty() ? 0 : scopes_.back().barrier);
  if (declarations != nullptr) {
    Children kids(*this, declarations, "ParameterDeclarations");
    for (const Element* element : kids.all("ParameterDeclaration")) {
      recover([&] {
        Entry entry = read_declaration(element);
        const auto same = std::find_if(
            scope.entries.begin(), scope.entries.end(),
            [&](const Entry& other) { return other.declaration.name == entry.declaration.name; });
        if (same != scope.entries.end()) {
          lenient(element,
                  "parameter '" + clip(entry.declaration.name) +
                      "' is declared twice (first at line " +
                      std::to_string(same->element->GetLineNum()) + ")",
                  "the later declaration");
          scope.entries.erase(same);
        }
        scope.entries.push_back(std::move(entry));
      });
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
      record(InputError(make_error(
          assignment.source.file_name(), assignment.source.line,
          std::string(owner) + " declares no parameter '" + clip(assignment.parameter_ref) + "'")));
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

std::optional<ParameterType> ParseContext::parameter_type(const std::string& name) {
  const Entry* entry = lookup(name, scopes_.size(), nullptr);
  if (entry != nullptr) return entry->declaration.value.type;
  return std::nullopt;
}

std::optional<ParameterType> ParseContext::variable_type(const std::string& name) const {
  const auto found = variables.find(name);
  if (found == variables.end()) return std::nullopt;
  return found->second;
}

}  // namespace corsa::xosc
