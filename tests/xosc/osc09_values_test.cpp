// The 0.9-to-1.0 mapping's judgement of values: attributes holding `$parameters` judged by the
// parameter's value, 0.9 enum words inside parameter values, the AfterTermination rule of an
// act, Dynamics giving two dimensions, degenerate references, and 0.9 catalog files.

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>

#include "lenient_load.h"
#include "osc09_draft.h"

namespace corsa::test {
namespace {

// The draft with more 0.9 parameters and a Storyboard End of one RelativeDistance condition.
std::string draft_with_end(const std::string& parameters, const std::string& distance_attributes,
                           const std::string& condition_attributes = "") {
  std::string xml = osc09_draft();
  replace_once(xml, "</ParameterDeclaration>", parameters + "</ParameterDeclaration>");
  replace_once(xml, "<End>\n</End>",
               "<End>\n<ConditionGroup>\n<Condition name=\"Near\" delay=\"0\"" +
                   condition_attributes +
                   ">\n<ByEntity>\n<TriggeringEntities rule=\"any\">\n<Entity name=\"Ego\"/>\n"
                   "</TriggeringEntities>\n<EntityCondition>\n<RelativeDistance entity=\"Ego\" "
                   "type=\"longitudinal\" freespace=\"false\" value=\"5\"" +
                   distance_attributes +
                   "/>\n</EntityCondition>\n</ByEntity>\n</Condition>\n</ConditionGroup>\n</End>");
  return xml;
}

const xosc::Condition& end_condition(const xosc::Scenario& scenario) {
  return scenario.storyboard.stop_trigger.value().groups.at(0).conditions.at(0);
}

const xosc::RelativeDistanceCondition& end_distance(const xosc::Scenario& scenario) {
  const auto& by_entity = std::get<xosc::ByEntityCondition>(end_condition(scenario).kind);
  return std::get<xosc::RelativeDistanceCondition>(by_entity.condition);
}

const xosc::Act& the_act(const xosc::Scenario& scenario) {
  return scenario.storyboard.stories.at(0).acts.at(0);
}

xosc::Rule time_rule(const xosc::Trigger& trigger) {
  const auto& by_value =
      std::get<xosc::ByValueCondition>(trigger.groups.at(0).conditions.at(0).kind);
  return std::get<xosc::SimulationTimeCondition>(by_value).rule;
}

xosc::Rule event_rule(const xosc::Scenario& scenario) {
  return time_rule(
      the_act(scenario).maneuver_groups.at(0).maneuvers.at(0).events.at(0).start_trigger.value());
}

TEST_CASE("a 0.9 alongRoute given by a parameter is judged by the parameter's value",
          "[xosc][osc09]") {
  const std::string xml =
      draft_with_end("<Parameter name=\"$Along\" type=\"boolean\" value=\"true\"/>\n",
                     " rule=\"less_than\" alongRoute=\"$Along\"");
  const Loaded loaded = load_without_errors(xml);
  const auto& distance = end_distance(*loaded.scenario);
  CHECK(distance.coordinate_system == xosc::CoordinateSystem::kRoad);
  CHECK(distance.rule == xosc::Rule::kLessThan);

  // The same parameter false: measured as 1.0's default.
  std::string off = xml;
  replace_once(off, "value=\"true\"/>", "value=\"false\"/>");
  TempDir dir;
  const Loaded loaded_off = lenient_load(dir, off);
  REQUIRE(loaded_off.errors.empty());
  CHECK(!end_distance(*loaded_off.scenario).coordinate_system.has_value());
}

TEST_CASE("0.9 enum words held by parameters are read as their 1.0 words, warned at the use",
          "[xosc][osc09]") {
  const std::string xml = draft_with_end(
      "<Parameter name=\"$Rule\" type=\"string\" value=\"greater_than\"/>\n"
      "<Parameter name=\"$Edge\" type=\"string\" value=\"any\"/>\n"
      "<Parameter name=\"$Kind\" type=\"string\" value=\"inertial\"/>\n",
      " rule=\"$Rule\" type2=\"\"", " edge=\"$Edge\"");
  std::string text = xml;
  replace_once(text, "type=\"longitudinal\"", "type=\"$Kind\"");
  replace_once(text, " type2=\"\"", "");
  const Loaded loaded = load_without_errors(text);
  const auto& distance = end_distance(*loaded.scenario);
  CHECK(distance.rule == xosc::Rule::kGreaterThan);
  CHECK(distance.relative_distance_type == xosc::RelativeDistanceType::kEuclidianDistance);
  CHECK(end_condition(*loaded.scenario).edge == xosc::ConditionEdge::kRisingOrFalling);
  const auto rule = warning_with(loaded, "0.9 value 'greater_than' of parameter '$Rule'");
  CHECK(rule.line == line_of(text, "rule=\"$Rule\""));
  CHECK_THAT(rule.message, Catch::Contains("(read as 'greaterThan')"));
  const auto edge = warning_with(loaded, "0.9 value 'any' of parameter '$Edge'");
  CHECK(edge.line == line_of(text, "edge=\"$Edge\""));

  // --strict: an error at the use.
  TempDir dir;
  const Loaded strict = lenient_load(dir, text, true);
  bool found = false;
  for (const auto& error : strict.errors) {
    if (error.message.find("0.9 value 'greater_than'") != std::string::npos) {
      found = true;
      CHECK(error.line == line_of(text, "rule=\"$Rule\""));
    }
  }
  CHECK(found);
}

TEST_CASE("a parameter value given from outside is what a 0.9 attribute is judged by",
          "[xosc][osc09]") {
  const std::string xml =
      draft_with_end("<Parameter name=\"$Along\" type=\"boolean\" value=\"false\"/>\n",
                     " rule=\"less_than\" alongRoute=\"$Along\"");
  TempDir dir;
  write_text(dir.path() / "map.xodr", minimal_xodr());
  write_text(dir.path() / "s.xosc", xml);
  corsa::Diagnostics diagnostics;
  xosc::LoadOptions options;
  options.parameters = {{"Along", "true"}};
  const auto scenario = xosc::load_scenario(dir.path() / "s.xosc", options, diagnostics);
  CHECK(end_distance(scenario).coordinate_system == xosc::CoordinateSystem::kRoad);
}

TEST_CASE("0.9 AfterTermination rule=\"end\" of an act holds once the act's End conditions end it",
          "[xosc][osc09]") {
  std::string xml = osc09_draft();
  replace_once(xml, "<AtStart type=\"act\" name=\"A\"/>",
               "<AfterTermination type=\"act\" name=\"A\" rule=\"end\"/>");
  const Loaded loaded = load_without_errors(xml);
  const auto state_of = [](const xosc::Scenario& scenario) {
    const auto& event = first_event(scenario);
    const auto& condition = event.start_trigger->groups.at(0).conditions.at(0);
    const auto& by_value = std::get<xosc::ByValueCondition>(condition.kind);
    return std::get<xosc::StoryboardElementStateCondition>(by_value).state;
  };
  // The act's End conditions become its StopTrigger (a stop transition): "end" is the complete
  // state, reached by either transition.
  CHECK(state_of(*loaded.scenario) == xosc::StoryboardElementState::kCompleteState);

  // An event ends by itself: its end transition.
  replace_once(xml, "type=\"act\" name=\"A\" rule=\"end\"",
               "type=\"event\" name=\"E\" rule=\"end\"");
  CHECK(state_of(*load_without_errors(xml).scenario) ==
        xosc::StoryboardElementState::kEndTransition);

  // A rule that is none of the three: located.
  replace_once(xml, "rule=\"end\"", "rule=\"finish\"");
  TempDir dir;
  const Loaded finish = lenient_load(dir, xml);
  REQUIRE(!finish.errors.empty());
  CHECK(finish.errors[0].line == line_of(xml, "rule=\"finish\""));
  CHECK_THAT(finish.errors[0].message, Catch::Contains("finish"));
}

TEST_CASE("a 0.9 Dynamics with both time and rate keeps the time, warned at its line",
          "[xosc][osc09]") {
  std::string xml = osc09_draft();
  replace_once(xml, "<Dynamics shape=\"linear\" rate=\"2\"/>",
               "<Dynamics shape=\"linear\" rate=\"2\" time=\"4\"/>");
  const Loaded loaded = load_without_errors(xml);
  const auto& event = first_event(*loaded.scenario);
  const auto& action = std::get<xosc::PrivateAction>(event.actions.at(0).action);
  const auto& speed = std::get<xosc::SpeedAction>(action);
  CHECK(speed.dynamics.dimension == xosc::DynamicsDimension::kTime);
  CHECK(speed.dynamics.value == 4.0);
  const auto warning = warning_with(loaded, "0.9 Dynamics gives time=\"4\", rate=\"2\"");
  CHECK(warning.line == line_of(xml, "rate=\"2\" time=\"4\""));
  CHECK_THAT(warning.message, Catch::Contains("(read as time 4"));
  TempDir dir;
  const Loaded strict = lenient_load(dir, xml, true);
  bool found = false;
  for (const auto& error : strict.errors) {
    found = found || error.message.find("0.9 Dynamics gives") != std::string::npos;
  }
  CHECK(found);
}

TEST_CASE("degenerate 0.9 parameter references are located errors, never a crash",
          "[xosc][osc09]") {
  TempDir dir;
  SECTION("a declaration named by a bare $") {
    std::string xml = osc09_draft();
    replace_once(xml, "</ParameterDeclaration>",
                 "<Parameter name=\"$\" type=\"double\" value=\"1\"/>\n</ParameterDeclaration>");
    const Loaded loaded = lenient_load(dir, xml);
    REQUIRE(!loaded.errors.empty());
    CHECK(loaded.errors[0].line == line_of(xml, "name=\"$\""));
  }
  SECTION("alongRoute naming an undeclared parameter, or a bare $") {
    for (const std::string along : {"$Nowhere", "$", "$$"}) {
      const std::string xml =
          draft_with_end("", " rule=\"less_than\" alongRoute=\"" + along + "\"");
      const Loaded loaded = lenient_load(dir, xml);
      REQUIRE(!loaded.errors.empty());
      CHECK(loaded.errors[0].line == line_of(xml, "alongRoute="));
      CHECK_THAT(loaded.errors[0].message, Catch::Contains("alongRoute"));
    }
  }
  SECTION("a rule or an edge of a bare $") {
    const std::string xml = draft_with_end("", " rule=\"$\"", " edge=\"$\"");
    const Loaded loaded = lenient_load(dir, xml);
    REQUIRE(loaded.errors.size() >= 2);
    CHECK(loaded.errors[0].line == line_of(xml, "edge=\"$\""));
    CHECK(loaded.errors[1].line == line_of(xml, "rule=\"$\""));
  }
  SECTION("parameters referring to each other in a cycle") {
    const std::string xml = draft_with_end(
        "<Parameter name=\"$A\" type=\"string\" value=\"$B\"/>\n"
        "<Parameter name=\"$B\" type=\"string\" value=\"$A\"/>\n",
        " rule=\"$A\"");
    const Loaded loaded = lenient_load(dir, xml);
    REQUIRE(!loaded.errors.empty());
  }
}

TEST_CASE("a 0.9 catalog file referenced by a 0.9 scenario is read through the same mapping",
          "[xosc][osc09]") {
  std::string xml = osc09_draft();
  replace_once(xml, "<Catalogs>\n<RouteCatalog>\n</RouteCatalog>\n</Catalogs>",
               "<Catalogs>\n<VehicleCatalog>\n<Directory path=\"catalogs\"/>\n</VehicleCatalog>\n"
               "</Catalogs>");
  const size_t from = xml.find("<Object");
  const size_t to = xml.find("</Object>") + 9;
  xml.replace(from, to - from,
              "<Object name=\"Ego\">\n<CatalogReference catalogName=\"VehicleCatalog\" "
              "entryName=\"car_white\">\n<ParameterAssignment>\n"
              "<Parameter name=\"$Mass\" value=\"1500\"/>\n</ParameterAssignment>\n"
              "</CatalogReference>\n</Object>");
  const std::string catalog =
      "<?xml version=\"1.0\"?>\n<OpenSCENARIO>\n"
      "<FileHeader revMajor=\"0\" revMinor=\"9\" date=\"2018-11-8T17:00:00\" author=\"a\"/>\n"
      "<Catalog name=\"VehicleCatalog\">\n"
      "<Vehicle name=\"car_white\" category=\"car\">\n"
      "<ParameterDeclaration>\n<Parameter name=\"$Mass\" type=\"double\" value=\"2000\"/>\n"
      "</ParameterDeclaration>\n"
      "<BoundingBox>\n<Center x=\"1.4\" y=\"0.0\" z=\"0.9\"/>\n"
      "<Dimension width=\"2.0\" length=\"5.0\" height=\"1.8\"/>\n</BoundingBox>\n"
      "<Performance maxSpeed=\"69\" maxDeceleration=\"30\" mass=\"$Mass\"/>\n"
      "<Axles>\n<Front maxSteering=\"0.5\" wheelDiameter=\"0.8\" trackWidth=\"1.68\" "
      "positionX=\"2.98\" positionZ=\"0.4\"/>\n"
      "<Rear maxSteering=\"0.5\" wheelDiameter=\"0.8\" trackWidth=\"1.68\" positionX=\"0\" "
      "positionZ=\"0.4\"/>\n</Axles>\n"
      "<Properties>\n<Property name=\"model_id\" value=\"0\"/>\n</Properties>\n"
      "</Vehicle>\n</Catalog>\n</OpenSCENARIO>\n";
  TempDir dir;
  std::filesystem::create_directories(dir.path() / "catalogs");
  write_text(dir.path() / "catalogs" / "VehicleCatalog.xosc", catalog);
  Loaded loaded = lenient_load(dir, xml);
  INFO((loaded.errors.empty() ? std::string() : loaded.errors[0].format()));
  REQUIRE(loaded.errors.empty());
  const auto& vehicle = std::get<xosc::Vehicle>(loaded.scenario->entities.objects.at(0).object);
  CHECK(vehicle.category == xosc::VehicleCategory::kCar);
  CHECK(vehicle.bounding_box.length == 5.0);
  CHECK(vehicle.axles.front_axle.value().position_x == 2.98);
  CHECK(vehicle.mass == std::optional<double>(1500.0));
  // The catalog's own warning, at its FileHeader.
  int catalog_warnings = 0;
  for (const auto& warning : loaded.warnings) {
    if (warning.file.find("VehicleCatalog.xosc") == std::string::npos ||
        warning.message.find("OpenSCENARIO 0.9 draft") == std::string::npos) {
      continue;
    }
    ++catalog_warnings;
    CHECK_THAT(warning.message, Catch::Contains("(read as 1.0") && Catch::Contains("Dimension") &&
                                    Catch::Contains("Front"));
    CHECK(warning.line == 3);
  }
  CHECK(catalog_warnings == 1);
  // --strict: the catalog's 0.9 form is an error there too.
  const Loaded strict = lenient_load(dir, xml, true);
  bool catalog_error = false;
  for (const auto& error : strict.errors) {
    catalog_error = catalog_error || (error.file.find("VehicleCatalog.xosc") != std::string::npos &&
                                      error.line == 3);
  }
  CHECK(catalog_error);

  // An error inside the 0.9 catalog points at the catalog's own line.
  std::string bad = catalog;
  replace_once(bad, "length=\"5.0\"", "length=\"long\"");
  write_text(dir.path() / "catalogs" / "VehicleCatalog.xosc", bad);
  loaded = lenient_load(dir, xml);
  REQUIRE(!loaded.errors.empty());
  CHECK(loaded.errors[0].file.find("VehicleCatalog.xosc") != std::string::npos);
  CHECK(loaded.errors[0].line == line_of(bad, "length=\"long\""));
}

// The draft with a global $Rule greater_than, its maneuver declaring $Rule as `inner` and
// starting its event also at SimulationTime 2 by it, and the act starting at 1 by $Rule.
std::string draft_with_two_rules(const std::string& inner) {
  std::string xml = osc09_draft();
  replace_once(xml, "</ParameterDeclaration>",
               "<Parameter name=\"$Rule\" type=\"string\" value=\"greater_than\"/>\n"
               "</ParameterDeclaration>");
  replace_once(xml, "<Maneuver name=\"M\">\n",
               "<Maneuver name=\"M\">\n<ParameterDeclaration>\n"
               "<Parameter name=\"$Rule\" type=\"string\" value=\"" +
                   inner +
                   "\"/>\n"
                   "</ParameterDeclaration>\n");
  replace_once(xml, "<AtStart type=\"act\" name=\"A\"/>\n</ByState>",
               "<AtStart type=\"act\" name=\"A\"/>\n</ByState>\n</Condition>\n"
               "<Condition name=\"T\" delay=\"0\" edge=\"none\">\n<ByValue>\n"
               "<SimulationTime value=\"2\" rule=\"$Rule\"/>\n</ByValue>");
  replace_once(xml, "<SimulationTime value=\"0\" rule=\"greater_than\"/>",
               "<SimulationTime value=\"1\" rule=\"$Rule\"/>");
  return xml;
}

TEST_CASE("a 0.9 Maneuver's parameter hides the global one inside the maneuver only",
          "[xosc][osc09]") {
  const std::string xml = draft_with_two_rules("less_than");
  const Loaded loaded = load_without_errors(xml);
  // The act's start, mapped after its sequences, sees the global parameter.
  CHECK(time_rule(the_act(*loaded.scenario).start_trigger.value()) == xosc::Rule::kGreaterThan);
  const auto& event = the_act(*loaded.scenario).maneuver_groups.at(0).maneuvers.at(0).events.at(0);
  const auto& inner = std::get<xosc::ByValueCondition>(
      event.start_trigger.value().groups.at(0).conditions.at(1).kind);
  CHECK(std::get<xosc::SimulationTimeCondition>(inner).rule == xosc::Rule::kLessThan);
  CHECK(warning_with(loaded, "0.9 value 'greater_than' of parameter '$Rule'").line ==
        line_of(xml, "<SimulationTime value=\"1\""));
  CHECK(warning_with(loaded, "0.9 value 'less_than' of parameter '$Rule'").line ==
        line_of(xml, "<SimulationTime value=\"2\""));
}

TEST_CASE("a 0.9 Maneuver's 1.0 word leaves no global 0.9 word for the reader to refuse",
          "[xosc][osc09]") {
  TempDir dir;
  const std::string ten = draft_with_two_rules("lessThan");
  const Loaded loaded_ten = lenient_load(dir, ten);
  INFO((loaded_ten.errors.empty() ? std::string() : loaded_ten.errors[0].format()));
  REQUIRE(loaded_ten.errors.empty());
  CHECK(time_rule(the_act(*loaded_ten.scenario).start_trigger.value()) == xosc::Rule::kGreaterThan);
}

// A 0.9 ManeuverCatalog: "Speedup" declares $Rule (default `rule`) and starts its event by it;
// "Other" uses $Rule without declaring it.
std::string osc09_maneuver_catalog(const std::string& rule) {
  const std::string event =
      "<Event name=\"E\" priority=\"overwrite\">\n<Action name=\"Faster\">\n<Private>\n"
      "<Longitudinal>\n<Speed>\n<Dynamics shape=\"step\"/>\n<Target>\n<Absolute "
      "value=\"20\"/>\n</Target>\n</Speed>\n</Longitudinal>\n</Private>\n</Action>\n"
      "<StartConditions>\n<ConditionGroup>\n<Condition name=\"C\" delay=\"0\" "
      "edge=\"none\">\n<ByValue>\n<SimulationTime value=\"2\" rule=\"$Rule\"/>\n</ByValue>\n"
      "</Condition>\n</ConditionGroup>\n</StartConditions>\n</Event>\n";
  return "<?xml version=\"1.0\"?>\n<OpenSCENARIO>\n"
         "<FileHeader revMajor=\"0\" revMinor=\"9\" date=\"2019-10-23T10:00:00\" "
         "author=\"a\"/>\n<Catalog name=\"ManeuverCatalog\">\n"
         "<Maneuver name=\"Speedup\">\n<ParameterDeclaration>\n"
         "<Parameter name=\"$Rule\" type=\"string\" value=\"" +
         rule + "\"/>\n</ParameterDeclaration>\n" + event +
         "</Maneuver>\n<Maneuver name=\"Other\">\n" + event +
         "</Maneuver>\n</Catalog>\n</OpenSCENARIO>\n";
}

// The draft whose maneuver is the catalog's `entry`, with `assignment` (0.9 Parameter elements).
std::string draft_with_catalog_maneuver(const std::string& entry, const std::string& assignment) {
  std::string xml = osc09_draft();
  replace_once(xml, "<Catalogs>\n<RouteCatalog>\n</RouteCatalog>\n</Catalogs>",
               "<Catalogs>\n<ManeuverCatalog>\n<Directory path=\"catalogs\"/>\n"
               "</ManeuverCatalog>\n</Catalogs>");
  const size_t from = xml.find("<Maneuver name=\"M\">");
  const size_t to = xml.find("</Maneuver>") + 11;
  xml.replace(from, to - from,
              "<CatalogReference catalogName=\"ManeuverCatalog\" entryName=\"" + entry + "\">\n" +
                  (assignment.empty()
                       ? std::string()
                       : "<ParameterAssignment>\n" + assignment + "</ParameterAssignment>\n") +
                  "</CatalogReference>");
  return xml;
}

TEST_CASE(
    "a 0.9 catalog entry's parameters are its own, and a reference's assignment replaces a "
    "0.9 default",
    "[xosc][osc09]") {
  TempDir dir;
  std::filesystem::create_directories(dir.path() / "catalogs");
  const std::string catalog = osc09_maneuver_catalog("greater_than");
  write_text(dir.path() / "catalogs" / "ManeuverCatalog.xosc", catalog);

  // The default, a 0.9 word, read as its 1.0 word, warned at the use in the catalog.
  const Loaded plain = lenient_load(dir, draft_with_catalog_maneuver("Speedup", ""));
  INFO((plain.errors.empty() ? std::string() : plain.errors[0].format()));
  REQUIRE(plain.errors.empty());
  CHECK(event_rule(*plain.scenario) == xosc::Rule::kGreaterThan);
  const auto use = warning_with(plain, "0.9 value 'greater_than' of parameter '$Rule'");
  CHECK(use.file.find("ManeuverCatalog.xosc") != std::string::npos);
  CHECK(use.line == line_of(catalog, "rule=\"$Rule\""));

  // A 1.0 word assigned replaces the default.
  const Loaded assigned = lenient_load(
      dir,
      draft_with_catalog_maneuver("Speedup", "<Parameter name=\"$Rule\" value=\"lessThan\"/>\n"));
  INFO((assigned.errors.empty() ? std::string() : assigned.errors[0].format()));
  REQUIRE(assigned.errors.empty());
  CHECK(event_rule(*assigned.scenario) == xosc::Rule::kLessThan);

  // A 0.9 word assigned: its 1.0 word, warned at the assignment.
  const std::string old_word =
      draft_with_catalog_maneuver("Speedup", "<Parameter name=\"$Rule\" value=\"less_than\"/>\n");
  const Loaded assigned_old = lenient_load(dir, old_word);
  INFO((assigned_old.errors.empty() ? std::string() : assigned_old.errors[0].format()));
  REQUIRE(assigned_old.errors.empty());
  CHECK(event_rule(*assigned_old.scenario) == xosc::Rule::kLessThan);
  const auto assignment = warning_with(assigned_old, "0.9 value 'less_than' assigned to parameter");
  CHECK(assignment.line == line_of(old_word, "value=\"less_than\""));
  CHECK_THAT(assignment.message, Catch::Contains("'$Rule'") && Catch::Contains("'lessThan'"));
}

TEST_CASE("a 0.9 catalog entry does not see another entry's parameters", "[xosc][osc09]") {
  TempDir dir;
  std::filesystem::create_directories(dir.path() / "catalogs");
  const std::string catalog = osc09_maneuver_catalog("greater_than");
  write_text(dir.path() / "catalogs" / "ManeuverCatalog.xosc", catalog);
  // The reader's undefined parameter, at the use in the catalog.
  const Loaded other = lenient_load(dir, draft_with_catalog_maneuver("Other", ""));
  REQUIRE(!other.errors.empty());
  CHECK_THAT(other.errors[0].message, Catch::Contains("undefined parameter '$Rule'"));
  CHECK(other.errors[0].file.find("ManeuverCatalog.xosc") != std::string::npos);
  const size_t other_use = catalog.find("rule=\"$Rule\"", catalog.find("name=\"Other\""));
  CHECK(other.errors[0].line ==
        1 + std::count(catalog.begin(), catalog.begin() + static_cast<long>(other_use), '\n'));
}

TEST_CASE("a 0.9 catalog file with too many mapping errors keeps them located", "[xosc][osc09]") {
  const std::string condition =
      "<Condition name=\"C\" delay=\"0\" edge=\"rising\">\n<ByEntity>\n"
      "<TriggeringEntities rule=\"any\">\n<Entity name=\"Ego\"/>\n</TriggeringEntities>\n"
      "<EntityCondition>\n<RelativeDistance entity=\"Ego\" type=\"inertial\" value=\"5\" "
      "freespace=\"false\" alongRoute=\"maybe\" rule=\"less_than\"/>\n</EntityCondition>\n"
      "</ByEntity>\n</Condition>\n";
  std::string conditions;
  for (int i = 0; i < 600; ++i) conditions += condition;
  std::string catalog = osc09_maneuver_catalog("greater_than");
  replace_once(catalog, "<Condition name=\"C\"", conditions + "<Condition name=\"C\"");
  TempDir dir;
  std::filesystem::create_directories(dir.path() / "catalogs");
  write_text(dir.path() / "catalogs" / "ManeuverCatalog.xosc", catalog);
  const Loaded loaded = lenient_load(dir, draft_with_catalog_maneuver("Speedup", ""));
  REQUIRE(!loaded.errors.empty());
  // The first alongRoute's error, at its line in the catalog, rather than the file said unread.
  CHECK(loaded.errors[0].file.find("ManeuverCatalog.xosc") != std::string::npos);
  CHECK(loaded.errors[0].line == line_of(catalog, "alongRoute=\"maybe\""));
  CHECK_THAT(loaded.errors[0].message, Catch::Contains("alongRoute"));
  for (const auto& error : loaded.errors) {
    CHECK_THAT(error.message, !Catch::Contains("could not be read"));
  }
}

}  // namespace
}  // namespace corsa::test
