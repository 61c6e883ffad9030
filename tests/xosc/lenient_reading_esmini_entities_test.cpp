// Rule breaks met in esmini's examples whose meaning is clear, read as meant with a located
// `(read as ...)` warning and refused under LoadOptions::strict: a swarm's central object written
// with its type's name <CentralSwarmObject> or without its offset, a Performance without one of its
// limits, esmini's misspelled <Axels> of <Axel> elements.

#include <catch2/catch.hpp>
#include <string>
#include <variant>

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

// A story whose one event starts a TrafficSwarmAction around Ego, its central object written
// as `central` (an element name).
std::string swarm_story(const std::string& central) {
  return "<Story name=\"S\">\n<Act name=\"Act\">\n<ManeuverGroup name=\"G\" "
         "maximumExecutionCount=\"1\">\n<Actors selectTriggeringEntities=\"false\"/>\n"
         "<Maneuver name=\"M\">\n<Event name=\"E\" priority=\"override\">\n<Action name=\"A\">"
         "<GlobalAction><TrafficAction><TrafficSwarmAction innerRadius=\"20\" "
         "numberOfVehicles=\"1\" offset=\"0\" semiMajorAxis=\"120\" semiMinorAxis=\"15\">\n<" +
         central +
         " entityRef=\"Ego\"/>\n</TrafficSwarmAction></TrafficAction></GlobalAction></Action>\n"
         "<StartTrigger><ConditionGroup><Condition name=\"C\" delay=\"0\" conditionEdge=\"none\">"
         "<ByValueCondition><SimulationTimeCondition value=\"1\" rule=\"greaterThan\"/>"
         "</ByValueCondition></Condition></ConditionGroup></StartTrigger>\n"
         "</Event>\n</Maneuver>\n</ManeuverGroup>\n</Act>\n</Story>\n";
}

const TrafficSwarmAction& only_swarm(const Loaded& loaded) {
  const auto& event =
      loaded.scenario->storyboard.stories[0].acts[0].maneuver_groups[0].maneuvers[0].events[0];
  return std::get<TrafficSwarmAction>(std::get<GlobalAction>(event.actions[0].action));
}

std::string performance_entities(const std::string& performance) {
  ScenarioText text;
  const std::string valid =
      "<Performance maxSpeed=\"69\" maxAcceleration=\"10\" maxDeceleration=\"10\"/>";
  std::string entities = text.entities;
  entities.replace(entities.find(valid), valid.size(), performance);
  return entities;
}

}  // namespace

TEST_CASE("a swarm's CentralSwarmObject is read as its CentralObject", "[xosc][lenient]") {
  // 1.0 and 1.3 both name the element CentralObject; CentralSwarmObject is its type's name.
  for (const std::string version : {"0", "3"}) {
    ScenarioText text;
    text.version = version;
    text.stories = swarm_story("CentralSwarmObject");
    const std::string xml = text.str();
    check_both_ways(xml, "<CentralSwarmObject> in <TrafficSwarmAction>",
                    line_of(xml, "<CentralSwarmObject"));
    corsa::test::TempDir dir;
    const Loaded loaded = lenient_load(dir, xml);
    REQUIRE(loaded.scenario);
    CHECK(only_swarm(loaded).central_object == "Ego");
  }
  ScenarioText valid;
  valid.stories = swarm_story("CentralObject");
  corsa::test::TempDir dir;
  const Loaded loaded = lenient_load(dir, valid.str(), true);
  REQUIRE(loaded.errors.empty());
  CHECK(only_swarm(loaded).central_object == "Ego");
  // Any other name is still an unknown element and leaves the required CentralObject missing.
  ScenarioText other;
  other.stories = swarm_story("CentralThing");
  CHECK(!lenient_load(dir, other.str()).errors.empty());
}

TEST_CASE("a swarm without offset is read as centred on its central object", "[xosc][lenient]") {
  ScenarioText text;
  text.version = "0";
  text.stories = swarm_story("CentralObject");
  const std::string with_offset = " offset=\"0\"";
  text.stories.erase(text.stories.find(with_offset), with_offset.size());
  const std::string xml = text.str();
  check_both_ways(xml, "<TrafficSwarmAction> without offset", line_of(xml, "<TrafficSwarmAction"));
  corsa::test::TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(loaded.scenario);
  CHECK(only_swarm(loaded).offset == 0.0);
  CHECK(only_swarm(loaded).semi_major_axis == 120.0);
}

TEST_CASE("a Performance without maxAcceleration is read as no limit given", "[xosc][lenient]") {
  ScenarioText text;
  text.version = "0";
  text.entities = performance_entities("<Performance maxSpeed=\"69\" maxDeceleration=\"30\"/>");
  const std::string xml = text.str();
  check_both_ways(xml, "<Performance> has no maxAcceleration", line_of(xml, "<Performance"));
  corsa::test::TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(loaded.scenario);
  const auto& vehicle = std::get<Vehicle>(loaded.scenario->entities.objects[0].object);
  CHECK(vehicle.performance.max_acceleration == 0.0);
  CHECK(vehicle.performance.max_deceleration == 30.0);
  CHECK(vehicle.performance.max_speed == 69.0);
}

TEST_CASE("esmini's Axels of Axel elements are read as Axles placed by their positionX",
          "[xosc][lenient]") {
  ScenarioText text;
  text.version = "0";
  const std::string axels =
      "<Axels>\n"
      "<Axel maxSteering=\"0\" positionX=\"0\" positionZ=\"0.4\" trackWidth=\"1.6\" "
      "wheelDiameter=\"0.7\"/>\n"
      "<Axel maxSteering=\"0.5\" positionX=\"2.98\" positionZ=\"0.4\" trackWidth=\"1.68\" "
      "wheelDiameter=\"0.8\"/>\n"
      "</Axels>\n";
  std::string entities = text.entities;
  const size_t begin = entities.find("<Axles>");
  const size_t end = entities.find("</Axles>\n") + std::string("</Axles>\n").size();
  entities.replace(begin, end - begin, axels);
  text.entities = entities;
  const std::string xml = text.str();
  check_both_ways(xml, "<Axels> of <Axel> elements is a misspelling of <Axles>",
                  line_of(xml, "<Axels>"));
  corsa::test::TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(loaded.scenario);
  const auto& axles = std::get<Vehicle>(loaded.scenario->entities.objects[0].object).axles;
  REQUIRE(axles.front_axle);
  CHECK(axles.front_axle->position_x == 2.98);
  CHECK(axles.front_axle->max_steering == 0.5);
  CHECK(axles.rear_axle.position_x == 0.0);
  CHECK(axles.rear_axle.track_width == 1.6);
  CHECK(axles.additional_axles.empty());
  // Only this misspelling: another spelling stays an unknown element (and Axles stays missing).
  ScenarioText other = text;
  other.entities.replace(other.entities.find("<Axels>"), 7, "<Axells>");
  other.entities.replace(other.entities.find("</Axels>"), 8, "</Axells>");
  CHECK(!lenient_load(dir, other.str()).errors.empty());
}

TEST_CASE("an environment catalog file named like the vehicle catalog is found by its directory",
          "[xosc][lenient]") {
  // esmini's EnvironmentCatalog.xosc calls itself VehicleCatalog: a second catalog of that name,
  // which the lookup by name skips, but the Environment directory's file still holds the entry.
  const auto catalog_file = [](const std::string& entry) {
    return "<?xml version=\"1.0\"?>\n<OpenSCENARIO>\n"
           "<FileHeader revMajor=\"1\" revMinor=\"3\" date=\"2024-01-01T00:00:00\" "
           "description=\"c\" author=\"corsa\"/>\n<Catalog name=\"VehicleCatalog\">\n" +
           entry + "</Catalog>\n</OpenSCENARIO>\n";
  };
  ScenarioText text;
  text.catalogs =
      "<VehicleCatalog><Directory path=\"veh\"/></VehicleCatalog>\n"
      "<EnvironmentCatalog><Directory path=\"env\"/></EnvironmentCatalog>\n";
  text.stories = corsa::test::story_with(
      "<Event name=\"E\" priority=\"override\">\n<Action name=\"A\"><GlobalAction>"
      "<EnvironmentAction>\n<CatalogReference catalogName=\"EnvironmentCatalog\" "
      "entryName=\"winter\"/>\n</EnvironmentAction></GlobalAction></Action>\n</Event>\n");
  const std::string xml = text.str();
  corsa::test::TempDir dir;
  corsa::test::write_text(dir.path() / "veh" / "VehicleCatalog.xosc",
                          catalog_file("<Controller name=\"unused\"/>\n"));
  corsa::test::write_text(
      dir.path() / "env" / "EnvironmentCatalog.xosc",
      catalog_file("<Environment name=\"winter\">\n<TimeOfDay animation=\"false\" "
                   "dateTime=\"2024-01-01T12:00:00\"/>\n<Weather/>\n"
                   "<RoadCondition frictionScaleFactor=\"0.4\"/>\n</Environment>\n"));
  const Loaded lenient = lenient_load(dir, xml);
  INFO((lenient.errors.empty() ? std::string() : lenient.errors[0].format()));
  REQUIRE(lenient.errors.empty());
  const auto warning =
      warning_with(lenient, "no catalog file declares catalog 'EnvironmentCatalog'");
  CHECK(warning.line == line_of(xml, "<CatalogReference"));
  CHECK_THAT(warning.message, Catch::Contains("EnvironmentCatalog.xosc"));
  const auto& event =
      lenient.scenario->storyboard.stories[0].acts[0].maneuver_groups[0].maneuvers[0].events[0];
  const auto& environment =
      std::get<EnvironmentAction>(std::get<GlobalAction>(event.actions[0].action)).environment;
  CHECK(environment.name == "winter");
  const Loaded strict = lenient_load(dir, xml, true);
  REQUIRE(!strict.errors.empty());
  CHECK_THAT(strict.errors[0].message, Catch::Contains("no catalog file declares catalog"));
}
