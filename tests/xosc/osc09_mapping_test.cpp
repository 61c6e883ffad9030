// OpenSCENARIO 0.9 drafts read as 1.0 through the 0.9-to-1.0 mapping: one warning at the
// FileHeader (an error under --strict), the 1.0 model, and later errors at the 0.9 lines.

#include <catch2/catch.hpp>

#include "lenient_load.h"
#include "osc09_draft.h"

namespace corsa::test {
namespace {

TEST_CASE("an OpenSCENARIO 0.9 draft is read as 1.0 with one warning at its header",
          "[xosc][osc09]") {
  const std::string xml = osc09_draft();
  const Loaded loaded = load_without_errors(xml);
  const auto warning = warning_with(loaded,
                                    "OpenSCENARIO 0.9 draft (read as 1.0 by the "
                                    "0.9-to-1.0 mapping: ParameterDeclaration, ");
  CHECK(warning.line == line_of(xml, "<FileHeader"));
  for (const auto& other : loaded.warnings) {
    CHECK(other.message.find("older than 1.0") == std::string::npos);
    CHECK(other.message.find("deprecated") == std::string::npos);
  }
  const auto& scenario = *loaded.scenario;
  REQUIRE(scenario.parameters.size() == 1);
  CHECK(scenario.parameters[0].name == "Speed");
  REQUIRE(scenario.storyboard.init.privates.size() == 1);
  const auto& init = scenario.storyboard.init.privates[0];
  CHECK(init.entity_ref == "Ego");
  REQUIRE(init.actions.size() == 2);
  // The TeleportAction the mapping adds stands at the line of the 0.9 <Position>.
  const auto* teleport = std::get_if<xosc::TeleportAction>(&init.actions[0]);
  REQUIRE(teleport != nullptr);
  CHECK(teleport->source.line == line_of(xml, "<Position>"));
  REQUIRE(scenario.storyboard.stories.size() == 1);
  const auto& act = scenario.storyboard.stories[0].acts.at(0);
  CHECK(act.start_trigger.has_value());
  REQUIRE(act.maneuver_groups.size() == 1);
  // $owner is the Story's owner.
  CHECK(act.maneuver_groups[0].actors.entity_refs == std::vector<std::string>{"Ego"});
  CHECK(act.maneuver_groups[0].source.line == line_of(xml, "<Sequence"));
}

TEST_CASE("an OpenSCENARIO 0.9 draft is an error under --strict", "[xosc][osc09]") {
  const std::string xml = osc09_draft();
  TempDir dir;
  const Loaded strict = lenient_load(dir, xml, true);
  REQUIRE(!strict.errors.empty());
  CHECK(strict.errors[0].line == line_of(xml, "<FileHeader"));
  CHECK_THAT(strict.errors[0].message,
             Catch::Contains("OpenSCENARIO 0.9 draft") && Catch::Contains("--strict"));
}

TEST_CASE("an error in a translated 0.9 element points at its own line", "[xosc][osc09]") {
  std::string xml = osc09_draft();
  xml.replace(xml.find("<Absolute value=\"20\"/>"), 23, "<Absolute value=\"fast\"/>");
  xml.replace(xml.find("<AtStart type=\"act\" name=\"A\"/>"), 30,
              "<AtStart type=\"act\" name=\"Nowhere\"/>");
  TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(loaded.errors.size() == 2);
  CHECK(loaded.errors[0].line == line_of(xml, "value=\"fast\""));
  CHECK(loaded.errors[1].line == line_of(xml, "name=\"Nowhere\""));
  CHECK_THAT(loaded.errors[1].message, Catch::Contains("Nowhere"));
}

TEST_CASE("a 0.9 event holding EXT_Quit beside other actions keeps its start conditions",
          "[xosc][osc09]") {
  std::string xml = osc09_draft();
  const std::string faster_end = "</Private>\n</Action>\n<StartConditions>";
  xml.replace(xml.find(faster_end), faster_end.size(),
              "</Private>\n</Action>\n<Action name=\"Quit\">\n<Global>\n<EXT_Quit/>\n</Global>\n"
              "</Action>\n<StartConditions>");
  const Loaded loaded = load_without_errors(xml);
  const auto& board = loaded.scenario->storyboard;
  const auto& group = board.stories.at(0).acts.at(0).maneuver_groups.at(0);
  const auto& event = group.maneuvers.at(0).events.at(0);
  // The event keeps its own action and its AtStart condition.
  CHECK(event.actions.size() == 1);
  REQUIRE(event.start_trigger.has_value());
  REQUIRE(event.start_trigger->groups.size() == 1);
  // The run stops when the event starts, not when its conditions first hold.
  REQUIRE(board.stop_trigger.has_value());
  REQUIRE(board.stop_trigger->groups.size() == 1);
  const auto& condition = board.stop_trigger->groups[0].conditions.at(0);
  const auto* by_value = std::get_if<xosc::ByValueCondition>(&condition.kind);
  REQUIRE(by_value != nullptr);
  const auto* state = std::get_if<xosc::StoryboardElementStateCondition>(by_value);
  REQUIRE(state != nullptr);
  CHECK(state->storyboard_element_ref == "E");
  CHECK(state->state == xosc::StoryboardElementState::kStartTransition);
  CHECK(condition.source.line == line_of(xml, "<Event name=\"E\""));
}

TEST_CASE("a 0.9 Meeting whose offsetTime parameter holds a time is left for the reader to refuse",
          "[xosc][osc09]") {
  std::string xml = osc09_draft();
  const std::string faster = "<Action name=\"Faster\">\n<Private>\n<Longitudinal>";
  xml.replace(xml.find(faster), faster.size(),
              "<Action name=\"Meet\">\n<Private>\n<Meeting mode=\"straight\">\n"
              "<Position>\n<World x=\"100\" y=\"0\"/>\n</Position>\n"
              "<Relative object=\"Ego\" offsetTime=\"$Speed\" continuous=\"true\">\n"
              "<Position>\n<World x=\"200\" y=\"0\"/>\n</Position>\n</Relative>\n"
              "</Meeting>\n</Private>\n</Action>\n" +
                  faster);
  TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(!loaded.errors.empty());
  CHECK(loaded.errors[0].line == line_of(xml, "<Meeting"));
  CHECK_THAT(loaded.errors[0].message, Catch::Contains("Meeting"));

  // A parameter holding 0: no offset, a SynchronizeAction.
  xml.replace(xml.find("</ParameterDeclaration>"), 23,
              "<Parameter name=\"$Offset\" type=\"double\" value=\"0\"/>\n</ParameterDeclaration>");
  xml.replace(xml.find("offsetTime=\"$Speed\""), 19, "offsetTime=\"$Offset\"");
  const Loaded zero = lenient_load(dir, xml);
  INFO((zero.errors.empty() ? std::string() : zero.errors[0].format()));
  REQUIRE(zero.errors.empty());
  const auto& event = first_event(*zero.scenario);
  const auto& action = std::get<xosc::PrivateAction>(event.actions.at(0).action);
  CHECK(std::holds_alternative<xosc::SynchronizeAction>(action));
}

}  // namespace
}  // namespace corsa::test
