// The 0.9-to-1.0 mapping of the 0.9.1 schema's forms beyond esmini's and CARLA's examples
// (docs/openscenario.md, "OpenSCENARIO 0.9 drafts"): the entity conditions Collision,
// TimeToCollision, ReachPosition and Distance, ByValue TimeOfDay, the "scene" element type,
// Visibility, Autonomous, the distance actions, LaneOffset, Routing (an inline Route and
// Trajectory, AcquirePosition), Global Entity and Parameter, and a maxSteering in degrees.

#include <catch2/catch.hpp>

#include "lenient_load.h"
#include "osc09_draft.h"

namespace corsa::test {
namespace {

// A 0.9 Condition of Ego's `entity_condition`.
std::string by_ego(const std::string& name, const std::string& entity_condition) {
  return "<Condition name=\"" + name +
         "\" delay=\"0\" edge=\"rising\">\n<ByEntity>\n<TriggeringEntities rule=\"any\">\n"
         "<Entity name=\"Ego\"/>\n</TriggeringEntities>\n<EntityCondition>\n" +
         entity_condition + "</EntityCondition>\n</ByEntity>\n</Condition>\n";
}

const xosc::EntityCondition& entity_condition(const xosc::Event& event, size_t at) {
  return std::get<xosc::ByEntityCondition>(event.start_trigger->groups.at(0).conditions.at(at).kind)
      .condition;
}

TEST_CASE("the 0.9.1 schema's entity and value conditions are read as 1.0", "[xosc][osc09]") {
  std::string xml = osc09_draft();
  replace_once(xml,
               "<Condition name=\"C\" delay=\"0\" edge=\"rising\">\n<ByState>\n"
               "<AtStart type=\"act\" name=\"A\"/>\n</ByState>\n</Condition>\n",
               by_ego("Hit", "<Collision>\n<ByEntity name=\"Ego\"/>\n</Collision>\n") +
                   by_ego("Soon",
                          "<TimeToCollision value=\"3\" freespace=\"false\" "
                          "alongRoute=\"false\" rule=\"less_than\">\n<Target>\n"
                          "<Entity name=\"Ego\"/>\n</Target>\n</TimeToCollision>\n") +
                   by_ego("There",
                          "<ReachPosition tolerance=\"2\">\n<Position>\n"
                          "<World x=\"50\" y=\"0\"/>\n</Position>\n</ReachPosition>\n") +
                   by_ego("Near",
                          "<Distance value=\"10\" freespace=\"false\" alongRoute=\"false\" "
                          "rule=\"less_than\">\n<Position>\n<World x=\"60\" y=\"0\"/>\n"
                          "</Position>\n</Distance>\n") +
                   "<Condition name=\"Noon\" delay=\"0\" edge=\"rising\">\n<ByValue>\n"
                   "<TimeOfDay rule=\"greater_than\">\n<Time hour=\"12\" min=\"0\" sec=\"0\"/>\n"
                   "<Date day=\"1\" month=\"7\" year=\"2020\"/>\n</TimeOfDay>\n</ByValue>\n"
                   "</Condition>\n"
                   "<Condition name=\"Done\" delay=\"0\" edge=\"rising\">\n<ByState>\n"
                   "<AfterTermination type=\"scene\" name=\"Q\" rule=\"end\"/>\n</ByState>\n"
                   "</Condition>\n");
  const xosc::Scenario scenario = load_with_warning(xml, "OpenSCENARIO 0.9 draft");
  const xosc::Event& event = first_event(scenario);
  const auto& hit = std::get<xosc::CollisionCondition>(entity_condition(event, 0));
  CHECK(hit.entity_ref == "Ego");
  const auto& soon = std::get<xosc::TimeToCollisionCondition>(entity_condition(event, 1));
  CHECK(soon.value == 3.0);
  CHECK(soon.rule == xosc::Rule::kLessThan);
  CHECK(soon.target_entity_ref == "Ego");
  const auto& there = std::get<xosc::ReachPositionCondition>(entity_condition(event, 2));
  CHECK(there.tolerance == 2.0);
  CHECK(std::get<xosc::WorldPosition>(there.position.kind).x == 50.0);
  const auto& near = std::get<xosc::DistanceCondition>(entity_condition(event, 3));
  CHECK(near.value == 10.0);
  CHECK(std::get<xosc::WorldPosition>(near.position.kind).x == 60.0);
  const auto& conditions = event.start_trigger->groups.at(0).conditions;
  const auto& noon =
      std::get<xosc::TimeOfDayCondition>(std::get<xosc::ByValueCondition>(conditions.at(4).kind));
  CHECK(noon.date_time == "2020-07-01T12:00:00");
  CHECK(noon.rule == xosc::Rule::kGreaterThan);
  const auto& done = std::get<xosc::StoryboardElementStateCondition>(
      std::get<xosc::ByValueCondition>(conditions.at(5).kind));
  CHECK(done.type == xosc::StoryboardElementType::kManeuverGroup);
  CHECK(done.state == xosc::StoryboardElementState::kEndTransition);
}

TEST_CASE("the 0.9.1 schema's private and global actions are read as 1.0", "[xosc][osc09]") {
  const std::string xml = osc09_draft_doing(
      "<Action name=\"Hide\">\n<Private>\n<Visibility graphics=\"false\" traffic=\"true\" "
      "sensors=\"true\"/>\n</Private>\n</Action>\n"
      "<Action name=\"Auto\">\n<Private>\n<Autonomous activate=\"false\" domain=\"both\"/>\n"
      "</Private>\n</Action>\n"
      "<Action name=\"Keep\">\n<Private>\n<Longitudinal>\n<Distance object=\"Ego\" "
      "timeGap=\"2\" freespace=\"true\">\n<Dynamics>\n<Limited maxAcceleration=\"3\" "
      "maxDeceleration=\"6\" maxSpeed=\"30\"/>\n</Dynamics>\n</Distance>\n</Longitudinal>\n"
      "</Private>\n</Action>\n"
      "<Action name=\"Shift\">\n<Private>\n<Lateral>\n<LaneOffset>\n"
      "<Dynamics maxLateralAcc=\"0.5\" duration=\"3\" shape=\"sinusoidal\"/>\n<Target>\n"
      "<Absolute value=\"0.4\"/>\n</Target>\n</LaneOffset>\n</Lateral>\n</Private>\n"
      "</Action>\n"
      "<Action name=\"Go\">\n<Private>\n<Routing>\n<AcquirePosition>\n<Position>\n"
      "<World x=\"80\" y=\"0\"/>\n</Position>\n</AcquirePosition>\n</Routing>\n</Private>\n"
      "</Action>\n"
      "<Action name=\"Set\">\n<Global>\n<Parameter name=\"$Speed\">\n<Set value=\"12\"/>\n"
      "</Parameter>\n</Global>\n</Action>\n"
      "<Action name=\"Gone\">\n<Global>\n<Entity name=\"Ego\">\n<Delete/>\n</Entity>\n"
      "</Global>\n</Action>\n");
  const xosc::Scenario scenario =
      load_with_warning(xml, "0.9 LaneOffset Dynamics duration=\"3\"", line_of(xml, "duration="));
  const auto& actions = first_event(scenario).actions;
  REQUIRE(actions.size() == 7);
  const auto private_action = [&](size_t at) {
    return std::get<xosc::PrivateAction>(actions.at(at).action);
  };
  CHECK(std::get<xosc::VisibilityAction>(private_action(0)).graphics == false);
  const auto controller = std::get<xosc::ActivateControllerAction>(private_action(1));
  CHECK(controller.lateral == false);
  CHECK(controller.longitudinal == false);
  const auto keep = std::get<xosc::LongitudinalDistanceAction>(private_action(2));
  CHECK(keep.entity_ref == "Ego");
  CHECK(keep.time_gap == 2.0);
  CHECK(keep.continuous);
  REQUIRE(keep.constraints.has_value());
  CHECK(keep.constraints->max_deceleration == 6.0);
  const auto shift = std::get<xosc::LaneOffsetAction>(private_action(3));
  CHECK(shift.shape == xosc::DynamicsShape::kSinusoidal);
  CHECK(shift.max_lateral_acc == 0.5);
  CHECK(std::get<xosc::AbsoluteTargetLaneOffset>(shift.target).value == 0.4);
  const auto go = std::get<xosc::AcquirePositionAction>(private_action(4));
  CHECK(std::get<xosc::WorldPosition>(go.position.kind).x == 80.0);
  const auto& set = std::get<xosc::GlobalAction>(actions.at(5).action);
  CHECK(std::get<xosc::ParameterSetAction>(set).parameter_ref == "Speed");
  const auto& gone = std::get<xosc::GlobalAction>(actions.at(6).action);
  CHECK(std::get<xosc::DeleteEntityAction>(gone).entity_ref == "Ego");
}

const std::string kTrajectory =
    "<Action name=\"Path\">\n<Private>\n<Routing>\n<FollowTrajectory>\n"
    "<Trajectory name=\"T\" closed=\"false\" domain=\"time\">\n"
    "<Vertex reference=\"0\">\n<Position>\n<World x=\"0\" y=\"0\"/>\n</Position>\n"
    "<Shape>\n<Polyline/>\n</Shape>\n</Vertex>\n"
    "<Vertex reference=\"4\">\n<Position>\n<World x=\"40\" y=\"1\"/>\n</Position>\n"
    "<Shape>\n<Clothoid curvature=\"0\" curvatureDot=\"0\" length=\"40\"/>\n</Shape>\n</Vertex>\n"
    "</Trajectory>\n<Longitudinal>\n<Timing domain=\"relative\" scale=\"1\" offset=\"0\"/>\n"
    "</Longitudinal>\n<Lateral purpose=\"steering\"/>\n</FollowTrajectory>\n</Routing>\n"
    "</Private>\n</Action>\n";

TEST_CASE("an inline 0.9 Trajectory is read as a 1.0 Polyline, warned", "[xosc][osc09]") {
  const std::string xml = osc09_draft_doing(kTrajectory);
  check_both_ways(xml, "0.9 Trajectory of 2 Vertex elements, each with a Shape of its own",
                  line_of(xml, "<Trajectory"));
  const xosc::Scenario scenario = load_with_warning(xml, "(Clothoid among them)");
  const auto& follow = std::get<xosc::FollowTrajectoryAction>(
      std::get<xosc::PrivateAction>(first_event(scenario).actions.at(0).action));
  CHECK(follow.following_mode == xosc::FollowingMode::kFollow);
  REQUIRE(follow.time_reference.timing.has_value());
  CHECK(follow.time_reference.timing->domain_absolute_relative ==
        xosc::ReferenceContext::kRelative);
  const auto& polyline = std::get<xosc::Polyline>(follow.trajectory.shape);
  REQUIRE(polyline.vertices.size() == 2);
  CHECK(polyline.vertices[1].time == 4.0);
  CHECK(std::get<xosc::WorldPosition>(polyline.vertices[1].position.kind).x == 40.0);

  // A distance domain has no 1.0 place: the vertices have no times.
  std::string by_distance = xml;
  replace_once(by_distance, "domain=\"time\"", "domain=\"distance\"");
  const xosc::Scenario distance = load_with_warning(by_distance, "without times (domain distance)");
  const auto& untimed = std::get<xosc::Polyline>(
      std::get<xosc::FollowTrajectoryAction>(
          std::get<xosc::PrivateAction>(first_event(distance).actions.at(0).action))
          .trajectory.shape);
  CHECK(!untimed.vertices[1].time.has_value());
}

TEST_CASE("an inline 0.9 Route is read as 1.0, named in the draft's warning", "[xosc][osc09]") {
  const std::string xml = osc09_draft_doing(
      "<Action name=\"Way\">\n<Private>\n<Routing>\n<FollowRoute>\n"
      "<Route name=\"R\" closed=\"false\">\n<Waypoint strategy=\"shortest\">\n<Position>\n"
      "<World x=\"0\" y=\"0\"/>\n</Position>\n</Waypoint>\n<Waypoint strategy=\"fastest\">\n"
      "<Position>\n<World x=\"90\" y=\"0\"/>\n</Position>\n</Waypoint>\n</Route>\n"
      "</FollowRoute>\n</Routing>\n</Private>\n</Action>\n");
  const xosc::Scenario scenario = load_with_warning(xml, "inline Route");
  const auto& assign = std::get<xosc::AssignRouteAction>(
      std::get<xosc::PrivateAction>(first_event(scenario).actions.at(0).action));
  REQUIRE(assign.route.waypoints.size() == 2);
  CHECK(assign.route.waypoints[1].route_strategy == xosc::RouteStrategy::kFastest);
}

TEST_CASE("a 0.9 maxSteering past pi/2 is read as degrees, warned", "[xosc][osc09]") {
  std::string xml = osc09_draft();
  replace_once(xml, "maxSteering=\"0.5\"", "maxSteering=\"30\"");
  check_both_ways(xml, "0.9 maxSteering=\"30\" is more than pi/2 rad", line_of(xml, "\"30\""));
  const xosc::Scenario scenario = load_with_warning(xml, "degrees: 0.523599 rad");
  const auto& vehicle = std::get<xosc::Vehicle>(scenario.entities.objects.at(0).object);
  CHECK(vehicle.axles.front_axle->max_steering == Approx(0.523599));
  // Radians stay as written.
  CHECK(std::get<xosc::Vehicle>(
            load_without_errors(osc09_draft()).scenario->entities.objects[0].object)
            .axles.front_axle->max_steering == 0.5);
}

}  // namespace
}  // namespace corsa::test
