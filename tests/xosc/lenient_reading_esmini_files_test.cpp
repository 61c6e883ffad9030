// Rule breaks that kept whole esmini examples from loading, read as meant with a located
// `(read as ...)` warning and refused under LoadOptions::strict: a ManeuverGroup without Actors
// and an XML attribute written twice.

#include <catch2/catch.hpp>
#include <string>

#include "corsa/xosc/scenario.h"
#include "lenient_load.h"
#include "scenario_text.h"
#include "temp_dir.h"

using namespace corsa::xosc;
using corsa::test::check_both_ways;
using corsa::test::lenient_load;
using corsa::test::line_of;
using corsa::test::Loaded;
using corsa::test::ScenarioText;
using corsa::test::warning_with;

namespace {

// An act starting at once whose one maneuver group is `group` (its XML, without the act).
std::string story_with_group(const std::string& group) {
  return "<Story name=\"S\">\n<Act name=\"Act\">\n" + group +
         "<StartTrigger><ConditionGroup><Condition name=\"C\" delay=\"0\" "
         "conditionEdge=\"none\"><ByValueCondition><SimulationTimeCondition value=\"0\" "
         "rule=\"greaterThan\"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>\n"
         "</Act>\n</Story>\n";
}

}  // namespace

TEST_CASE("a ManeuverGroup without Actors has no actors", "[xosc][lenient]") {
  ScenarioText text;
  text.stories = story_with_group(
      "<ManeuverGroup maximumExecutionCount=\"1\" name=\"Dummy\">\n"
      "<Maneuver name=\"M\"><Event name=\"E\" priority=\"override\"><Action name=\"A\">"
      "<PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics "
      "dynamicsShape=\"step\" dynamicsDimension=\"time\" value=\"0\"/><SpeedActionTarget>"
      "<AbsoluteTargetSpeed value=\"5\"/></SpeedActionTarget></SpeedAction>"
      "</LongitudinalAction></PrivateAction></Action></Event></Maneuver>\n"
      "</ManeuverGroup>\n");
  const std::string xml = text.str();
  check_both_ways(xml, "<ManeuverGroup> 'Dummy' without <Actors>",
                  line_of(xml, "<ManeuverGroup"));
  corsa::test::TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(loaded.scenario);
  const auto& group = loaded.scenario->storyboard.stories[0].acts[0].maneuver_groups[0];
  CHECK(group.actors.entity_refs.empty());
  CHECK(!group.actors.select_triggering_entities);
  CHECK(group.actors.source.line == line_of(xml, "<ManeuverGroup"));
  CHECK(group.maneuvers.size() == 1);
  // An Actors element that is there is still read as before.
  ScenarioText with_actors;
  with_actors.stories = story_with_group(
      "<ManeuverGroup maximumExecutionCount=\"1\" name=\"G\">\n"
      "<Actors selectTriggeringEntities=\"true\"><EntityRef entityRef=\"Ego\"/></Actors>\n"
      "</ManeuverGroup>\n");
  const Loaded plain = lenient_load(dir, with_actors.str());
  REQUIRE(plain.scenario);
  const auto& actors = plain.scenario->storyboard.stories[0].acts[0].maneuver_groups[0].actors;
  CHECK(actors.select_triggering_entities);
  CHECK(actors.entity_refs == std::vector<std::string>{"Ego"});
  CHECK(plain.warnings.empty());
}
