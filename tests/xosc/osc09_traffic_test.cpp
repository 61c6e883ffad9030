// The 0.9-to-1.0 mapping of the 0.9.1 schema's signals, selections, traffic and user-defined
// actions, as ASAM's 0.9.1-to-1.0 migration maps them (docs/openscenario.md, "OpenSCENARIO 0.9
// drafts"): RoadNetwork/Signals, Entities/Selection, Actors/ByCondition, Global/Infrastructure,
// Global/Traffic (Source, Sink, Swarm, their TrafficDefinition) and UserDefined/Command; and the
// forms with no 1.0 meaning refused at their line: Traffic/Jam, UserDefined/Script, a Swarm
// without numberOfVehicles, the schema's Meeting and an Event priority "following".

#include <catch2/catch.hpp>

#include "lenient_load.h"
#include "osc09_draft.h"

namespace corsa::test {
namespace {

std::string global(const std::string& name, const std::string& body) {
  return "<Action name=\"" + name + "\">\n<Global>\n" + body + "</Global>\n</Action>\n";
}

const std::string kDefinition =
    "<TrafficDefinition name=\"Flow\">\n<VehicleDistribution>\n"
    "<Vehicle category=\"truck\" percentage=\"30\"/>\n"
    "<Vehicle category=\"car\" percentage=\"70\"/>\n</VehicleDistribution>\n"
    "<DriverDistribution>\n<Driver name=\"Calm\" percentage=\"100\"/>\n</DriverDistribution>\n"
    "</TrafficDefinition>\n";

const std::string kLanePosition =
    "<Position>\n<Lane roadId=\"1\" laneId=\"-1\" s=\"20\"/>\n</Position>\n";

TEST_CASE("0.9.1 Signals and Selection are read as 1.0's TrafficSignals and EntitySelection",
          "[xosc][osc09]") {
  std::string xml = osc09_draft();
  replace_once(xml, "</RoadNetwork>",
               "<Signals name=\"Set\">\n<Controller name=\"Main\" delay=\"1\">\n"
               "<Phase type=\"go\" duration=\"5\">\n<Signal name=\"7\" state=\"green\"/>\n"
               "</Phase>\n<Phase type=\"stop\" duration=\"3\">\n"
               "<Signal name=\"7\" state=\"red\"/>\n</Phase>\n</Controller>\n</Signals>\n"
               "</RoadNetwork>");
  replace_once(xml, "</Entities>",
               "<Selection name=\"All\">\n<Members>\n<ByEntity name=\"Ego\"/>\n</Members>\n"
               "</Selection>\n<Selection name=\"Walkers\">\n<Members>\n"
               "<ByType type=\"pedestrian\"/>\n</Members>\n</Selection>\n</Entities>");
  const Loaded loaded = load_without_errors(xml);
  warning_with(loaded, "Signals, Controller, Signal");
  warning_with(loaded, "Selection, ByEntity");
  const xosc::Scenario& scenario = *loaded.scenario;
  const auto& controllers = scenario.road_network.traffic_signal_controllers;
  REQUIRE(controllers.size() == 1);
  CHECK(controllers[0].name == "Main");
  CHECK(controllers[0].delay == 1.0);
  REQUIRE(controllers[0].phases.size() == 2);
  CHECK(controllers[0].phases[1].name == "stop");
  CHECK(controllers[0].phases[1].duration == 3.0);
  REQUIRE(controllers[0].phases[1].states.size() == 1);
  CHECK(controllers[0].phases[1].states[0].traffic_signal_id == "7");
  CHECK(controllers[0].phases[1].states[0].state == "red");
  const auto& selections = scenario.entities.selections;
  REQUIRE(selections.size() == 2);
  CHECK(selections[0].name == "All");
  CHECK(selections[0].entity_refs == std::vector<std::string>{"Ego"});
  REQUIRE(selections[1].by_type.size() == 1);
  CHECK(selections[1].by_type[0].object_type == xosc::ObjectType::kPedestrian);
}

TEST_CASE("0.9.1 Infrastructure, Traffic and UserDefined actions are read as 1.0's",
          "[xosc][osc09]") {
  const std::string xml = osc09_draft_doing(
      global("Phase",
             "<Infrastructure>\n<Signal>\n<SetController name=\"Main\" state=\"stop\"/>\n"
             "</Signal>\n</Infrastructure>\n") +
      global("Lamp",
             "<Infrastructure>\n<Signal>\n<SetState name=\"7\" state=\"off\"/>\n"
             "</Signal>\n</Infrastructure>\n") +
      global("In", "<Traffic>\n<Source rate=\"0.5\" radius=\"2\">\n" + kLanePosition + kDefinition +
                       "</Source>\n</Traffic>\n") +
      global("Out", "<Traffic>\n<Sink rate=\"3\" radius=\"10\">\n" + kLanePosition + kDefinition +
                        "</Sink>\n</Traffic>\n") +
      global("Around",
             "<Traffic>\n<Swarm semiMajorAxis=\"100\" semiMinorAxis=\"20\" "
             "innerRadius=\"10\" offset=\"5\" numberOfVehicles=\"12\">\n"
             "<CentralObject name=\"Ego\"/>\n" +
                 kDefinition + "</Swarm>\n</Traffic>\n") +
      "<Action name=\"Say\">\n<UserDefined>\n<Command type=\"corsa:note\">hello</Command>\n"
      "</UserDefined>\n</Action>\n");
  // The 0.9 SetController names a controller this draft has no Signals for: declared here.
  std::string with_signals = xml;
  replace_once(with_signals, "</RoadNetwork>",
               "<Signals name=\"Set\">\n<Controller name=\"Main\">\n"
               "<Phase type=\"stop\" duration=\"5\"/>\n</Controller>\n</Signals>\n"
               "</RoadNetwork>");
  const Loaded loaded = load_without_errors(with_signals);
  warning_with(loaded, "Infrastructure, Signal, SetController");
  warning_with(loaded, "0.9 DriverDistribution names drivers (Calm)");
  const auto& actions = first_event(*loaded.scenario).actions;
  REQUIRE(actions.size() == 6);
  const auto global_of = [&](size_t at) -> const xosc::GlobalAction& {
    return std::get<xosc::GlobalAction>(actions.at(at).action);
  };
  const auto& phase = std::get<xosc::TrafficSignalControllerAction>(global_of(0));
  CHECK(phase.traffic_signal_controller_ref == "Main");
  CHECK(phase.phase == "stop");
  const auto& lamp = std::get<xosc::TrafficSignalStateAction>(global_of(1));
  CHECK(lamp.name == "7");
  CHECK(lamp.state == "off");
  const auto& source = std::get<xosc::TrafficSourceAction>(global_of(2));
  CHECK(source.rate == 0.5);
  CHECK(source.radius == 2.0);
  CHECK(std::get<xosc::LanePosition>(source.position.kind).s == 20.0);
  REQUIRE(source.traffic_definition);
  REQUIRE(source.traffic_definition->vehicle_categories.size() == 2);
  CHECK(source.traffic_definition->vehicle_categories[0].category == xosc::VehicleCategory::kTruck);
  CHECK(source.traffic_definition->vehicle_categories[0].weight == 30.0);
  REQUIRE(source.traffic_definition->controllers.size() == 1);
  CHECK(source.traffic_definition->controllers[0].weight == 100.0);
  CHECK(source.traffic_definition->controllers[0].controller.name == "Calm");
  const auto& sink = std::get<xosc::TrafficSinkAction>(global_of(3));
  CHECK(sink.rate == 3.0);
  CHECK(sink.radius == 10.0);
  const auto& swarm = std::get<xosc::TrafficSwarmAction>(global_of(4));
  CHECK(swarm.central_object == "Ego");
  CHECK(swarm.number_of_vehicles == 12);
  CHECK(swarm.semi_major_axis == 100.0);
  CHECK(swarm.offset == 5.0);
  const auto& say = std::get<xosc::UserDefinedAction>(actions.at(5).action);
  CHECK(say.type == "corsa:note");
  CHECK(say.content == "hello");
}

TEST_CASE("a 0.9 Command without a type is read with its text as the type",
          "[xosc][osc09][lenient]") {
  const std::string xml = osc09_draft_doing(
      "<Action name=\"Say\">\n<UserDefined>\n<Command> corsa:note </Command>\n"
      "</UserDefined>\n</Action>\n");
  const Loaded loaded = check_both_ways(xml, "0.9 UserDefined Command \"corsa:note\" has no type",
                                        line_of(xml, "<Command>"));
  const auto& say =
      std::get<xosc::UserDefinedAction>(first_event(*loaded.scenario).actions.at(0).action);
  CHECK(say.type == "corsa:note");
}

TEST_CASE("a 0.9 VehicleDistribution category that 1.0 lacks is read as car",
          "[xosc][osc09][lenient]") {
  std::string definition = kDefinition;
  replace_once(definition, "category=\"truck\"", "category=\"lorry\"");
  const std::string xml =
      osc09_draft_doing(global("In", "<Traffic>\n<Source rate=\"1\" radius=\"2\">\n" +
                                         kLanePosition + definition + "</Source>\n</Traffic>\n"));
  const Loaded loaded =
      check_both_ways(xml, "0.9 VehicleDistribution category=\"lorry\" is no 1.0 vehicle category",
                      line_of(xml, "category=\"lorry\""));
  const auto& source = std::get<xosc::TrafficSourceAction>(
      std::get<xosc::GlobalAction>(first_event(*loaded.scenario).actions.at(0).action));
  CHECK(source.traffic_definition->vehicle_categories[0].category == xosc::VehicleCategory::kCar);
}

TEST_CASE("0.9 ByCondition actors: triggeringEntity selects them, anyEntity is warned",
          "[xosc][osc09][lenient]") {
  std::string xml = osc09_draft();
  replace_once(xml, "<Actors>\n<Entity name=\"$owner\"/>\n</Actors>",
               "<Actors>\n<ByCondition actor=\"triggeringEntity\"/>\n</Actors>");
  const xosc::Scenario scenario = load_with_warning(xml, "ByCondition");
  const auto& actors = scenario.storyboard.stories.at(0).acts.at(0).maneuver_groups.at(0).actors;
  CHECK(actors.select_triggering_entities);
  CHECK(actors.entity_refs.empty());

  std::string any = osc09_draft();
  replace_once(any, "<Actors>\n<Entity name=\"$owner\"/>\n</Actors>",
               "<Actors>\n<Entity name=\"$owner\"/>\n<ByCondition actor=\"anyEntity\"/>\n"
               "</Actors>");
  const Loaded loaded =
      check_both_ways(any, "0.9 Actors ByCondition actor=\"anyEntity\" has no 1.0 form",
                      line_of(any, "<ByCondition"));
  const auto& listed =
      loaded.scenario->storyboard.stories.at(0).acts.at(0).maneuver_groups.at(0).actors;
  CHECK(!listed.select_triggering_entities);
  CHECK(listed.entity_refs == std::vector<std::string>{"Ego"});
  CHECK_THAT(warning_with(loaded, "anyEntity").message,
             Catch::Contains("the Entity elements listed are the actors"));
}

// A 0.9 form that has no 1.0 meaning: the load fails with an error at `needle`'s line naming
// `text`.
void check_refused(const std::string& xml, const std::string& needle, const std::string& text) {
  TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(!loaded.errors.empty());
  CHECK(loaded.errors[0].line == line_of(xml, needle));
  CHECK_THAT(loaded.errors[0].message, Catch::Contains(text));
}

TEST_CASE("0.9 forms with no 1.0 meaning are refused at their line", "[xosc][osc09]") {
  check_refused(osc09_draft_doing(
                    global("J", "<Traffic>\n<Jam direction=\"east\" speed=\"2\" length=\"100\">\n" +
                                    kLanePosition + kDefinition + "</Jam>\n</Traffic>\n")),
                "<Jam", "0.9 Traffic Jam has no 1.0 form");
  check_refused(osc09_draft_doing("<Action name=\"Run\">\n<UserDefined>\n"
                                  "<Script name=\"s\" file=\"go.py\" execution=\"single\"/>\n"
                                  "</UserDefined>\n</Action>\n"),
                "<Script", "0.9 UserDefined Script file=\"go.py\" has no 1.0 form");
  check_refused(
      osc09_draft_doing(global("S",
                               "<Traffic>\n<Swarm semiMajorAxis=\"100\" semiMinorAxis=\"20\" "
                               "innerRadius=\"10\" offset=\"5\">\n<CentralObject name=\"Ego\"/>\n" +
                                   kDefinition + "</Swarm>\n</Traffic>\n")),
      "<Swarm", "0.9 Swarm gives no numberOfVehicles");
  check_refused(osc09_draft_doing("<Action name=\"Meet\">\n<Private>\n"
                                  "<Meeting mode=\"straight\" timingOffset=\"0\">\n" +
                                  kLanePosition + "</Meeting>\n</Private>\n</Action>\n"),
                "<Meeting", "0.9 Meeting without a Relative entity to meet");
  std::string following = osc09_draft();
  replace_once(following, "priority=\"overwrite\"", "priority=\"following\"");
  check_refused(following, "priority=\"following\"",
                "0.9 Event priority 'following' has no 1.0 form");
}

}  // namespace
}  // namespace corsa::test
