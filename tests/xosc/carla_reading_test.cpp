// The readings of CARLA scenario_runner's scenario forms (docs/openscenario.md, "Published
// scenarios"): a town name as LogicFile, "criteria_" conditions, and the 0.9 forms its 0.9
// examples use (Global SetEnvironment, StandStill, TraveledDistance, ByValue Parameter,
// EndConditions, PedestrianControllerCatalog, a Vehicle's ParameterDeclaration).

#include <catch2/catch.hpp>

#include "lenient_load.h"
#include "osc09_draft.h"

namespace corsa::test {
namespace {

std::string criterion(const std::string& name, const std::string& ref) {
  return "<Condition name=\"" + name +
         "\" delay=\"0\" conditionEdge=\"rising\">\n"
         "<ByValueCondition><ParameterCondition parameterRef=\"" +
         ref + "\" value=\"100\" rule=\"lessThan\"/></ByValueCondition>\n</Condition>\n";
}

const std::string kLate =
    "<Condition name=\"Late\" delay=\"0\" conditionEdge=\"rising\">\n<ByValueCondition>"
    "<SimulationTimeCondition value=\"5\" rule=\"greaterThan\"/></ByValueCondition>\n"
    "</Condition>\n";

// The first error of loading `xml` stands at the line of `at` and says `text`.
void check_first_error(const std::string& xml, const std::string& at, const std::string& text) {
  TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(!loaded.errors.empty());
  CHECK(loaded.errors[0].line == line_of(xml, at));
  CHECK_THAT(loaded.errors[0].message, Catch::Contains(text));
}

TEST_CASE("a LogicFile naming a CARLA town without extension is read as the town's .xodr",
          "[xosc][lenient][carla]") {
  ScenarioText text;
  text.road = "<LogicFile filepath=\"map\"/>";
  const std::string xml = text.str();
  check_both_ways(xml, "map file 'map' has no extension and names no file",
                  line_of(xml, "<LogicFile"));
  const auto scenario = load_with_warning(xml, "map file 'map' has no extension");
  CHECK(scenario.road_network.logic_file_path.filename() == "map.xodr");
}

TEST_CASE("a town name with no .xodr beside it stays a located error", "[xosc][carla]") {
  ScenarioText text;
  text.road = "<LogicFile filepath=\"Town99\"/>";
  check_first_error(text.str(), "<LogicFile", "map file 'Town99' not found");
}

TEST_CASE("CARLA's criteria conditions never hold: their groups are left out",
          "[xosc][lenient][carla]") {
  ScenarioText text;
  text.stop = "<ConditionGroup>\n" + criterion("criteria_CollisionTest", "") +
              "</ConditionGroup>\n<ConditionGroup>\n" + kLate +
              criterion("criteria_DrivenDistanceTest", "distance_success") +
              "</ConditionGroup>\n<ConditionGroup>\n" + kLate + "</ConditionGroup>\n";
  const std::string xml = text.str();
  // One warning for the file, at the first, naming the count; a note at each.
  check_both_ways(xml, "2 conditions are CARLA evaluation criteria",
                  line_of(xml, "criteria_CollisionTest"));
  TempDir dir;
  corsa::Diagnostics diagnostics;
  write_text(dir.path() / "map.xodr", minimal_xodr());
  write_text(dir.path() / "s.xosc", xml);
  const auto scenario = xosc::load_scenario(dir.path() / "s.xosc", {}, diagnostics);
  size_t warnings = 0;
  std::vector<int> notes;
  for (const auto& diagnostic : diagnostics.all()) {
    if (diagnostic.message.find("CARLA") == std::string::npos) continue;
    if (diagnostic.severity == corsa::Severity::kWarning) ++warnings;
    if (diagnostic.severity == corsa::Severity::kNote) notes.push_back(diagnostic.line);
  }
  CHECK(warnings == 1);
  CHECK(notes == std::vector<int>{line_of(xml, "criteria_CollisionTest"),
                                  line_of(xml, "criteria_DrivenDistanceTest")});
  // Only the third group, without a criterion, is left.
  const auto& stop = scenario.storyboard.stop_trigger;
  REQUIRE(stop.has_value());
  REQUIRE(stop->groups.size() == 1);
  REQUIRE(stop->groups[0].conditions.size() == 1);
  CHECK(stop->groups[0].conditions[0].name == "Late");
}

TEST_CASE("an undeclared parameter outside a criteria condition stays an error", "[xosc][carla]") {
  ScenarioText text;
  text.stop = "<ConditionGroup>\n" + criterion("Collision", "") + "</ConditionGroup>\n";
  check_first_error(text.str(), "<ParameterCondition", "undefined parameter ''");
}

TEST_CASE("a criteria condition on a declared parameter is an ordinary condition",
          "[xosc][carla]") {
  ScenarioText text;
  text.parameters = "<ParameterDeclaration name=\"d\" parameterType=\"double\" value=\"1\"/>\n";
  text.stop = "<ConditionGroup>\n" + criterion("criteria_D", "d") + "</ConditionGroup>\n";
  const Loaded loaded = load_without_errors(text.str());
  CHECK(loaded.scenario->storyboard.stop_trigger->groups.size() == 1);
  for (const auto& warning : loaded.warnings) {
    CHECK(warning.message.find("CARLA") == std::string::npos);
  }
}

// osc09_draft() in the forms of CARLA's 0.9 examples.
std::string carla_draft() {
  std::string xml = osc09_draft();
  replace_once(xml, "<Catalogs>\n<RouteCatalog>\n</RouteCatalog>\n</Catalogs>",
               "<Catalogs>\n<DriverCatalog>\n<Directory path=\"Drivers\"/>\n</DriverCatalog>\n"
               "<PedestrianControllerCatalog>\n<Directory path=\"Walkers\"/>\n"
               "</PedestrianControllerCatalog>\n</Catalogs>");
  replace_once(xml, "<Vehicle name=\"car\" vehicleCategory=\"car\">\n",
               "<Vehicle name=\"car\" vehicleCategory=\"car\">\n<ParameterDeclaration/>\n");
  replace_once(xml, "<Actions>\n<Private object=\"Ego\">",
               "<Actions>\n<Global>\n<SetEnvironment>\n<Environment name=\"E\">\n"
               "<TimeOfDay animation=\"false\">\n<Time hour=\"9\" min=\"5\" sec=\"7.0\"/>\n"
               "<Date day=\"25\" month=\"6\" year=\"2019\"/>\n</TimeOfDay>\n"
               "<Weather cloudState=\"free\">\n<Precipitation type=\"rain\" intensity=\"0.5\"/>\n"
               "</Weather>\n<RoadCondition frictionScale=\"0.8\"/>\n</Environment>\n"
               "</SetEnvironment>\n</Global>\n<Private object=\"Ego\">");
  replace_once(xml, "<AtStart type=\"act\" name=\"A\"/>\n</ByState>",
               "<AtStart type=\"act\" name=\"A\"/>\n</ByState>\n</Condition>\n"
               "<Condition name=\"Still\" delay=\"0\" edge=\"rising\">\n<ByEntity>\n"
               "<TriggeringEntities rule=\"any\">\n<Entity name=\"Ego\"/>\n</TriggeringEntities>\n"
               "<EntityCondition>\n<StandStill duration=\"2\"/>\n</EntityCondition>\n</ByEntity>");
  replace_once(xml, "<End>\n</End>",
               "<EndConditions>\n<ConditionGroup>\n"
               "<Condition name=\"Far\" delay=\"0\" edge=\"rising\">\n<ByEntity>\n"
               "<TriggeringEntities rule=\"any\">\n<Entity name=\"Ego\"/>\n</TriggeringEntities>\n"
               "<EntityCondition>\n<TraveledDistance value=\"200\"/>\n</EntityCondition>\n"
               "</ByEntity>\n</Condition>\n</ConditionGroup>\n<ConditionGroup>\n"
               "<Condition name=\"Fast\" delay=\"0\" edge=\"rising\">\n<ByValue>\n"
               "<Parameter name=\"$Speed\" value=\"30\" rule=\"greater_than\"/>\n</ByValue>\n"
               "</Condition>\n</ConditionGroup>\n</EndConditions>");
  return xml;
}

TEST_CASE("CARLA's 0.9 forms are read as 1.0", "[xosc][osc09][carla]") {
  const std::string xml = carla_draft();
  const Loaded loaded = load_without_errors(xml);
  const auto& scenario = *loaded.scenario;
  const auto header = warning_with(loaded, "OpenSCENARIO 0.9 draft");
  CHECK_THAT(header.message,
             Catch::Contains("SetEnvironment") && Catch::Contains("TimeOfDay Time/Date") &&
                 Catch::Contains("StandStill") && Catch::Contains("TraveledDistance"));
  // One ControllerCatalog: the DriverCatalog's, the other warned at its line.
  REQUIRE(scenario.catalog_locations.controller.has_value());
  CHECK(scenario.catalog_locations.controller->path == "Drivers");
  const auto second = warning_with(loaded, "<PedestrianControllerCatalog> beside <DriverCatalog>");
  CHECK(second.line == line_of(xml, "<PedestrianControllerCatalog"));
  // The environment.
  REQUIRE(scenario.storyboard.init.global_actions.size() == 1);
  const auto* action =
      std::get_if<xosc::EnvironmentAction>(&scenario.storyboard.init.global_actions[0]);
  REQUIRE(action != nullptr);
  const auto& environment = action->environment;
  REQUIRE(environment.time_of_day.has_value());
  CHECK(environment.time_of_day->date_time == "2019-06-25T09:05:07");
  REQUIRE(environment.weather.has_value());
  REQUIRE(environment.weather->precipitation.has_value());
  CHECK(environment.weather->precipitation->type == xosc::PrecipitationType::kRain);
  REQUIRE(environment.road_condition.has_value());
  CHECK(environment.road_condition->friction_scale_factor == 0.8);
  // The conditions.
  const auto& start = first_event(scenario).start_trigger;
  REQUIRE(start.has_value());
  REQUIRE(start->groups.at(0).conditions.size() == 2);
  const auto& still = std::get<xosc::ByEntityCondition>(start->groups[0].conditions[1].kind);
  REQUIRE(std::holds_alternative<xosc::StandStillCondition>(still.condition));
  CHECK(std::get<xosc::StandStillCondition>(still.condition).duration == 2.0);
  const auto& stop = scenario.storyboard.stop_trigger;
  REQUIRE(stop.has_value());
  REQUIRE(stop->groups.size() == 2);
  const auto& far = std::get<xosc::ByEntityCondition>(stop->groups[0].conditions.at(0).kind);
  REQUIRE(std::holds_alternative<xosc::TraveledDistanceCondition>(far.condition));
  CHECK(std::get<xosc::TraveledDistanceCondition>(far.condition).value == 200.0);
  const auto& fast = std::get<xosc::ByValueCondition>(stop->groups[1].conditions.at(0).kind);
  const auto* parameter = std::get_if<xosc::ParameterCondition>(&fast);
  REQUIRE(parameter != nullptr);
  CHECK(parameter->parameter_ref == "Speed");
  CHECK(parameter->rule == xosc::Rule::kGreaterThan);
  // EndConditions is the 0.9.1 schema's own name: no warning of its own.
  for (const auto& warning : loaded.warnings) {
    CHECK(warning.message.find("<EndConditions>") == std::string::npos);
  }
}

TEST_CASE("CARLA's 0.9 forms are errors under --strict", "[xosc][osc09][carla]") {
  const std::string xml = carla_draft();
  TempDir dir;
  const Loaded strict = lenient_load(dir, xml, true);
  bool header = false;
  for (const auto& error : strict.errors) {
    if (error.message.find("OpenSCENARIO 0.9 draft") == std::string::npos) continue;
    header = true;
    CHECK(error.line == line_of(xml, "<FileHeader"));
  }
  CHECK(header);
}

// OpenSCENARIO 1.0's ControllerAction: an AssignControllerAction and an
// OverrideControllerValueAction together (CARLA's 1.0 examples write both).
const std::string kControllerPair =
    "<PrivateAction><ControllerAction>\n"
    "<AssignControllerAction><Controller name=\"Agent\"><Properties>"
    "<Property name=\"module\" value=\"external_control\"/></Properties></Controller>"
    "</AssignControllerAction>\n"
    "<OverrideControllerValueAction>\n<Throttle value=\"0\" active=\"false\"/>"
    "<Brake value=\"0\" active=\"false\"/><Clutch value=\"0\" active=\"false\"/>"
    "<ParkingBrake value=\"0\" active=\"false\"/>"
    "<SteeringWheel value=\"0\" active=\"false\"/><Gear number=\"0\" active=\"false\"/>\n"
    "</OverrideControllerValueAction>\n</ControllerAction></PrivateAction>\n";

TEST_CASE("a 1.0 ControllerAction pair in Init is read as its two actions, without a warning",
          "[xosc][carla]") {
  ScenarioText text;
  text.version = "0";
  text.init = "<Private entityRef=\"Ego\">\n" + kControllerPair + "</Private>\n";
  TempDir dir;
  const Loaded loaded = lenient_load(dir, text.str(), true);
  INFO((loaded.errors.empty() ? std::string() : loaded.errors[0].format()));
  REQUIRE(loaded.errors.empty());
  REQUIRE(loaded.scenario);
  const auto& actions = loaded.scenario->storyboard.init.privates.at(0).actions;
  REQUIRE(actions.size() == 2);
  CHECK(std::holds_alternative<xosc::AssignControllerAction>(actions[0]));
  const auto* override_values = std::get_if<xosc::OverrideControllerValueAction>(&actions[1]);
  REQUIRE(override_values != nullptr);
  REQUIRE(override_values->brake.has_value());
  CHECK(!override_values->brake->active);
  // No reading of its own (1.2's deprecations of the 1.0 override attributes aside).
  for (const auto& warning : loaded.warnings) {
    INFO(warning.message);
    CHECK(warning.message.find("unknown") == std::string::npos);
    CHECK(warning.message.find("not supported") == std::string::npos);
    CHECK(warning.message.find("read as") == std::string::npos);
  }
}

TEST_CASE("a 1.0 ControllerAction pair in an event keeps its AssignControllerAction, warned",
          "[xosc][lenient][carla]") {
  ScenarioText text;
  text.version = "0";
  text.stories =
      "<Story name=\"S\"><Act name=\"A\"><ManeuverGroup name=\"G\" "
      "maximumExecutionCount=\"1\"><Actors selectTriggeringEntities=\"false\">"
      "<EntityRef entityRef=\"Ego\"/></Actors><Maneuver name=\"M\">"
      "<Event name=\"E\" priority=\"override\"><Action name=\"Take\">\n" +
      kControllerPair +
      "</Action><StartTrigger><ConditionGroup><Condition name=\"C\" delay=\"0\" "
      "conditionEdge=\"none\"><ByValueCondition><SimulationTimeCondition value=\"1\" "
      "rule=\"greaterThan\"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>"
      "</Event></Maneuver></ManeuverGroup></Act></Story>\n";
  const std::string xml = text.str();
  check_both_ways(xml, "OpenSCENARIO 1.0 <OverrideControllerValueAction> beside an",
                  line_of(xml, "<OverrideControllerValueAction>"));
  const auto scenario = load_with_warning(xml, "<OverrideControllerValueAction> beside an");
  const auto& action = first_event(scenario).actions.at(0).action;
  const auto* private_action = std::get_if<xosc::PrivateAction>(&action);
  REQUIRE(private_action != nullptr);
  CHECK(std::holds_alternative<xosc::AssignControllerAction>(*private_action));
}

}  // namespace
}  // namespace corsa::test
