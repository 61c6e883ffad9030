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
  check_both_ways(xml, "<ManeuverGroup> 'Dummy' without <Actors>", line_of(xml, "<ManeuverGroup"));
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

TEST_CASE("an attribute written twice in a tag is read as its first value", "[xosc][lenient]") {
  ScenarioText text;
  text.stories = story_with_group(
      "<ManeuverGroup maximumExecutionCount=\"2\" name=\"G\" maximumExecutionCount=\"5\">\n"
      "<Actors selectTriggeringEntities=\"false\"><EntityRef entityRef=\"Ego\"/></Actors>\n"
      "</ManeuverGroup>\n");
  // A comment and a '>' inside a value are not tags: neither misleads the scan.
  text.parameters =
      "<!-- <X a=\"1\" a=\"2\"> -->\n"
      "<ParameterDeclaration name=\"Gt\" parameterType=\"string\" value=\"a>b\"/>\n";
  const std::string xml = text.str();
  const int line = line_of(xml, "<ManeuverGroup");
  check_both_ways(xml, "attribute maximumExecutionCount written twice in <ManeuverGroup>", line);
  corsa::test::TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(loaded.scenario);
  CHECK(warning_with(loaded, "written twice").message.find("'2', then '5'") != std::string::npos);
  const auto& group = loaded.scenario->storyboard.stories[0].acts[0].maneuver_groups[0];
  CHECK(group.maximum_execution_count == 2);
  // Lines after the repaired tag keep their numbers.
  CHECK(group.actors.source.line == line_of(xml, "<Actors"));
  CHECK(loaded.scenario->parameters.size() == 1);
  CHECK(loaded.warnings.size() == 1);
  // Other attribute errors stay malformed XML at their line.
  std::string broken = xml;
  broken.replace(broken.find("name=\"G\""), 8, "name=G");
  const Loaded refused = lenient_load(dir, broken);
  REQUIRE(refused.errors.size() == 1);
  CHECK_THAT(refused.errors[0].message, Catch::Contains("malformed XML: bad attribute"));
  CHECK(refused.errors[0].line == line);
}

TEST_CASE("an attribute written twice in a catalog file is warned at the catalog's line",
          "[xosc][lenient]") {
  corsa::test::TempDir dir;
  std::filesystem::create_directories(dir.path() / "catalogs");
  const std::string catalog =
      "<?xml version=\"1.0\"?>\n<OpenSCENARIO>\n"
      "<FileHeader revMajor=\"1\" revMinor=\"3\" date=\"2024-01-01T00:00:00\" "
      "description=\"c\" author=\"corsa\"/>\n"
      "<Catalog name=\"Controllers\">\n"
      "<Controller name=\"Plain\" name=\"Other\"><Properties/></Controller>\n"
      "</Catalog>\n</OpenSCENARIO>\n";
  corsa::test::write_text(dir.path() / "catalogs" / "c.xosc", catalog);
  ScenarioText text;
  text.catalogs = "<ControllerCatalog><Directory path=\"catalogs\"/></ControllerCatalog>\n";
  text.entities.replace(text.entities.find("</ScenarioObject>"), 17,
                        "<ObjectController><CatalogReference catalogName=\"Controllers\" "
                        "entryName=\"Plain\"/></ObjectController>\n</ScenarioObject>");
  const Loaded loaded = lenient_load(dir, text.str());
  INFO((loaded.errors.empty() ? std::string() : loaded.errors[0].format()));
  REQUIRE(loaded.scenario);
  const auto warning = warning_with(loaded, "attribute name written twice in <Controller>");
  CHECK(warning.line == line_of(catalog, "<Controller "));
  CHECK_THAT(warning.file, Catch::EndsWith("c.xosc"));
  CHECK(!lenient_load(dir, text.str(), true).errors.empty());
}
