// Reading OpenSCENARIO 0.9 drafts (FileHeader revMajor="0" revMinor="9"): a pass over the XML
// tree, before the normal reader, that rewrites the 0.9 forms into their 1.0 equivalents
// (ASAM OpenSCENARIO 1.0 migration notes; the 0.9 schema; esmini's 0.9 reader where the draft
// leaves a choice). Renamed elements keep their own line; an element the mapping adds (a wrapper
// such as <TeleportAction>) takes the line of the 0.9 element it stands for, so that a later
// error still points at the original text. This file: the document, its parameters, entities
// and catalogs; osc09_storyboard.cpp and osc09_actions.cpp the rest.

#include "osc09_mapping.h"

#include <algorithm>
#include <cstdlib>

#include "osc09_rewriter.h"

namespace corsa::xosc {
namespace {

// tinyxml2 has no setter for a node's line; a pointer to the protected member, formed in a
// derived class, reaches it without touching anything else.
struct Osc09LineAccess : tinyxml2::XMLNode {
  static int tinyxml2::XMLNode::*line_member() { return &Osc09LineAccess::_parseLineNum; }
};

bool says_osc09(const Element* root) {
  const Element* header = root->FirstChildElement("FileHeader");
  return header != nullptr && header->IntAttribute("revMajor", -1) == 0 &&
         header->IntAttribute("revMinor", -1) == 9;
}

}  // namespace

std::vector<Element*> osc09_children(Element* parent, const char* name) {
  std::vector<Element*> out;
  for (Element* c = parent->FirstChildElement(name); c != nullptr;
       c = c->NextSiblingElement(name)) {
    out.push_back(c);
  }
  return out;
}

Osc09Rewriter::Osc09Rewriter(ParseContext& ctx, tinyxml2::XMLDocument& document)
    : ctx_(ctx), document_(document) {}

// --- tree edits ----------------------------------------------------------------------------------
void Osc09Rewriter::note(const std::string& form) {
  if (std::find(forms_.begin(), forms_.end(), form) == forms_.end()) forms_.push_back(form);
}

void Osc09Rewriter::rename(Element* e, const char* name) {
  if (std::string_view(e->Name()) == name) return;
  note(e->Name());
  e->SetName(name);
}

// 0.9 named a parameter `name="$X"` where 1.0 writes `parameterRef="X"`.
void Osc09Rewriter::parameter_ref(Element* e) {
  move_attribute(e, "name", "parameterRef");
  const char* ref = e->Attribute("parameterRef");
  if (ref != nullptr && ref[0] == '$' && ref[1] != '\0') {
    const std::string bare = ref + 1;
    e->SetAttribute("parameterRef", bare.c_str());
  }
}

void Osc09Rewriter::move_attribute(Element* e, const char* from, const char* to) {
  const char* value = e->Attribute(from);
  if (value == nullptr) return;
  const std::string text = value;
  e->DeleteAttribute(from);
  e->SetAttribute(to, text.c_str());
}

void Osc09Rewriter::default_attribute(Element* e, const char* name, const char* value) {
  if (e->Attribute(name) == nullptr) e->SetAttribute(name, value);
}

Element* Osc09Rewriter::new_element(const char* name, const Element* line_of) {
  Element* e = document_.NewElement(name);
  e->*Osc09LineAccess::line_member() = line_of->GetLineNum();
  return e;
}

Element* Osc09Rewriter::wrap(Element* e, const char* name) {
  Element* wrapper = new_element(name, e);
  e->Parent()->InsertAfterChild(e, wrapper);
  wrapper->InsertEndChild(e);
  return wrapper;
}

Source Osc09Rewriter::attribute_source(const Element* e, const char* attribute) const {
  return Source{ctx_.file().name, ctx_.attribute_line(e, attribute)};
}

// --- parameter values ----------------------------------------------------------------------------
// 0.9 declared `name="$X"` and typed it with `type`; 1.0 declares `name="X"` with
// `parameterType`, and references stay `$X`.
Osc09Rewriter::Osc09ScopeGuard::Osc09ScopeGuard(Osc09Rewriter& rewriter, Element* owner,
                                                bool isolated)
    : rewriter_(rewriter) {
  rewriter.scopes_.push_back(Osc09Scope{{}, isolated});
  for (Element* e : osc09_children(owner, "ParameterDeclaration")) {
    rewriter.parameter_declarations(e);
  }
}

void Osc09Rewriter::parameter_declarations(Element* e) {
  rename(e, "ParameterDeclarations");
  for (Element* p : osc09_children(e, "Parameter")) {
    rename(p, "ParameterDeclaration");
    move_attribute(p, "type", "parameterType");
    const char* name = p->Attribute("name");
    if (name == nullptr) continue;  // the reader reports the missing name
    std::string bare = name;
    if (bare.empty() || bare == "$") {
      // Nothing could refer to it: `$` alone is text, not a reference.
      ctx_.attribute_error(p, "name",
                           "parameter name '" + bare + "' is empty (no name after the '$')");
      continue;
    }
    if (bare.size() > 1 && bare[0] == '$') {
      bare.erase(0, 1);
      p->SetAttribute("name", bare.c_str());
    }
    // A name declared twice in one scope: the later declaration, as in the reader.
    const char* value = p->Attribute("value");
    scopes_.back().parameters[std::move(bare)] = Osc09Parameter{value != nullptr ? value : "", p};
  }
}

Osc09Rewriter::Osc09Parameter* Osc09Rewriter::find_parameter(std::string_view name, size_t upto,
                                                             size_t* found_in) {
  for (size_t k = upto; k-- > 0;) {
    auto& parameters = scopes_[k].parameters;
    if (const auto it = parameters.find(name); it != parameters.end()) {
      *found_in = k;
      return &it->second;
    }
    if (!scopes_[k].isolated) continue;
    // A catalog entry sees its own declarations, and the reader lends it the scenario's global
    // of that name (warned there).
    if (k == 0) return nullptr;
    auto& globals = scopes_[0].parameters;
    const auto global = globals.find(name);
    if (global == globals.end()) return nullptr;
    *found_in = 0;
    return &global->second;
  }
  return nullptr;
}

Osc09Rewriter::Osc09Parameter* Osc09Rewriter::referenced_parameter(std::string_view raw) {
  size_t declared = 0;
  for (const Osc09Scope& scope : scopes_) declared += scope.parameters.size();
  Osc09Parameter* holder = nullptr;
  std::string_view holder_name;
  size_t holder_scope = scopes_.size();
  std::string_view value = raw;
  // A cycle ends after as many steps as there are parameters, unresolved.
  for (size_t step = 0; !value.empty() && value[0] == '$'; ++step) {
    const std::string_view name = value.substr(1);
    if (step > declared) return nullptr;
    // A declaration's value sees its own scope and the outer ones; one that uses its own name
    // means the outer parameter of that name.
    const size_t upto =
        holder == nullptr ? scopes_.size() : holder_scope + (name == holder_name ? 0 : 1);
    size_t found_in = 0;
    holder = find_parameter(name, upto, &found_in);
    if (holder == nullptr) return nullptr;
    holder_name = name;
    holder_scope = found_in;
    value = holder->value;
  }
  return holder;
}

std::optional<std::string> Osc09Rewriter::value_of(const Element* e, const char* attribute,
                                                   bool* unresolved) {
  const char* raw = e->Attribute(attribute);
  if (raw == nullptr) return std::nullopt;
  if (raw[0] != '$') return std::string(raw);
  const Osc09Parameter* holder = referenced_parameter(raw);
  if (holder == nullptr) {
    if (unresolved != nullptr) *unresolved = true;
    return std::nullopt;
  }
  return holder->value;
}

void Osc09Rewriter::map_value(Element* e, const char* attribute, const ValueTable& table) {
  const char* raw = e->Attribute(attribute);
  if (raw == nullptr) return;
  if (const auto it = table.find(std::string_view(raw)); it != table.end()) {
    e->SetAttribute(attribute, it->second.c_str());
    return;
  }
  if (raw[0] != '$') return;
  // A reference the mapping cannot resolve is left for the reader, which reports it.
  Osc09Parameter* holder = referenced_parameter(raw);
  if (holder == nullptr) return;
  const auto it = table.find(holder->value);
  if (it == table.end()) return;  // a 1.0 word: the reference stays
  ctx_.lenient(attribute_source(e, attribute),
               std::string("0.9 value '") + clip(holder->value) + "' of parameter '" + clip(raw) +
                   "' in attribute " + attribute,
               "'" + it->second + "'");
  holder->value = it->second;
  if (holder->declaration != nullptr) {
    holder->declaration->SetAttribute("value", it->second.c_str());
  } else {
    e->SetAttribute(attribute, it->second.c_str());
  }
}

std::optional<bool> Osc09Rewriter::bool_value(Element* e, const char* attribute) {
  bool unresolved = false;
  const auto value = value_of(e, attribute, &unresolved);
  if (unresolved) {
    ctx_.attribute_error(e, attribute,
                         std::string("attribute ") + attribute + ": undefined parameter '" +
                             clip(e->Attribute(attribute)) + "'");
    return std::nullopt;
  }
  if (!value) return std::nullopt;
  if (*value == "true" || *value == "1") return true;
  if (*value == "false" || *value == "0") return false;
  ctx_.attribute_error(
      e, attribute,
      std::string("attribute ") + attribute + ": '" + clip(*value) + "' is not a valid boolean");
  return std::nullopt;
}

std::optional<double> Osc09Rewriter::double_value(const Element* e, const char* attribute) {
  const auto value = value_of(e, attribute);
  if (!value || value->empty()) return std::nullopt;
  char* end = nullptr;
  const double number = std::strtod(value->c_str(), &end);
  if (end != value->c_str() + value->size()) return std::nullopt;
  return number;
}

const Osc09Rewriter::ValueTable& Osc09Rewriter::rule_words() {
  static const ValueTable words{
      {"greater_than", "greaterThan"}, {"less_than", "lessThan"}, {"equal_to", "equalTo"}};
  return words;
}

void Osc09Rewriter::rule(Element* e) { map_value(e, "rule", rule_words()); }

// --- the document --------------------------------------------------------------------------------
void Osc09Rewriter::scenario(Element* root) {
  const Osc09ScopeGuard globals(*this, root, false);
  // Values given from outside replace the declared ones, as in the reader.
  for (const auto& [name, value] : ctx_.options().parameters) {
    const std::string_view bare =
        !name.empty() && name[0] == '$' ? std::string_view(name).substr(1) : std::string_view(name);
    auto& parameters = scopes_.back().parameters;
    if (const auto it = parameters.find(bare); it != parameters.end()) {
      it->second = Osc09Parameter{value, nullptr};
    }
  }
  for (Element* e : osc09_children(root)) {
    const std::string_view name = e->Name();
    if (name == "Catalogs") {
      catalog_locations(e);
    } else if (name == "RoadNetwork") {
      road_network(e);
    } else if (name == "Entities") {
      entities(e);
    } else if (name == "Storyboard") {
      storyboard(e);
    }
  }
  catalog_references(root);
}

// 0.9 allowed an empty catalog element for "no catalog"; its DriverCatalog and
// PedestrianControllerCatalog became 1.0's one ControllerCatalog: the first of them given is
// kept, a second is left out with a warning.
void Osc09Rewriter::catalog_locations(Element* e) {
  rename(e, "CatalogLocations");
  const Element* controllers = nullptr;
  for (Element* c : osc09_children(e)) {
    const std::string_view name = c->Name();
    if (c->FirstChildElement("Directory") == nullptr) {
      e->DeleteChild(c);
    } else if (name == "DriverCatalog" || name == "PedestrianControllerCatalog") {
      if (controllers != nullptr) {
        ctx_.lenient(c,
                     "<" + std::string(name) + "> beside <" + controllers->Value() +
                         "> (1.0 has one ControllerCatalog for both)",
                     "the ControllerCatalog of <" + std::string(controllers->Value()) + ">, line " +
                         std::to_string(controllers->GetLineNum()) + "; this one left out");
        e->DeleteChild(c);
        continue;
      }
      note(c->Name());
      controllers = c;
    }
  }
  if (controllers != nullptr) const_cast<Element*>(controllers)->SetName("ControllerCatalog");
}

void Osc09Rewriter::road_network(Element* e) {
  for (Element* c : osc09_children(e, "Logics")) rename(c, "LogicFile");
  for (Element* c : osc09_children(e, "SceneGraph")) rename(c, "SceneGraphFile");
  for (Element* c : osc09_children(e, "Signals")) signals(c);
}

// esmini's 0.9 files mark a default-controlled entity with the property control="internal",
// which is what 1.0 means by an entity without an ObjectController.
void Osc09Rewriter::entities(Element* e) {
  for (Element* object : osc09_children(e, "Object")) {
    rename(object, "ScenarioObject");
    for (Element* properties : osc09_children(object, "Properties")) {
      const Element* property = properties->FirstChildElement("Property");
      if (property != nullptr && property->NextSiblingElement() == nullptr &&
          property->Attribute("name", "control") && property->Attribute("value", "internal")) {
        object->DeleteChild(properties);
      }
    }
    for (Element* controller : osc09_children(object, "Controller")) {
      rename(controller, "ObjectController");
      controllers(controller);
    }
    for (Element* entry : osc09_children(object)) {
      const std::string_view name = entry->Name();
      if (name == "Vehicle" || name == "Pedestrian" || name == "MiscObject") {
        const Osc09ScopeGuard scope(*this, entry, false);
        entity_body(entry);
      }
    }
  }
  for (Element* s : osc09_children(e, "Selection")) selection(s);
}

// 0.9's CatalogReference assigned values in ParameterAssignment/Parameter name="$X"; 1.0 in
// ParameterAssignments/ParameterAssignment parameterRef="X".
void Osc09Rewriter::catalog_references(Element* e) {
  for (Element* c : osc09_children(e)) {
    if (std::string_view(c->Name()) != "CatalogReference") {
      catalog_references(c);
      continue;
    }
    for (Element* assignments : osc09_children(c, "ParameterAssignment")) {
      rename(assignments, "ParameterAssignments");
      for (Element* p : osc09_children(assignments, "Parameter")) {
        rename(p, "ParameterAssignment");
        parameter_ref(p);
        // The entry's parameter holds a 1.0 word once its catalog is mapped; a 0.9 rule word
        // assigned to it is read as its 1.0 word. The other 0.9 words (any, overwrite, ...) are
        // also text a string parameter may mean, and stay.
        const char* value = p->Attribute("value");
        if (value == nullptr) continue;
        const auto word = rule_words().find(std::string_view(value));
        if (word == rule_words().end()) continue;
        ctx_.lenient(
            attribute_source(p, "value"),
            std::string("0.9 value '") + value + "' assigned to parameter '$" +
                clip(p->Attribute("parameterRef", nullptr) != nullptr ? p->Attribute("parameterRef")
                                                                      : "") +
                "'",
            "'" + word->second + "'");
        p->SetAttribute("value", word->second.c_str());
      }
    }
  }
}

// --- catalogs ------------------------------------------------------------------------------------
// A 0.9 catalog file: its entries' own ParameterDeclaration, a Vehicle's category, Dimension,
// Front/Rear axles and Performance mass, a Driver (1.0's Controller), a Pedestrian's and a
// MiscObject's category, a Driver's or PedestrianController's Controller, an Environment, and
// maneuvers, routes and trajectories in their 0.9 forms. An attribute is judged
// by its parameter's declared value (a reference's assignment is not known here); a 0.9 word
// is rewritten in the declaration, which an assignment still replaces.
void Osc09Rewriter::catalog(Element* catalog) {
  controllers(catalog);
  for (Element* entry : osc09_children(catalog)) {
    const Osc09ScopeGuard scope(*this, entry, true);
    const std::string_view name = entry->Name();
    if (name == "Vehicle" || name == "Pedestrian" || name == "MiscObject") {
      entity_body(entry);
    } else if (name == "Maneuver") {
      for (Element* event : osc09_children(entry, "Event")) this->event(entry, event);
    } else if (name == "Route") {
      route(entry);
    } else if (name == "Trajectory") {
      trajectory(entry);
    } else if (name == "Environment") {
      environment(entry);
    }
  }
  catalog_references(catalog);
}

// A Vehicle, Pedestrian or MiscObject, in a catalog or in the scenario's Entities (its
// ParameterDeclaration mapped by the caller's scope).
void Osc09Rewriter::entity_body(Element* entry) {
  const std::string_view name = entry->Name();
  if (name == "Vehicle") {
    vehicle(entry);
    return;
  }
  // The 0.9 MiscObject categories guardRail and other are 1.0's railing and none.
  if (name == "MiscObject")
    map_value(entry, "category", {{"guardRail", "railing"}, {"other", "none"}});
  move_attribute(entry, "category",
                 name == "Pedestrian" ? "pedestrianCategory" : "miscObjectCategory");
  for (Element* box : osc09_children(entry, "BoundingBox")) bounding_box(box);
}

// 0.9's Performance carried the mass, 1.1 puts it on the Vehicle (Performance's maxAcceleration,
// which 0.9 did not have, is left to the reader's reading of a missing limit).
void Osc09Rewriter::vehicle(Element* e) {
  if (e->Attribute("category") != nullptr) {
    note("Vehicle category");
    move_attribute(e, "category", "vehicleCategory");
  }
  for (Element* box : osc09_children(e, "BoundingBox")) bounding_box(box);
  for (Element* performance : osc09_children(e, "Performance")) {
    if (const char* mass = performance->Attribute("mass")) {
      note("Performance mass");
      const std::string text = mass;
      performance->DeleteAttribute("mass");
      default_attribute(e, "mass", text.c_str());
    }
  }
  for (Element* axles : osc09_children(e, "Axles")) {
    for (Element* front : osc09_children(axles, "Front")) rename(front, "FrontAxle");
    for (Element* rear : osc09_children(axles, "Rear")) rename(rear, "RearAxle");
    for (Element* other : osc09_children(axles, "Additional")) rename(other, "AdditionalAxle");
    for (Element* one : osc09_children(axles)) axle(one);
  }
}

void Osc09Rewriter::bounding_box(Element* e) {
  for (Element* d : osc09_children(e, "Dimension")) rename(d, "Dimensions");
}

// --- entry point ---------------------------------------------------------------------------------
void map_osc09_to_osc10(ParseContext& ctx, tinyxml2::XMLDocument& document) {
  Element* root = document.RootElement();
  if (root == nullptr || !says_osc09(root)) return;
  Osc09Rewriter rewriter(ctx, document);
  if (Element* catalog = root->FirstChildElement("Catalog")) {
    rewriter.catalog(catalog);
  } else {
    rewriter.scenario(root);
  }
  if (rewriter.forms().empty()) return;  // a 0.9 header over 1.0 forms: read as before
  Element* header = root->FirstChildElement("FileHeader");
  std::string forms;
  for (const std::string& form : rewriter.forms()) {
    forms += (forms.empty() ? "" : ", ") + form;
  }
  ctx.lenient(header, "OpenSCENARIO 0.9 draft", "1.0 by the 0.9-to-1.0 mapping: " + forms);
  // The header now says what the document has become, so that it is not warned about twice.
  header->SetAttribute("revMajor", 1);
  header->SetAttribute("revMinor", 0);
}

void map_osc09_catalog_file(XmlFile& file) {
  if (!file.document) return;
  Diagnostics diagnostics;
  const LoadOptions options;
  ParseContext ctx(diagnostics, options);
  ctx.swap_file({file.name, file.directory, file.text, file.document.get()});
  try {
    map_osc09_to_osc10(ctx, *file.document);
  } catch (const TooManyErrors&) {
    // The mapping stopped (ctx.errors() holds what it found, the last saying so); the file is
    // kept with those located errors, which each load reading it reports.
  }
  // ParseContext::lenient words a warning "message (read as X)": split back into its parts, so
  // that a strict load makes it its error.
  const std::string read_as = " (read as ";
  for (const Diagnostic& warning : diagnostics.all()) {
    const size_t at = warning.message.rfind(read_as);
    if (warning.severity != Severity::kWarning || at == std::string::npos) continue;
    const size_t from = at + read_as.size();
    file.mapping_notes.push_back({Source{file.name, warning.line}, warning.message.substr(0, at),
                                  warning.message.substr(from, warning.message.size() - from - 1)});
  }
  for (const Diagnostic& error : ctx.errors()) {
    file.mapping_notes.push_back({Source{file.name, error.line}, error.message, std::nullopt});
  }
}

}  // namespace corsa::xosc
