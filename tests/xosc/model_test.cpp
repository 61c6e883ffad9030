#include <catch2/catch.hpp>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <variant>
#include <vector>

#include "corsa/xosc/scenario.h"
#include "shared_data.h"

namespace fs = std::filesystem;
using namespace corsa::xosc;

using corsa::test::kAsamExamples;

namespace {

Scenario load(const char* name, const LoadOptions& options = {}) {
  corsa::Diagnostics diagnostics;
  return load_scenario(kAsamExamples / name, options, diagnostics);
}

template <class T>
const T& private_action(const Event& event, size_t index = 0) {
  return std::get<T>(std::get<PrivateAction>(event.actions.at(index).action));
}

}  // namespace

TEST_CASE("expressions and parameters in TrailerConnect resolve to numbers", "[xosc][model]") {
  const Scenario scenario = load("TrailerConnect.xosc");
  REQUIRE(scenario.storyboard.init.privates.size() == 2);
  const auto& car = scenario.storyboard.init.privates[1];
  CHECK(car.entity_ref == "Car");
  const auto& teleport = std::get<TeleportAction>(car.actions.at(0));
  const auto& world = std::get<WorldPosition>(teleport.position.kind);
  CHECK(world.x == Approx(1.7 - 12.0));         // ${$X0 - $TrajRadius}
  CHECK(world.y == Approx(13.5 + 12.0 + 4.7));  // ${$Y0 + $TrajRadius + 4.7}
  CHECK(world.source.line == 43);
  CHECK(world.source.file_name() == (kAsamExamples / "TrailerConnect.xosc").string());

  const auto& maneuver =
      scenario.storyboard.stories.at(0).acts.at(0).maneuver_groups.at(0).maneuvers.at(0);
  const auto& speed = private_action<SpeedAction>(maneuver.events.at(0));
  CHECK(std::get<AbsoluteTargetSpeed>(speed.target).value == -4.0);  // ${-$Speed}
  const auto& follow = private_action<FollowTrajectoryAction>(maneuver.events.at(0), 1);
  const auto& clothoid = std::get<Clothoid>(follow.trajectory.shape);
  CHECK(clothoid.curvature == Approx(-1.0 / 12.0));
  CHECK(clothoid.length == Approx(0.25 * 2.0 * 3.141592 * 12.0));
  CHECK(clothoid.curvature_prime == 0.0);  // from the deprecated curvatureDot
  CHECK_FALSE(follow.time_reference.timing.has_value());
  CHECK(follow.following_mode == FollowingMode::kPosition);
  // Priority "overwrite" (1.1) reads as override.
  CHECK(maneuver.events.at(0).priority == Priority::kOverride);
  CHECK(maneuver.events.at(3).priority == Priority::kParallel);
}

TEST_CASE("catalog references expand to the entry with its parameters", "[xosc][model]") {
  const Scenario scenario = load("TrailerConnect.xosc");
  const ScenarioObject* trailer = scenario.entities.find_object("Trailer");
  REQUIRE(trailer != nullptr);
  const auto& vehicle = std::get<Vehicle>(trailer->object);
  CHECK(vehicle.name == "car_trailer");
  CHECK(vehicle.category == VehicleCategory::kTrailer);
  CHECK(vehicle.performance.max_speed == Approx(250.0 / 3.6));
  REQUIRE(vehicle.catalog.has_value());
  CHECK(vehicle.catalog->catalog_name == "VehicleCatalog");
  CHECK(vehicle.catalog->entry_name == "car_trailer");
  CHECK(vehicle.source.file_name() ==
        (kAsamExamples / "Catalogs/Vehicles/VehicleCatalog.xosc").lexically_normal().string());
  REQUIRE(vehicle.trailer_coupler.has_value());
  CHECK(vehicle.trailer_coupler->dx == 3.25);
  REQUIRE(scenario.catalog_files.size() == 1);
}

TEST_CASE("catalog entry names given by parameters and route catalogs resolve", "[xosc][model]") {
  const Scenario scenario = load("SynchronizedArrivalToIntersection.xosc");
  const auto& ego = std::get<Vehicle>(scenario.entities.objects.at(0).object);
  CHECK(ego.name == "car1");  // entryName="$HostVehicle"
  CHECK(scenario.catalog_files.size() == 2);
  const auto& assign =
      std::get<AssignRouteAction>(scenario.storyboard.init.privates.at(0).actions.at(0));
  CHECK(assign.route.name == "HostStraightRoute");
  CHECK(assign.route.waypoints.size() == 2);
  CHECK(std::get<LanePosition>(assign.route.waypoints[0].position.kind).s == 63.0);
}

TEST_CASE("storyboard element references resolve to full paths", "[xosc][model]") {
  const Scenario scenario = load("CutIn.xosc");
  const auto& stop = scenario.storyboard.stop_trigger;
  REQUIRE(stop.has_value());
  const auto& condition = std::get<StoryboardElementStateCondition>(
      std::get<ByValueCondition>(stop->groups.at(0).conditions.at(0).kind));
  CHECK(condition.storyboard_element_ref == "Act1");
  CHECK(condition.resolved_path == "MyStory::Act1");
  CHECK(condition.type == StoryboardElementType::kAct);
}

TEST_CASE("event_actions lists every event's actions in document order", "[xosc][model]") {
  const auto actions = [](std::initializer_list<const char*> names) {
    std::vector<Action> out;
    for (const char* name : names) {
      out.emplace_back().name = name;
    }
    return out;
  };
  Storyboard board;
  board.stories.resize(2);
  board.stories[0].acts.resize(2);  // the second act has no groups
  auto& groups = board.stories[0].acts[0].maneuver_groups;
  groups.resize(2);
  groups[0].maneuvers.resize(1);
  groups[0].maneuvers[0].events.resize(3);  // the second event has no actions
  groups[0].maneuvers[0].events[0].actions = actions({"a", "b"});
  groups[0].maneuvers[0].events[2].actions = actions({"c"});
  groups[1].maneuvers.resize(2);
  groups[1].maneuvers[1].events.resize(1);
  groups[1].maneuvers[1].events[0].actions = actions({"d"});
  auto& last = board.stories[1].acts.emplace_back().maneuver_groups.emplace_back();
  last.maneuvers.emplace_back().events.emplace_back().actions = actions({"e", "f"});
  std::vector<std::string> names;
  for (const Action* action : event_actions(board)) {
    names.push_back(action->name);
  }
  CHECK(names == std::vector<std::string>{"a", "b", "c", "d", "e", "f"});
  CHECK(event_actions(board).front() == &groups[0].maneuvers[0].events[0].actions[0]);
  CHECK(event_actions(Storyboard{}).empty());
}

TEST_CASE("the road network LogicFile resolves against the scenario's folder", "[xosc][model]") {
  const Scenario scenario = load("CutIn.xosc");
  CHECK(scenario.road_network.logic_file->filepath == "Databases/AB_RQ31_Straight.xodr");
  CHECK(scenario.road_network.logic_file_path ==
        fs::absolute(kAsamExamples / "Databases/AB_RQ31_Straight.xodr").lexically_normal());
}

TEST_CASE("parameter overrides replace declared values before anything uses them",
          "[xosc][model]") {
  LoadOptions options;
  options.parameters = {{"Speed", "7.5"}, {"TrajRadius", "20"}};
  const Scenario scenario = load("TrailerConnect.xosc", options);
  const ParameterDeclaration* speed = scenario.find_parameter("Speed");
  REQUIRE(speed != nullptr);
  CHECK(speed->overridden);
  CHECK(speed->declared_text == "7.5");
  CHECK(std::get<double>(speed->value.data) == 7.5);
  const auto& car = scenario.storyboard.init.privates[1];
  const auto& world =
      std::get<WorldPosition>(std::get<TeleportAction>(car.actions.at(0)).position.kind);
  CHECK(world.x == Approx(1.7 - 20.0));
}
