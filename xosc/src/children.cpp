// Children of an element checked against the schema rule of its XSD type.

#include <algorithm>
#include <exception>
#include <string>
#include <utility>

#include "corsa/core/strings.h"
#include "parse_context.h"
#include "schema_table.h"

namespace corsa::xosc {
namespace {

// Elements of the OpenSCENARIO 0.9 draft that 1.0 renamed (esmini still ships a few 0.9 files):
// naming the 1.0 form tells the reader why a whole file is refused.
std::string_view draft_replacement(std::string_view name) {
  static constexpr std::pair<std::string_view, std::string_view> kDraft[] = {
      {"ParameterDeclaration", "ParameterDeclarations"},
      {"Catalogs", "CatalogLocations"},
      {"Logics", "LogicFile"},
      {"SceneGraph", "SceneGraphFile"},
      {"Object", "ScenarioObject"},
      {"Sequence", "ManeuverGroup"},
      {"StartConditions", "StartTrigger"},
      {"Conditions", "StartTrigger and StopTrigger"},
  };
  for (const auto& [draft, replacement] : kDraft) {
    if (name == draft) return replacement;
  }
  return {};
}

// Text in an element whose type holds only elements (XSD element-only content, e.g. a word
// between <TrajectoryCatalog> and its <Directory>): an error at the text's own line, not read.
void report_stray_text(ParseContext& context, const Element* element) {
  for (const tinyxml2::XMLNode* node = element->FirstChild(); node != nullptr;
       node = node->NextSibling()) {
    const tinyxml2::XMLText* text = node->ToText();
    if (text == nullptr || text->Value() == nullptr) continue;
    const std::string_view value = text->Value();
    const size_t first = value.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos) continue;
    const size_t last = value.find_last_not_of(" \t\r\n");
    // tinyxml2 counts the line from the text's first non-blank character.
    const int line = text->GetLineNum();
    context.error_at_line(element, line,
                          "text '" + clip(value.substr(first, last - first + 1)) + "' in <" +
                              element->Name() + ">, which holds only elements (not read)");
  }
}

}  // namespace

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
      if (!rule->children().empty()) {
        message += " (expected ";
        for (size_t i = 0; i < rule->children().size(); ++i) {
          message += (i == 0                             ? ""
                      : i + 1 == rule->children().size() ? " or "
                                                         : ", ") +
                     std::string(rule->children()[i]);
        }
        message += ")";
      }
      if (const std::string_view replacement = draft_replacement(child->Name());
          !replacement.empty()) {
        message += "; <" + std::string(child->Name()) +
                   "> is OpenSCENARIO 0.9 (a draft before 1.0), which 1.0 replaced with <" +
                   std::string(replacement) + ">: Corsa reads 1.0 to 1.3";
      }
      context.error(child, std::move(message));  // reported; the child is not read
    }
  }
  if (!rule->children().empty()) report_stray_text(context, element);
  for (const tinyxml2::XMLAttribute* a = element->FirstAttribute(); a != nullptr; a = a->Next()) {
    const std::string_view name = a->Name();
    // An allowed attribute written with other capitals is warned about where it is read.
    const bool misspelled = std::any_of(
        rule->attributes().begin(), rule->attributes().end(), [&](std::string_view allowed) {
          return iequals(allowed, name) &&
                 element->Attribute(std::string(allowed).c_str()) == nullptr;
        });
    if (!rule->allows_attribute(name) && !misspelled && name.substr(0, 5) != "xmlns" &&
        name.substr(0, 4) != "xsi:") {
      context.warn_once(element, "attribute:" + std::string(element->Name()) + "." + a->Name(),
                        "unknown attribute '" + std::string(a->Name()) + "' of <" +
                            element->Name() + "> ignored");
    }
  }
}

Children::~Children() {
  if (consumed_all_ || std::uncaught_exceptions() > 0) return;
  const TypeRule* rule = find_type_rule(type_);
  for (const Element* child = element_->FirstChildElement(); child != nullptr;
       child = child->NextSiblingElement()) {
    const std::string_view name = child->Name();
    if (!rule->allows_child(name)) continue;  // an unknown element, reported as an error
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
    context_.error(first->NextSiblingElement(name),
                   "<" + std::string(element_->Name()) + "> may contain only one <" + name + ">");
    // The first is read; the others are read for the errors inside them.
    for (const Element* extra = first->NextSiblingElement(name); extra != nullptr;
         extra = extra->NextSiblingElement(name)) {
      context_.recover([&] { read_extra_child(context_, extra); });
    }
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
    for (size_t i = 0; i < rule->children().size(); ++i) {
      options += (i == 0 ? "" : ", ") + std::string(rule->children()[i]);
    }
    context_.fail(element_, "<" + std::string(element_->Name()) + "> needs one of: " + options);
  }
  const TypeRule* rule = find_type_rule(type_);
  if (!rule->allows_child(child->Name())) {
    // Reported by the constructor; nothing of the element can be read.
    throw RecordedError(context_.source(child).error("unknown element"));
  }
  // A second child breaks the choice of the element holding both: the error is at that element
  // and names where each child is. The first is read by the caller; the others (of names the
  // type allows: an unknown one is reported by the constructor) are read here for the errors
  // inside them, so those are reported before the first child's.
  if (const Element* second = child->NextSiblingElement(); second != nullptr) {
    context_.error(element_, "<" + std::string(element_->Name()) + "> takes one child, found <" +
                                 child->Name() + "> (line " + std::to_string(child->GetLineNum()) +
                                 ") and <" + second->Name() + "> (line " +
                                 std::to_string(second->GetLineNum()) + ")");
    for (const Element* extra = second; extra != nullptr; extra = extra->NextSiblingElement()) {
      if (!rule->allows_child(extra->Name())) continue;
      context_.recover([&] { read_extra_child(context_, extra); });
    }
  }
  return child;
}

}  // namespace corsa::xosc
