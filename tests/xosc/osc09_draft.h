#pragma once

// A small OpenSCENARIO 0.9 draft (the forms of esmini's basic_ego) for the 0.9-to-1.0 mapping
// tests, which vary it by replacing parts of its text.

#include <catch2/catch.hpp>
#include <string>

#include "corsa/xosc/scenario.h"
#include "scenario_text.h"

namespace corsa::test {

// Replaces the first `from` in `text` with `to`; `from` must be there.
inline void replace_once(std::string& text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), to);
}

// ScenarioText's entity (a ScenarioObject with an inline Vehicle) as a 0.9 <Object>.
inline std::string osc09_object() {
  std::string object = ScenarioText().entities;
  object.replace(object.find("<ScenarioObject"), 15, "<Object");
  object.replace(object.find("</ScenarioObject>"), 17, "</Object>");
  return object;
}

// A 0.9 draft in the forms of esmini's basic_ego.
inline std::string osc09_draft() {
  return "<?xml version=\"1.0\"?>\n<OpenSCENARIO>\n"
         "<FileHeader revMajor=\"0\" revMinor=\"9\" date=\"2019-10-23T10:00:00\" "
         "description=\"d\" author=\"corsa\"/>\n"
         "<ParameterDeclaration>\n"
         "<Parameter name=\"$Speed\" type=\"double\" value=\"10\"/>\n"
         "</ParameterDeclaration>\n"
         "<Catalogs>\n<RouteCatalog>\n</RouteCatalog>\n</Catalogs>\n"
         "<RoadNetwork>\n<Logics filepath=\"map.xodr\"/>\n</RoadNetwork>\n"
         "<Entities>\n" +
         osc09_object() +
         "</Entities>\n"
         "<Storyboard>\n<Init>\n<Actions>\n<Private object=\"Ego\">\n"
         "<Action>\n<Position>\n<World x=\"0\" y=\"0\" h=\"0\"/>\n</Position>\n</Action>\n"
         "<Action>\n<Longitudinal>\n<Speed>\n<Dynamics shape=\"step\"/>\n"
         "<Target>\n<Absolute value=\"$Speed\"/>\n</Target>\n</Speed>\n</Longitudinal>\n"
         "</Action>\n</Private>\n</Actions>\n</Init>\n"
         "<Story name=\"S\" owner=\"Ego\">\n<Act name=\"A\">\n"
         "<Sequence name=\"Q\" numberOfExecutions=\"1\">\n"
         "<Actors>\n<Entity name=\"$owner\"/>\n</Actors>\n"
         "<Maneuver name=\"M\">\n<Event name=\"E\" priority=\"overwrite\">\n"
         "<Action name=\"Faster\">\n<Private>\n<Longitudinal>\n<Speed>\n"
         "<Dynamics shape=\"linear\" rate=\"2\"/>\n"
         "<Target>\n<Absolute value=\"20\"/>\n</Target>\n</Speed>\n</Longitudinal>\n"
         "</Private>\n</Action>\n"
         "<StartConditions>\n<ConditionGroup>\n"
         "<Condition name=\"C\" delay=\"0\" edge=\"rising\">\n<ByState>\n"
         "<AtStart type=\"act\" name=\"A\"/>\n</ByState>\n</Condition>\n"
         "</ConditionGroup>\n</StartConditions>\n"
         "</Event>\n</Maneuver>\n</Sequence>\n"
         "<Conditions>\n<Start>\n<ConditionGroup>\n"
         "<Condition name=\"Go\" delay=\"0\">\n<ByValue>\n"
         "<SimulationTime value=\"0\" rule=\"greater_than\"/>\n</ByValue>\n</Condition>\n"
         "</ConditionGroup>\n</Start>\n</Conditions>\n"
         "</Act>\n</Story>\n<End>\n</End>\n</Storyboard>\n</OpenSCENARIO>\n";
}

// osc09_draft() whose event does `actions` (0.9 Action elements) in place of its one action.
inline std::string osc09_draft_doing(const std::string& actions) {
  std::string xml = osc09_draft();
  replace_once(xml,
               "<Action name=\"Faster\">\n<Private>\n<Longitudinal>\n<Speed>\n"
               "<Dynamics shape=\"linear\" rate=\"2\"/>\n<Target>\n<Absolute value=\"20\"/>\n"
               "</Target>\n</Speed>\n</Longitudinal>\n</Private>\n</Action>\n",
               actions);
  return xml;
}

// The first event of the first maneuver of the first story's first act: where the drafts put
// the action or condition a test looks at.
inline const xosc::Event& first_event(const xosc::Scenario& scenario) {
  return scenario.storyboard.stories.at(0)
      .acts.at(0)
      .maneuver_groups.at(0)
      .maneuvers.at(0)
      .events.at(0);
}

}  // namespace corsa::test
