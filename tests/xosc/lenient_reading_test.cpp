// Files that break a rule of the standard in a way whose meaning is clear are read as their
// authors meant, with a located `(read as ...)` warning; with LoadOptions::strict the same
// files are refused with the same text as an error.

#include <catch2/catch.hpp>
#include <string>

#include "corsa/xosc/scenario.h"
#include "lenient_load.h"
#include "scenario_text.h"
#include "temp_dir.h"

using namespace corsa::xosc;
using corsa::test::check_both_ways;
using corsa::test::line_of;
using corsa::test::Loaded;
using corsa::test::ScenarioText;
using corsa::test::warning_with;

TEST_CASE("a string parameter holding a number is read as that number in an expression",
          "[xosc][lenient]") {
  ScenarioText text;
  text.parameters = "<ParameterDeclaration name=\"Lane\" parameterType=\"string\" value=\"-1\"/>\n";
  text.init =
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><TeleportAction><Position>"
      "<WorldPosition x=\"${$Lane * 3.5}\" y=\"0\" h=\"0\"/></Position></TeleportAction>"
      "</PrivateAction>\n</Private>\n";
  const std::string xml = text.str();
  const Loaded loaded = check_both_ways(
      xml, "string parameter '$Lane' = '-1' used in an expression", line_of(xml, "WorldPosition"));
  const auto& teleport =
      std::get<TeleportAction>(loaded.scenario->storyboard.init.privates[0].actions[0]);
  CHECK(std::get<WorldPosition>(teleport.position.kind).x == -3.5);
}

TEST_CASE("the constant pi in an expression is read as pi", "[xosc][lenient]") {
  ScenarioText text;
  text.init =
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><TeleportAction><Position>"
      "<WorldPosition x=\"0\" y=\"0\" h=\"${pi / 2}\"/></Position></TeleportAction>"
      "</PrivateAction>\n</Private>\n";
  const std::string xml = text.str();
  const Loaded loaded = check_both_ways(xml, "constant 'pi' in expression '${pi / 2}'",
                                        line_of(xml, "WorldPosition"));
  const auto& teleport =
      std::get<TeleportAction>(loaded.scenario->storyboard.init.privates[0].actions[0]);
  CHECK(*std::get<WorldPosition>(teleport.position.kind).h == 1.5707963267948966);
}

TEST_CASE("ordering rules on string parameters holding numbers compare the numbers",
          "[xosc][lenient]") {
  ScenarioText text;
  text.parameters =
      "<ParameterDeclaration name=\"LaneId\" parameterType=\"string\" value=\"-4\">\n"
      "<ConstraintGroup><ValueConstraint rule=\"lessOrEqual\" value=\"-3\"/>\n"
      "<ValueConstraint rule=\"greaterOrEqual\" value=\"-5\"/></ConstraintGroup>\n"
      "</ParameterDeclaration>\n";
  const std::string xml = text.str();
  check_both_ways(xml, "rule lessOrEqual on string parameter 'LaneId'",
                  line_of(xml, "rule=\"lessOrEqual\""));
  // As text, "-4" <= "-3" happens to hold too, but "-4" >= "-5" does not: the numbers decide.
  ScenarioText out_of_range = text;
  out_of_range.parameters =
      "<ParameterDeclaration name=\"LaneId\" parameterType=\"string\" value=\"-6\">\n"
      "<ConstraintGroup><ValueConstraint rule=\"greaterOrEqual\" value=\"-5\"/>"
      "</ConstraintGroup>\n</ParameterDeclaration>\n";
  corsa::test::TempDir dir;
  const Loaded loaded = corsa::test::lenient_load(dir, out_of_range.str());
  REQUIRE(loaded.errors.size() == 1);
  CHECK(loaded.errors[0].message == "parameter 'LaneId' = '-6' violates its value constraints");
}

TEST_CASE("dateTime constraints compare instants across time zones", "[xosc][lenient]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  // 11:00+04:00 and 10:00+03:00 are the same instant (07:00Z): notEqualTo fails, equalTo holds.
  text.parameters =
      "<ParameterDeclaration name=\"Same\" parameterType=\"dateTime\" "
      "value=\"2021-07-09T11:00:00.34+04:00\">\n"
      "<ConstraintGroup><ValueConstraint rule=\"equalTo\" "
      "value=\"2021-07-09T10:00:00.34+03:00\"/></ConstraintGroup>\n</ParameterDeclaration>\n"
      "<ParameterDeclaration name=\"Later\" parameterType=\"dateTime\" "
      "value=\"2021-07-09T10:00:00Z\">\n"
      "<ConstraintGroup><ValueConstraint rule=\"greaterThan\" "
      "value=\"2021-07-09T11:30:00+02:00\"/></ConstraintGroup>\n</ParameterDeclaration>\n";
  const Loaded loaded = corsa::test::lenient_load(dir, text.str());
  CHECK(loaded.errors.empty());
  CHECK(date_time_instant("1970-01-02T00:00:00Z") == 86400.0);
  CHECK(date_time_instant("1970-01-01T01:00:00+01:00") == 0.0);
}

TEST_CASE("an int written with a zero fraction is read as that int", "[xosc][lenient]") {
  ScenarioText text;
  text.parameters = "<ParameterDeclaration name=\"N\" parameterType=\"int\" value=\"-5.0\"/>\n";
  const std::string xml = text.str();
  const Loaded loaded =
      check_both_ways(xml, "parameter 'N': '-5.0' is not an int", line_of(xml, "name=\"N\""));
  CHECK(std::get<int64_t>(loaded.scenario->parameters[0].value.data) == -5);
  // 2.5 is no int at all.
  text.parameters = "<ParameterDeclaration name=\"N\" parameterType=\"int\" value=\"2.5\"/>\n";
  corsa::test::TempDir dir;
  CHECK(corsa::test::lenient_load(dir, text.str()).errors.size() == 1);
}

TEST_CASE("a parameter declared with a leading $ is the name without it", "[xosc][lenient]") {
  ScenarioText text;
  text.parameters =
      "<ParameterDeclaration name=\"$Who\" parameterType=\"string\" value=\"Ego\"/>\n";
  text.init =
      "<Private entityRef=\"$Who\">\n"
      "<PrivateAction><TeleportAction><Position>"
      "<WorldPosition x=\"0\" y=\"0\" h=\"0\"/></Position></TeleportAction></PrivateAction>\n"
      "</Private>\n";
  const std::string xml = text.str();
  check_both_ways(xml, "parameter name '$Who' starts with '$'", line_of(xml, "name=\"$Who\""));
}

TEST_CASE("a repeated parameter declaration is read as the later one", "[xosc][lenient]") {
  ScenarioText text;
  text.parameters =
      "<ParameterDeclaration name=\"V\" parameterType=\"double\" value=\"1\"/>\n"
      "<ParameterDeclaration name=\"V\" parameterType=\"double\" value=\"2\"/>\n";
  const std::string xml = text.str();
  const Loaded loaded =
      check_both_ways(xml, "parameter 'V' is declared twice", line_of(xml, "value=\"2\""));
  REQUIRE(loaded.scenario->parameters.size() == 1);
  CHECK(std::get<double>(loaded.scenario->parameters[0].value.data) == 2.0);
}

TEST_CASE("a negative transition dynamics value is read as its magnitude", "[xosc][lenient]") {
  ScenarioText text;
  text.init =
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><LongitudinalAction><SpeedAction>\n"
      "<SpeedActionDynamics dynamicsShape=\"linear\" dynamicsDimension=\"rate\" value=\"-4\"/>\n"
      "<SpeedActionTarget><AbsoluteTargetSpeed value=\"0\"/></SpeedActionTarget>"
      "</SpeedAction></LongitudinalAction></PrivateAction>\n</Private>\n";
  const std::string xml = text.str();
  const Loaded loaded = check_both_ways(xml, "transition dynamics value -4 is negative",
                                        line_of(xml, "value=\"-4\""));
  const auto& speed =
      std::get<SpeedAction>(loaded.scenario->storyboard.init.privates[0].actions[0]);
  CHECK(speed.dynamics.value == 4.0);
}

TEST_CASE("an empty StartTrigger is read as none, an empty StopTrigger never fires",
          "[xosc][lenient]") {
  ScenarioText text;
  text.stories = corsa::test::story_with(
      "<Event name=\"E\" priority=\"override\">\n"
      "<Action name=\"Go\"><PrivateAction><LongitudinalAction><SpeedAction>"
      "<SpeedActionDynamics dynamicsShape=\"step\" dynamicsDimension=\"time\" value=\"0\"/>"
      "<SpeedActionTarget><AbsoluteTargetSpeed value=\"5\"/></SpeedActionTarget></SpeedAction>"
      "</LongitudinalAction></PrivateAction></Action>\n"
      "<StartTrigger/>\n</Event>\n");
  const std::string xml = text.str();
  const Loaded loaded =
      check_both_ways(xml, "empty <StartTrigger/>", line_of(xml, "<StartTrigger/>"));
  const auto& event =
      loaded.scenario->storyboard.stories[0].acts[0].maneuver_groups[0].maneuvers[0].events[0];
  CHECK(!event.start_trigger);
}

TEST_CASE("an empty trailer entityRef is no trailer", "[xosc][lenient]") {
  ScenarioText text;
  text.parameters = "<ParameterDeclaration name=\"T\" parameterType=\"string\" value=\"\"/>\n";
  const std::string vehicle_end = "</Axles>\n";
  text.entities.replace(text.entities.find(vehicle_end), vehicle_end.size(),
                        vehicle_end + "<Trailer><TrailerRef entityRef=\"$T\"/></Trailer>\n");
  const std::string xml = text.str();
  const Loaded loaded =
      check_both_ways(xml, "the trailer's entityRef is empty", line_of(xml, "entityRef=\"$T\""));
  CHECK(!std::get<Vehicle>(loaded.scenario->entities.objects[0].object).trailer);
}

TEST_CASE("a name attribute that is no expression is the literal name", "[xosc][lenient]") {
  ScenarioText text;
  text.stories = corsa::test::story_with(corsa::test::speed_event("Go"), "${Ego overtakes}");
  const std::string xml = text.str();
  check_both_ways(xml, "name '${Ego overtakes}' is not an expression",
                  line_of(xml, "<Story name="));
  corsa::test::TempDir dir;
  CHECK(corsa::test::lenient_load(dir, xml).scenario->storyboard.stories[0].name ==
        "${Ego overtakes}");
}

TEST_CASE("an OpenSCENARIO 0.9 header is an old file, not a newer one", "[xosc][lenient]") {
  ScenarioText text;
  std::string xml = text.str();
  xml.replace(xml.find("revMajor=\"1\" revMinor=\"3\""), 25, "revMajor=\"0\" revMinor=\"9\"");
  check_both_ways(xml, "OpenSCENARIO 0.9 is older than 1.0", line_of(xml, "<FileHeader"));
}

TEST_CASE("an ambiguous storyboard reference resolves to the element nearest to it",
          "[xosc][lenient]") {
  // Two stories with the same inner names, as when one maneuver is instantiated twice: each
  // event refers to "First", meaning the one in its own maneuver.
  ScenarioText text;
  const auto events = [](const std::string& story) {
    return corsa::test::speed_event("First") +
           corsa::test::speed_event("Second", "20",
                                    corsa::test::state_condition("event", "First")) +
           "<!-- " + story + " -->\n";
  };
  text.stories =
      corsa::test::story_with(events("S1"), "S1") + corsa::test::story_with(events("S2"), "S2");
  const std::string xml = text.str();
  const Loaded loaded = check_both_ways(xml, "the event name 'First' is not unique",
                                        line_of(xml, "storyboardElementRef=\"First\""));
  const auto resolved = [&](size_t story) {
    const auto& event = loaded.scenario->storyboard.stories[story]
                            .acts[0]
                            .maneuver_groups[0]
                            .maneuvers[0]
                            .events[1];
    return std::get<StoryboardElementStateCondition>(
               std::get<ByValueCondition>(event.start_trigger->groups[0].conditions[0].kind))
        .resolved_path;
  };
  CHECK(resolved(0) == "S1::A::G::M::First");
  CHECK(resolved(1) == "S2::A::G::M::First");
}

TEST_CASE("a step transition without dimension or value is read as a step at once",
          "[xosc][lenient]") {
  ScenarioText text;
  text.init =
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><LongitudinalAction><SpeedAction>\n"
      "<SpeedActionDynamics dynamicsShape=\"step\"/>\n"
      "<SpeedActionTarget><AbsoluteTargetSpeed value=\"20\"/></SpeedActionTarget>"
      "</SpeedAction></LongitudinalAction></PrivateAction>\n</Private>\n";
  const std::string xml = text.str();
  const Loaded loaded =
      check_both_ways(xml, "step transition dynamics without dynamicsDimension and value",
                      line_of(xml, "dynamicsShape=\"step\""));
  const auto& speed =
      std::get<SpeedAction>(loaded.scenario->storyboard.init.privates[0].actions[0]);
  CHECK(speed.dynamics.shape == DynamicsShape::kStep);
  CHECK(speed.dynamics.dimension == DynamicsDimension::kTime);
  CHECK(speed.dynamics.value == 0.0);

  // Only the value missing names only the value.
  std::string no_value = xml;
  no_value.replace(no_value.find("dynamicsShape=\"step\""), 20,
                   "dynamicsShape=\"step\" dynamicsDimension=\"rate\"");
  check_both_ways(no_value, "step transition dynamics without value",
                  line_of(no_value, "dynamicsShape=\"step\""));
}

TEST_CASE("a linear transition without its value stays an error", "[xosc][lenient]") {
  ScenarioText text;
  text.init =
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><LongitudinalAction><SpeedAction>\n"
      "<SpeedActionDynamics dynamicsShape=\"linear\" dynamicsDimension=\"rate\"/>\n"
      "<SpeedActionTarget><AbsoluteTargetSpeed value=\"20\"/></SpeedActionTarget>"
      "</SpeedAction></LongitudinalAction></PrivateAction>\n</Private>\n";
  const std::string xml = text.str();
  corsa::test::TempDir dir;
  const Loaded loaded = corsa::test::lenient_load(dir, xml);
  REQUIRE(loaded.errors.size() == 1);
  CHECK(loaded.errors[0].line == line_of(xml, "dynamicsShape=\"linear\""));
  CHECK_THAT(loaded.errors[0].message, Catch::Contains("needs the attribute value"));
}

TEST_CASE("a condition without conditionEdge is read as edge none", "[xosc][lenient]") {
  ScenarioText text;
  text.stories = corsa::test::story_with(corsa::test::speed_event(
      "Go", "10",
      "<ConditionGroup><Condition name=\"C\" delay=\"0\"><ByValueCondition>"
      "<SimulationTimeCondition value=\"1\" rule=\"greaterThan\"/></ByValueCondition>"
      "</Condition></ConditionGroup>\n"));
  const std::string xml = text.str();
  const Loaded loaded =
      check_both_ways(xml, "<Condition> without conditionEdge", line_of(xml, "<Condition name"));
  const auto& event =
      loaded.scenario->storyboard.stories[0].acts[0].maneuver_groups[0].maneuvers[0].events[0];
  CHECK(event.start_trigger->groups[0].conditions[0].edge == ConditionEdge::kNone);
}

TEST_CASE("the draft attribute edge of a condition is read as conditionEdge", "[xosc][lenient]") {
  const std::string condition =
      "<ConditionGroup><Condition name=\"C\" delay=\"0\" edge=\"rising\"><ByValueCondition>"
      "<SimulationTimeCondition value=\"1\" rule=\"greaterThan\"/></ByValueCondition>"
      "</Condition></ConditionGroup>\n";
  ScenarioText text;
  text.stories = corsa::test::story_with(corsa::test::speed_event("Go", "10", condition));
  const std::string xml = text.str();
  const Loaded loaded =
      check_both_ways(xml, "attribute 'edge' of <Condition>", line_of(xml, "<Condition name"));
  CHECK(loaded.warnings.size() == 1);  // no "unknown attribute" besides the reading
  const auto& event =
      loaded.scenario->storyboard.stories[0].acts[0].maneuver_groups[0].maneuvers[0].events[0];
  CHECK(event.start_trigger->groups[0].conditions[0].edge == ConditionEdge::kRising);

  // Both spellings at once say the edge twice: an error.
  std::string both = xml;
  both.replace(both.find("edge=\"rising\""), 13, "edge=\"rising\" conditionEdge=\"none\"");
  corsa::test::TempDir dir;
  const Loaded twice = corsa::test::lenient_load(dir, both);
  REQUIRE(twice.errors.size() == 1);
  CHECK_THAT(twice.errors[0].message, Catch::Contains("'edge' and 'conditionEdge' together"));
}

TEST_CASE("a capitalised boolean is read as its lower-case value", "[xosc][lenient]") {
  ScenarioText text;
  text.stories = corsa::test::story_with(corsa::test::speed_event("Go"));
  std::string xml = text.str();
  xml.replace(xml.find("selectTriggeringEntities=\"false\""), 32,
              "selectTriggeringEntities=\"True\"");
  check_both_ways(xml, "attribute selectTriggeringEntities: 'True' is not lower case",
                  line_of(xml, "<Actors"));
  corsa::test::TempDir dir;
  CHECK(corsa::test::lenient_load(dir, xml)
            .scenario->storyboard.stories[0]
            .acts[0]
            .maneuver_groups[0]
            .actors.select_triggering_entities);
  // esmini's reader (`--semantics esmini`): true only for the text `true` or `1`.
  const Loaded esmini = corsa::test::lenient_load(dir, xml, false, true);
  CHECK_FALSE(esmini.scenario->storyboard.stories[0]
                  .acts[0]
                  .maneuver_groups[0]
                  .actors.select_triggering_entities);
  CHECK_THAT(warning_with(esmini, "'True' is not lower case").message,
             Catch::Contains("(read as false, as esmini reads it)"));
  std::string wrong = xml;
  wrong.replace(wrong.find("\"True\""), 6, "\"no\"");
  const Loaded refused = corsa::test::lenient_load(dir, wrong);
  REQUIRE(refused.errors.size() == 1);
  CHECK_THAT(refused.errors[0].message, Catch::Contains("is not a boolean"));
}

TEST_CASE("an empty Storyboard StopTrigger lets a run with stories end with its stories",
          "[xosc]") {
  ScenarioText text;
  text.stories = corsa::test::story_with(corsa::test::speed_event("Go"));
  std::string xml = text.str();
  xml.replace(xml.find("</Storyboard>"), 13, "<StopTrigger/>\n</Storyboard>");
  corsa::test::TempDir dir;
  const Loaded loaded = corsa::test::lenient_load(dir, xml);
  REQUIRE(loaded.errors.empty());
  CHECK(!loaded.scenario->storyboard.stop_trigger);
  CHECK(loaded.warnings.empty());  // valid 1.0 form: no reading needed

  // Without stories it is kept, so a traffic-only run goes on until its duration.
  ScenarioText traffic;
  std::string bare = traffic.str();
  bare.replace(bare.find("</Storyboard>"), 13, "<StopTrigger/>\n</Storyboard>");
  const Loaded kept = corsa::test::lenient_load(dir, bare);
  REQUIRE(kept.scenario);
  REQUIRE(kept.scenario->storyboard.stop_trigger);
  CHECK(kept.scenario->storyboard.stop_trigger->groups.empty());
}

TEST_CASE("an OpenSCENARIO 0.9 element names its 1.0 replacement", "[xosc]") {
  ScenarioText text;
  std::string xml = text.str();
  xml.replace(xml.find("<CatalogLocations>"), 18, "<Catalogs>");
  xml.replace(xml.find("</CatalogLocations>"), 19, "</Catalogs>");
  corsa::test::TempDir dir;
  const Loaded loaded = corsa::test::lenient_load(dir, xml);
  REQUIRE(!loaded.errors.empty());
  CHECK(loaded.errors[0].line == line_of(xml, "<Catalogs>"));
  CHECK_THAT(loaded.errors[0].message, Catch::Contains("<Catalogs> is OpenSCENARIO 0.9") &&
                                           Catch::Contains("replaced with <CatalogLocations>"));
}

TEST_CASE("a catalog entry using a parameter only the scenario declares reads the scenario's",
          "[xosc][lenient]") {
  const std::string catalog =
      "<?xml version=\"1.0\"?>\n<OpenSCENARIO>\n"
      "<FileHeader revMajor=\"1\" revMinor=\"3\" date=\"2024-01-01T00:00:00\" "
      "description=\"c\" author=\"corsa\"/>\n"
      "<Catalog name=\"Moves\">\n<Maneuver name=\"Speed\">\n" +
      corsa::test::speed_event("Go", "$Target") + "</Maneuver>\n</Catalog>\n</OpenSCENARIO>\n";
  ScenarioText text;
  text.parameters =
      "<ParameterDeclaration name=\"Target\" parameterType=\"double\" value=\"12\"/>\n";
  text.catalogs = "<ManeuverCatalog><Directory path=\"cat\"/></ManeuverCatalog>\n";
  text.stories =
      "<Story name=\"S\">\n<Act name=\"A\">\n"
      "<ManeuverGroup name=\"G\" maximumExecutionCount=\"1\">\n"
      "<Actors selectTriggeringEntities=\"false\"><EntityRef entityRef=\"Ego\"/></Actors>\n"
      "<CatalogReference catalogName=\"Moves\" entryName=\"Speed\"/>\n"
      "</ManeuverGroup>\n</Act>\n</Story>\n";
  const std::string xml = text.str();
  corsa::test::TempDir dir;
  corsa::test::write_text(dir.path() / "cat" / "moves.xosc", catalog);
  const Loaded lenient = corsa::test::lenient_load(dir, xml);
  INFO((lenient.errors.empty() ? std::string() : lenient.errors[0].format()));
  REQUIRE(lenient.errors.empty());
  const auto warning = warning_with(lenient, "parameter '$Target' is not declared in its catalog");
  CHECK(warning.line == line_of(catalog, "AbsoluteTargetSpeed"));
  CHECK_THAT(warning.message, Catch::Contains("(read as the scenario's global parameter, '12')"));
  const auto& action = lenient.scenario->storyboard.stories[0]
                           .acts[0]
                           .maneuver_groups[0]
                           .maneuvers[0]
                           .events[0]
                           .actions[0];
  const auto& speed = std::get<SpeedAction>(std::get<PrivateAction>(action.action));
  CHECK(std::get<AbsoluteTargetSpeed>(speed.target).value == 12.0);
  const Loaded strict = corsa::test::lenient_load(dir, xml, true);
  REQUIRE(!strict.errors.empty());
  CHECK_THAT(strict.errors[0].message, Catch::Contains("not declared in its catalog entry"));

  // A name the scenario does not declare either stays undefined.
  std::string undeclared = xml;
  undeclared.replace(undeclared.find("name=\"Target\""), 13, "name=\"Other\"");
  const Loaded refused = corsa::test::lenient_load(dir, undeclared);
  REQUIRE(!refused.errors.empty());
  CHECK_THAT(refused.errors[0].message, Catch::Contains("undefined parameter '$Target'"));
}

TEST_CASE("a relative object position without dx or dy is read as no offset", "[xosc][lenient]") {
  ScenarioText text;
  text.init +=
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><TeleportAction><Position>\n"
      "<RelativeObjectPosition entityRef=\"Ego\" dy=\"2\"/>\n"
      "</Position></TeleportAction></PrivateAction>\n</Private>\n";
  const std::string xml = text.str();
  const Loaded loaded = check_both_ways(xml, "<RelativeObjectPosition> without dx",
                                        line_of(xml, "<RelativeObjectPosition"));
  const auto& teleport =
      std::get<TeleportAction>(loaded.scenario->storyboard.init.privates[1].actions[0]);
  const auto& relative = std::get<RelativeObjectPosition>(teleport.position.kind);
  CHECK(relative.dx == 0.0);
  CHECK(relative.dy == 2.0);
}

TEST_CASE("a VisibilityAction flag left out leaves that visibility unchanged", "[xosc][lenient]") {
  ScenarioText text;
  text.init +=
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><VisibilityAction sensors=\"false\"/></PrivateAction>\n</Private>\n";
  const std::string xml = text.str();
  const Loaded loaded = check_both_ways(xml, "<VisibilityAction> without graphics",
                                        line_of(xml, "<VisibilityAction"));
  const auto& visibility =
      std::get<VisibilityAction>(loaded.scenario->storyboard.init.privates[1].actions[0]);
  CHECK(visibility.sensors == std::optional<bool>(false));
  CHECK(!visibility.graphics);
  CHECK(!visibility.traffic);
}
