// Control from outside the scenario (corsa/engine/external_control.h): commands that take the
// place of a controller for one step (pose, speed, vehicle controls), entities of an external
// controller that move only by commands, and the values of UserDefinedValueConditions.

#include <cmath>
#include <stdexcept>

#include "engine_fixture.h"

namespace corsa::test {
namespace {

using Catch::Detail::Approx;
using engine::ExternalCommand;

engine::SimulationOptions external_options() {
  engine::SimulationOptions options;
  options.external_controllers = {"ExternalController"};
  return options;
}

ExternalCommand speed_command(double speed) {
  ExternalCommand command;
  command.speed = speed;
  return command;
}

bool warned(const Diagnostics& diagnostics, const std::string& text) {
  for (const Diagnostic& d : diagnostics.all()) {
    if (d.message.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST_CASE("An entity of an external controller ignores the scenario's actions and keeps its speed",
          "[engine][external]") {
  // Without the option the scenario's controller is a foreign one: the default controller moves
  // Ego and the story's SpeedAction takes it to 30 m/s at 1 s.
  FixtureRun scenario_driven(engine_fixture("external_control.xosc"));
  scenario_driven.run();
  CHECK_FALSE(scenario_driven.sim().external(scenario_driven.entity("Ego")));
  CHECK(scenario_driven.at(3.0, "Ego").speed == Approx(30.0));

  FixtureRun run(engine_fixture("external_control.xosc"), external_options());
  CHECK(run.sim().external(run.entity("Ego")));
  CHECK_FALSE(run.sim().external(run.entity("Npc")));
  run.run();
  CHECK(run.at(3.0, "Ego").speed == Approx(10.0));
  // It still drives along its lane at the speed it had (Init's 10 m/s).
  const auto& ego = run.at(3.0, "Ego");
  REQUIRE(ego.road);
  CHECK(ego.road->lane == -1);
  CHECK(ego.pose.x == Approx(10.0 + 3.0 * 10.0).margin(1e-6));
  CHECK(ego.pose.y == Approx(-1.75).margin(1e-9));
}

TEST_CASE("A speed command moves the entity at that speed; an external entity holds it",
          "[engine][external]") {
  FixtureRun run(engine_fixture("external_control.xosc"), external_options());
  auto& sim = run.sim();
  const size_t ego = run.entity("Ego");
  const size_t npc = run.entity("Npc");
  REQUIRE(sim.step());  // tick 0 -> 1 at Init speeds
  const double x0 = sim.state(ego).pose.x;
  sim.command(ego, speed_command(16.0));
  sim.command(npc, speed_command(0.0));
  REQUIRE(sim.step());
  // The step travels its end speed, as the default controller moves every entity.
  CHECK(sim.state(ego).speed == 16.0);
  CHECK(sim.state(ego).pose.x == Approx(x0 + 0.01 * 16.0));
  CHECK(sim.state(npc).speed == 0.0);
  // No new command: Ego (external) holds 16 m/s, Npc's controller takes over again at 20 m/s.
  REQUIRE(sim.step());
  CHECK(sim.state(ego).speed == 16.0);
  CHECK(sim.state(npc).speed == 20.0);
}

TEST_CASE("A pose command places the entity and its lane follows; speed as given or kept",
          "[engine][external]") {
  FixtureRun run(engine_fixture("external_control.xosc"), external_options());
  auto& sim = run.sim();
  const size_t ego = run.entity("Ego");
  REQUIRE(sim.step());
  ExternalCommand command;
  command.pose = engine::Pose{200.0, -5.25, 0.0, 0.1, 0.0, 0.0};
  sim.command(ego, command);
  REQUIRE(sim.step());
  const auto& placed = sim.state(ego);
  CHECK(placed.pose.x == 200.0);
  CHECK(placed.pose.y == -5.25);
  CHECK(placed.pose.h == 0.1);
  CHECK(placed.speed == 10.0);  // kept
  REQUIRE(placed.road);
  CHECK(placed.road->lane == -2);
  CHECK(placed.road->s == Approx(200.0));

  command.pose = engine::Pose{210.0, -5.25, 0.0, 0.0, 0.0, 0.0};
  command.speed = 4.0;
  sim.command(ego, command);
  REQUIRE(sim.step());
  CHECK(sim.state(ego).speed == 4.0);
  // Then it rolls on along lane -2 at 4 m/s.
  REQUIRE(sim.step());
  CHECK(sim.state(ego).pose.x == Approx(210.04));
  CHECK(sim.state(ego).pose.y == Approx(-5.25));
}

TEST_CASE("Controls drive the vehicle model for the commanded steps only",
          "[engine][external][dynamics]") {
  FixtureRun run(engine_fixture("external_control.xosc"), external_options());
  auto& sim = run.sim();
  const size_t npc = run.entity("Npc");
  REQUIRE(sim.step());
  ExternalCommand command;
  command.controls = engine::VehicleControls{1.0, 0.0, 0.05};
  for (int i = 0; i < 100; ++i) {
    sim.command(npc, command);
    REQUIRE(sim.step());
  }
  // One second of full throttle (10 m/s^2 through a 0.15 s drive lag) and a left wheel angle.
  const auto& driven = sim.state(npc);
  CHECK(driven.speed > 27.0);
  CHECK(driven.speed < 30.0);
  CHECK(driven.pose.h > 0.1);
  CHECK(driven.pose.y > -5.25 + 1.0);
  // Without commands the default controller moves it again, at its commanded 20 m/s.
  REQUIRE(sim.step());
  CHECK(sim.state(npc).speed == 20.0);

  // Held controls: an external entity keeps the last ones (full brake stops it and it stays).
  const size_t ego = run.entity("Ego");
  command.controls = engine::VehicleControls{0.0, 1.0, 0.0};
  sim.command(ego, command);
  for (int i = 0; i < 300; ++i) REQUIRE(sim.step());
  CHECK(sim.state(ego).speed == 0.0);
}

TEST_CASE("A bad command is refused before it reaches the run", "[engine][external]") {
  FixtureRun run(engine_fixture("external_control.xosc"), external_options());
  auto& sim = run.sim();
  CHECK_THROWS_AS(sim.command(5, speed_command(1.0)), std::invalid_argument);
  CHECK_THROWS_AS(sim.command(0, speed_command(std::nan(""))), std::invalid_argument);
  ExternalCommand both;
  both.pose = engine::Pose{};
  both.controls = engine::VehicleControls{};
  CHECK_THROWS_AS(sim.command(0, both), std::invalid_argument);
  ExternalCommand throttle;
  throttle.controls = engine::VehicleControls{1.5, 0.0, 0.0};
  CHECK_THROWS_AS(sim.command(0, throttle), std::invalid_argument);
}

TEST_CASE("UserDefinedValueConditions compare the provider's values", "[engine][external]") {
  FixtureRun run(engine_fixture("external_control.xosc"), external_options());
  std::vector<std::string> asked;
  run.sim().set_user_value_provider([&](std::string_view name) -> std::optional<xosc::Value> {
    asked.emplace_back(name);
    return xosc::Value{xosc::ParameterType::kBoolean, run.sim().time() >= 2.0};
  });
  run.run();
  REQUIRE_FALSE(asked.empty());
  CHECK(asked.front() == "ego_ready");
  CHECK(run.first("NpcSlow", engine::TransitionKind::kStart) == Approx(2.0));
  CHECK(run.at(3.0, "Npc").speed == 5.0);
  CHECK_FALSE(warned(run.diagnostics(), "UserDefinedValueCondition"));
}

TEST_CASE("A number compares numerically, text as text", "[engine][external]") {
  FixtureRun run(engine_fixture("external_control.xosc"), external_options());
  // "true" is not a number: the provided 1.0 is compared as the text "1", never equal.
  run.sim().set_user_value_provider([](std::string_view) -> std::optional<xosc::Value> {
    return xosc::Value{xosc::ParameterType::kDouble, 1.0};
  });
  run.run();
  CHECK_FALSE(run.first("NpcSlow", engine::TransitionKind::kStart));

  FixtureRun text(engine_fixture("external_control.xosc"), external_options());
  text.sim().set_user_value_provider([](std::string_view) -> std::optional<xosc::Value> {
    return xosc::Value{xosc::ParameterType::kString, std::string("true")};
  });
  text.run();
  CHECK(text.first("NpcSlow", engine::TransitionKind::kStart) == Approx(0.0));
}

TEST_CASE("Without a value a UserDefinedValueCondition never holds and warns where it is",
          "[engine][external]") {
  FixtureRun run(engine_fixture("external_control.xosc"));
  run.run();
  CHECK_FALSE(run.first("NpcSlow", engine::TransitionKind::kStart));
  const auto all = run.diagnostics().all();
  bool located = false;
  for (const Diagnostic& d : all) {
    located = located || (d.message.find("UserDefinedValueCondition 'ego_ready' has no value") !=
                              std::string::npos &&
                          d.line > 0 && d.file.find("external_control.xosc") != std::string::npos);
  }
  CHECK(located);
}

TEST_CASE("Every storyboard element is listed with its state", "[engine][external][storyboard]") {
  FixtureRun run(engine_fixture("external_control.xosc"), external_options());
  run.run();
  const auto elements = run.sim().elements();
  // The storyboard, the story, the act, two groups, maneuvers, events and actions.
  REQUIRE(elements.size() == 11);
  CHECK(elements.front().type == engine::ElementType::kStoryboard);
  CHECK(elements.front().path.empty());
  bool found = false;
  for (const auto& element : elements) {
    CHECK(run.sim().element_state(element.path) == element.state);
    if (element.path == "S::A::EgoGroup::EgoM::EgoFaster") {
      found = true;
      CHECK(element.type == engine::ElementType::kEvent);
      CHECK(element.state == engine::ElementState::kComplete);
    }
  }
  CHECK(found);
}

}  // namespace
}  // namespace corsa::test
