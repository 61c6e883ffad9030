#pragma once

// One factory function per condition kind, each defined in the condition's own file.

#include <memory>

#include "conditions/condition.h"

namespace corsa::engine::detail {

// By entity
std::unique_ptr<EntityCondition> make_end_of_road(const xosc::EndOfRoadCondition& c,
                                                  const SimState& state);
std::unique_ptr<EntityCondition> make_collision(const xosc::CollisionCondition& c,
                                                const SimState& state);
std::unique_ptr<EntityCondition> make_offroad(const xosc::OffroadCondition& c,
                                              const SimState& state);
std::unique_ptr<EntityCondition> make_time_headway(const xosc::TimeHeadwayCondition& c,
                                                   const SimState& state);
std::unique_ptr<EntityCondition> make_time_to_collision(const xosc::TimeToCollisionCondition& c,
                                                        const SimState& state);
std::unique_ptr<EntityCondition> make_acceleration(const xosc::AccelerationCondition& c,
                                                   const SimState& state);
std::unique_ptr<EntityCondition> make_stand_still(const xosc::StandStillCondition& c,
                                                  const SimState& state);
std::unique_ptr<EntityCondition> make_speed(const xosc::SpeedCondition& c, const SimState& state);
std::unique_ptr<EntityCondition> make_relative_speed(const xosc::RelativeSpeedCondition& c,
                                                     const SimState& state);
std::unique_ptr<EntityCondition> make_traveled_distance(const xosc::TraveledDistanceCondition& c,
                                                        const SimState& state);
std::unique_ptr<EntityCondition> make_reach_position(const xosc::ReachPositionCondition& c,
                                                     const SimState& state);
std::unique_ptr<EntityCondition> make_distance(const xosc::DistanceCondition& c,
                                               const SimState& state);
std::unique_ptr<EntityCondition> make_relative_distance(const xosc::RelativeDistanceCondition& c,
                                                        const SimState& state);
std::unique_ptr<EntityCondition> make_relative_clearance(const xosc::RelativeClearanceCondition& c,
                                                         const SimState& state);
std::unique_ptr<EntityCondition> make_angle(const xosc::AngleCondition& c, const SimState& state);
std::unique_ptr<EntityCondition> make_relative_angle(const xosc::RelativeAngleCondition& c,
                                                     const SimState& state);

// By value
std::unique_ptr<ValueCondition> make_simulation_time(const xosc::SimulationTimeCondition& c,
                                                     const SimState& state);
/// A SimulationTimeCondition whose value counts `shift` s later (negative: earlier), as the
/// triggers that esmini's ghost takes over (controllers/follow_ghost.h) read it.
std::unique_ptr<ValueCondition> make_shifted_simulation_time(const xosc::SimulationTimeCondition& c,
                                                             double shift);
std::unique_ptr<ValueCondition> make_storyboard_element_state(
    const xosc::StoryboardElementStateCondition& c, const SimState& state);
std::unique_ptr<ValueCondition> make_parameter(const xosc::ParameterCondition& c,
                                               const SimState& state);
std::unique_ptr<ValueCondition> make_variable(const xosc::VariableCondition& c,
                                              const SimState& state);
std::unique_ptr<ValueCondition> make_user_defined_value(const xosc::UserDefinedValueCondition& c,
                                                        const SimState& state);
std::unique_ptr<ValueCondition> make_time_of_day(const xosc::TimeOfDayCondition& c,
                                                 const SimState& state);
std::unique_ptr<ValueCondition> make_traffic_signal_condition(const xosc::TrafficSignalCondition& c,
                                                              const SimState& state);
std::unique_ptr<ValueCondition> make_traffic_signal_controller_condition(
    const xosc::TrafficSignalControllerCondition& c, const SimState& state);

/// The entity index of `name`; InputError located at `source` when there is no such entity.
uint32_t need_entity_index(const SimState& state, const std::string& name,
                           const xosc::Source& source);

}  // namespace corsa::engine::detail
