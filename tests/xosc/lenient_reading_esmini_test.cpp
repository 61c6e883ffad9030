// Rule breaks met in esmini's examples whose meaning is clear, read as meant with a located
// `(read as ...)` warning and refused under LoadOptions::strict: a maximumExecutionCount of -1,
// relative road and lane positions without their offsets, a catalog location without its
// Directory, an empty Action, a Maneuver or Story without a name, a relative target speed of 0
// without its value type.

#include <catch2/catch.hpp>
#include <limits>
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

// A story whose one event holds `action` (inner XML of <Action name="A">, empty for <Action/>)
// and whose event and maneuver group run at most `count` times.
std::string esmini_story(const std::string& count, const std::string& action,
                         const std::string& maneuver_attributes = "name=\"M\"") {
  const std::string action_xml =
      action.empty() ? "<Action name=\"A\"/>\n" : "<Action name=\"A\">" + action + "</Action>\n";
  return "<Story name=\"S\">\n<Act name=\"Act\">\n<ManeuverGroup name=\"G\" "
         "maximumExecutionCount=\"" +
         count +
         "\">\n<Actors selectTriggeringEntities=\"false\"><EntityRef entityRef=\"Ego\"/>"
         "</Actors>\n<Maneuver " +
         maneuver_attributes +
         ">\n<Event name=\"E\" priority=\"override\" maximumExecutionCount=\"" + count + "\">\n" +
         action_xml +
         "<StartTrigger><ConditionGroup><Condition name=\"C\" delay=\"0\" conditionEdge=\"none\">"
         "<ByValueCondition><SimulationTimeCondition value=\"1\" rule=\"greaterThan\"/>"
         "</ByValueCondition></Condition></ConditionGroup></StartTrigger>\n"
         "</Event>\n</Maneuver>\n</ManeuverGroup>\n</Act>\n</Story>\n";
}

const std::string kSpeedAction =
    "<PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics "
    "dynamicsShape=\"step\" dynamicsDimension=\"time\" value=\"0\"/><SpeedActionTarget>"
    "<AbsoluteTargetSpeed value=\"5\"/></SpeedActionTarget></SpeedAction></LongitudinalAction>"
    "</PrivateAction>";

const Event& only_event(const Loaded& loaded) {
  return loaded.scenario->storyboard.stories[0].acts[0].maneuver_groups[0].maneuvers[0].events[0];
}

}  // namespace

TEST_CASE("a maximumExecutionCount of -1 is read as no limit", "[xosc][lenient]") {
  ScenarioText text;
  text.stories = esmini_story("-1", kSpeedAction);
  const std::string xml = text.str();
  const Loaded loaded = check_both_ways(xml, "maximumExecutionCount -1 is not an unsignedInt",
                                        line_of(xml, "<ManeuverGroup"));
  const auto& group = loaded.scenario->storyboard.stories[0].acts[0].maneuver_groups[0];
  CHECK(group.maximum_execution_count == std::numeric_limits<uint32_t>::max());
  CHECK(only_event(loaded).maximum_execution_count == std::numeric_limits<uint32_t>::max());
  // Other negative counts stay errors: only -1 has the documented meaning.
  ScenarioText minus_two;
  minus_two.stories = esmini_story("-2", kSpeedAction);
  corsa::test::TempDir dir;
  CHECK(!lenient_load(dir, minus_two.str()).errors.empty());
}

TEST_CASE("relative road and lane positions without their offsets are the entity's own place",
          "[xosc][lenient]") {
  ScenarioText text;
  text.init +=
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><TeleportAction><Position>\n"
      "<RelativeRoadPosition entityRef=\"Ego\"/>\n"
      "</Position></TeleportAction></PrivateAction>\n"
      "<PrivateAction><TeleportAction><Position>\n"
      "<RelativeLanePosition entityRef=\"Ego\"><Orientation type=\"relative\" h=\"0.1\"/>"
      "</RelativeLanePosition>\n"
      "</Position></TeleportAction></PrivateAction>\n</Private>\n";
  const std::string xml = text.str();
  // The first reading is an error under --strict; each is a warning at its element.
  const Loaded loaded = check_both_ways(xml, "<RelativeRoadPosition> without ds",
                                        line_of(xml, "<RelativeRoadPosition"));
  CHECK(warning_with(loaded, "<RelativeRoadPosition> without dt").line ==
        line_of(xml, "<RelativeRoadPosition"));
  CHECK(warning_with(loaded, "<RelativeLanePosition> without dLane").line ==
        line_of(xml, "<RelativeLanePosition"));
  CHECK(warning_with(loaded, "<RelativeLanePosition> without ds or dsLane").line ==
        line_of(xml, "<RelativeLanePosition"));
  const auto& actions = loaded.scenario->storyboard.init.privates[1].actions;
  const auto& road =
      std::get<RelativeRoadPosition>(std::get<TeleportAction>(actions[0]).position.kind);
  CHECK(road.ds == 0.0);
  CHECK(road.dt == 0.0);
  const auto& lane =
      std::get<RelativeLanePosition>(std::get<TeleportAction>(actions[1]).position.kind);
  CHECK(lane.d_lane == 0);
  CHECK(lane.ds == std::optional<double>(0.0));
  CHECK(!lane.ds_lane);
  REQUIRE(lane.orientation);
  CHECK(lane.orientation->h == std::optional<double>(0.1));
}

TEST_CASE("a catalog location without a Directory is no catalog of that kind", "[xosc][lenient]") {
  ScenarioText text;
  text.catalogs = "<RouteCatalog/>\n";
  const std::string xml = text.str();
  const Loaded loaded =
      check_both_ways(xml, "<RouteCatalog> without a <Directory>", line_of(xml, "<RouteCatalog/>"));
  CHECK(!loaded.scenario->catalog_locations.route);
}

TEST_CASE("an empty Action is an action that does nothing", "[xosc][lenient]") {
  ScenarioText text;
  text.stories = esmini_story("1", "");
  const std::string xml = text.str();
  const Loaded loaded =
      check_both_ways(xml, "<Action> 'A' without an action", line_of(xml, "<Action name=\"A\"/>"));
  const auto& action = only_event(loaded).actions[0];
  CHECK(action.name == "A");
  const auto& user = std::get<UserDefinedAction>(action.action);
  CHECK(user.type.empty());
}

TEST_CASE("a Maneuver without a name is an unnamed maneuver", "[xosc][lenient]") {
  ScenarioText text;
  text.stories = esmini_story("1", kSpeedAction, "");
  const std::string xml = text.str();
  const Loaded loaded =
      check_both_ways(xml, "<Maneuver> without name", line_of(xml, "<Maneuver >"));
  const auto& maneuver =
      loaded.scenario->storyboard.stories[0].acts[0].maneuver_groups[0].maneuvers[0];
  CHECK(maneuver.name.empty());
  CHECK(maneuver.events.size() == 1);
}

TEST_CASE("a Story without a name is an unnamed story", "[xosc][lenient]") {
  ScenarioText text;
  text.stories = esmini_story("1", kSpeedAction);
  text.stories.replace(text.stories.find("<Story name=\"S\">"), 16, "<Story >");
  const std::string xml = text.str();
  const Loaded loaded = check_both_ways(xml, "<Story> without name", line_of(xml, "<Story >"));
  const auto& story = loaded.scenario->storyboard.stories[0];
  CHECK(story.name.empty());
  CHECK(story.acts[0].path == "Act");
  CHECK(only_event(loaded).path == "Act::G::M::E");
}

TEST_CASE("a relative target speed of 0 without its value type is the other entity's speed",
          "[xosc][lenient]") {
  ScenarioText text;
  text.init +=
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics "
      "dynamicsShape=\"step\" dynamicsDimension=\"time\" value=\"0\"/><SpeedActionTarget>\n"
      "<RelativeTargetSpeed entityRef=\"Ego\" value=\"0.0\" continuous=\"true\"/>\n"
      "</SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction>\n</Private>\n";
  const std::string xml = text.str();
  const Loaded loaded =
      check_both_ways(xml, "<RelativeTargetSpeed> of value 0 without speedTargetValueType",
                      line_of(xml, "<RelativeTargetSpeed"));
  const auto& speed =
      std::get<SpeedAction>(loaded.scenario->storyboard.init.privates[1].actions[0]);
  const auto& target = std::get<RelativeTargetSpeed>(speed.target);
  CHECK(target.value_type == SpeedTargetValueType::kDelta);
  CHECK(target.value == 0.0);
  // Any other value says nothing about delta or factor: still an error.
  std::string other = xml;
  other.replace(other.find("value=\"0.0\""), 11, "value=\"1.5\"");
  corsa::test::TempDir dir;
  CHECK(!lenient_load(dir, other).errors.empty());
}
