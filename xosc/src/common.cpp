// Small member functions of the model types.

#include "corsa/xosc/common.h"

#include "corsa/xosc/entities.h"
#include "corsa/xosc/scenario.h"
#include "corsa/xosc/storyboard.h"

namespace corsa::xosc {

const std::string& Source::file_name() const {
  static const std::string kEmpty;
  return file ? *file : kEmpty;
}

Diagnostic Source::error(std::string message) const {
  return make_error(file_name(), line, std::move(message));
}

Diagnostic Source::warning(std::string message) const {
  return make_warning(file_name(), line, std::move(message));
}

std::optional<std::string> Properties::get(const std::string& name) const {
  for (const auto& property : properties) {
    if (property.name == name) {
      return property.value;
    }
  }
  return std::nullopt;
}

const ScenarioObject* Entities::find_object(const std::string& name) const {
  for (const auto& object : objects) {
    if (object.name == name) {
      return &object;
    }
  }
  return nullptr;
}

const EntitySelection* Entities::find_selection(const std::string& name) const {
  for (const auto& selection : selections) {
    if (selection.name == name) {
      return &selection;
    }
  }
  return nullptr;
}

const ParameterDeclaration* Scenario::find_parameter(const std::string& name) const {
  for (const auto& parameter : parameters) {
    if (parameter.name == name) {
      return &parameter;
    }
  }
  return nullptr;
}

const VariableDeclaration* Scenario::find_variable(const std::string& name) const {
  for (const auto& variable : variables) {
    if (variable.name == name) {
      return &variable;
    }
  }
  return nullptr;
}

std::vector<const Action*> event_actions(const Storyboard& board) {
  std::vector<const Action*> actions;
  for (const Story& story : board.stories) {
    for (const Act& act : story.acts) {
      for (const ManeuverGroup& group : act.maneuver_groups) {
        for (const Maneuver& maneuver : group.maneuvers) {
          for (const Event& event : maneuver.events) {
            for (const Action& action : event.actions) {
              actions.push_back(&action);
            }
          }
        }
      }
    }
  }
  return actions;
}

}  // namespace corsa::xosc
