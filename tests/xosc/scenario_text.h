#pragma once

// Builds small OpenSCENARIO documents for tests, and finds the line a snippet landed on so that
// tests can assert the exact file:line of a message.

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace corsa::test {

/// The pieces of a minimal valid scenario; each member is the inner XML of its element.
struct ScenarioText {
  std::string version = "3";
  std::string parameters;
  std::string variables;
  std::string catalogs;
  std::string road = "<LogicFile filepath=\"map.xodr\"/>";
  std::string entities =
      "<ScenarioObject name=\"Ego\">\n"
      "<Vehicle name=\"car\" vehicleCategory=\"car\">\n"
      "<BoundingBox><Center x=\"1.4\" y=\"0\" z=\"0.9\"/>"
      "<Dimensions width=\"2\" length=\"5\" height=\"1.8\"/></BoundingBox>\n"
      "<Performance maxSpeed=\"69\" maxAcceleration=\"10\" maxDeceleration=\"10\"/>\n"
      "<Axles><FrontAxle maxSteering=\"0.5\" wheelDiameter=\"0.8\" trackWidth=\"1.7\" "
      "positionX=\"3\" positionZ=\"0.4\"/><RearAxle maxSteering=\"0\" wheelDiameter=\"0.8\" "
      "trackWidth=\"1.7\" positionX=\"0\" positionZ=\"0.4\"/></Axles>\n"
      "</Vehicle>\n"
      "</ScenarioObject>\n";
  std::string init =
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><TeleportAction><Position>"
      "<WorldPosition x=\"0\" y=\"0\" h=\"0\"/></Position></TeleportAction></PrivateAction>\n"
      "</Private>\n";
  std::string stories;
  std::string stop;

  std::string str() const {
    std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<OpenSCENARIO>\n";
    xml += "<FileHeader revMajor=\"1\" revMinor=\"" + version +
           "\" date=\"2024-01-01T00:00:00\" description=\"test\" author=\"corsa\"/>\n";
    if (!parameters.empty()) {
      xml += "<ParameterDeclarations>\n" + parameters + "</ParameterDeclarations>\n";
    }
    if (!variables.empty()) {
      xml += "<VariableDeclarations>\n" + variables + "</VariableDeclarations>\n";
    }
    xml += "<CatalogLocations>\n" + catalogs + "</CatalogLocations>\n";
    xml += "<RoadNetwork>\n" + road + "\n</RoadNetwork>\n";
    xml += "<Entities>\n" + entities + "</Entities>\n";
    xml += "<Storyboard>\n<Init><Actions>\n" + init + "</Actions></Init>\n" + stories;
    if (!stop.empty()) {
      xml += "<StopTrigger>\n" + stop + "</StopTrigger>\n";
    }
    xml += "</Storyboard>\n</OpenSCENARIO>\n";
    return xml;
  }
};

/// A story with one act, group and maneuver holding `events` (inner XML of the Maneuver).
inline std::string story_with(const std::string& events, const std::string& story = "S",
                              const std::string& act = "A") {
  return "<Story name=\"" + story + "\">\n<Act name=\"" + act + "\">\n" +
         "<ManeuverGroup name=\"G\" maximumExecutionCount=\"1\">\n"
         "<Actors selectTriggeringEntities=\"false\"><EntityRef entityRef=\"Ego\"/></Actors>\n"
         "<Maneuver name=\"M\">\n" +
         events + "</Maneuver>\n</ManeuverGroup>\n</Act>\n</Story>\n";
}

/// An event named `name` with one speed action and an optional start trigger (inner XML).
inline std::string speed_event(const std::string& name, const std::string& speed = "10",
                               const std::string& trigger = "") {
  std::string xml = "<Event name=\"" + name + "\" priority=\"override\">\n" + "<Action name=\"" +
                    name +
                    "Action\"><PrivateAction><LongitudinalAction>"
                    "<SpeedAction><SpeedActionDynamics dynamicsDimension=\"time\" "
                    "dynamicsShape=\"step\" value=\"0\"/><SpeedActionTarget>"
                    "<AbsoluteTargetSpeed value=\"" +
                    speed +
                    "\"/></SpeedActionTarget></SpeedAction></LongitudinalAction>"
                    "</PrivateAction></Action>\n";
  if (!trigger.empty()) {
    xml += "<StartTrigger>\n" + trigger + "</StartTrigger>\n";
  }
  return xml + "</Event>\n";
}

/// A condition group with one StoryboardElementStateCondition.
inline std::string state_condition(const std::string& type, const std::string& ref) {
  return "<ConditionGroup><Condition name=\"C\" delay=\"0\" conditionEdge=\"rising\">"
         "<ByValueCondition><StoryboardElementStateCondition storyboardElementType=\"" +
         type + "\" storyboardElementRef=\"" + ref +
         "\" state=\"endTransition\"/></ByValueCondition></Condition></ConditionGroup>\n";
}

/// 1-based line of the first occurrence of `needle` in `text` (0 when absent).
inline int line_of(std::string_view text, std::string_view needle) {
  const size_t at = text.find(needle);
  if (at == std::string_view::npos) return 0;
  int line = 1;
  for (size_t i = 0; i < at; ++i) line += text[i] == '\n' ? 1 : 0;
  return line;
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

/// A minimal well-formed OpenDRIVE file (the loader only checks that the LogicFile exists).
inline std::string minimal_xodr() {
  return "<?xml version=\"1.0\"?>\n<OpenDRIVE><header revMajor=\"1\" revMinor=\"6\"/>"
         "</OpenDRIVE>\n";
}

}  // namespace corsa::test
