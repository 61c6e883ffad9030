#include <cmath>
#include <map>
#include <type_traits>

#include "conditions/condition_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

bool compare(double value, xosc::Rule rule, double reference) {
  const bool equal = std::abs(value - reference) <= 1e-9 * std::max(1.0, std::abs(reference));
  switch (rule) {
    case xosc::Rule::kEqualTo:
      return equal;
    case xosc::Rule::kNotEqualTo:
      return !equal;
    case xosc::Rule::kGreaterThan:
      return value > reference && !equal;
    case xosc::Rule::kLessThan:
      return value < reference && !equal;
    case xosc::Rule::kGreaterOrEqual:
      return value > reference || equal;
    case xosc::Rule::kLessOrEqual:
      return value < reference || equal;
  }
  return false;
}

void share_equal_conditions(const std::vector<EntityCondition*>& conditions) {
  // The first condition of each key keeps the memo the later ones share.
  std::map<std::string, EntityCondition*> first;
  for (EntityCondition* condition : conditions) {
    std::string key = condition->value_key();
    if (key.empty()) continue;
    const auto [it, added] = first.emplace(std::move(key), condition);
    if (!added) condition->share_values(*it->second);
  }
}

uint32_t need_entity_index(const SimState& state, const std::string& name,
                           const xosc::Source& source) {
  const auto index = state.world.find(name);
  if (!index) {
    throw InputError(source.error("unknown entity '" + name + "'"));
  }
  return *index;
}

std::unique_ptr<EntityCondition> make_entity_condition(const xosc::EntityCondition& condition,
                                                       const SimState& state) {
  return std::visit(
      [&](const auto& c) -> std::unique_ptr<EntityCondition> {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, xosc::EndOfRoadCondition>) {
          return make_end_of_road(c, state);
        } else if constexpr (std::is_same_v<T, xosc::CollisionCondition>) {
          return make_collision(c, state);
        } else if constexpr (std::is_same_v<T, xosc::OffroadCondition>) {
          return make_offroad(c, state);
        } else if constexpr (std::is_same_v<T, xosc::TimeHeadwayCondition>) {
          return make_time_headway(c, state);
        } else if constexpr (std::is_same_v<T, xosc::TimeToCollisionCondition>) {
          return make_time_to_collision(c, state);
        } else if constexpr (std::is_same_v<T, xosc::AccelerationCondition>) {
          return make_acceleration(c, state);
        } else if constexpr (std::is_same_v<T, xosc::StandStillCondition>) {
          return make_stand_still(c, state);
        } else if constexpr (std::is_same_v<T, xosc::SpeedCondition>) {
          return make_speed(c, state);
        } else if constexpr (std::is_same_v<T, xosc::RelativeSpeedCondition>) {
          return make_relative_speed(c, state);
        } else if constexpr (std::is_same_v<T, xosc::TraveledDistanceCondition>) {
          return make_traveled_distance(c, state);
        } else if constexpr (std::is_same_v<T, xosc::ReachPositionCondition>) {
          return make_reach_position(c, state);
        } else if constexpr (std::is_same_v<T, xosc::DistanceCondition>) {
          return make_distance(c, state);
        } else if constexpr (std::is_same_v<T, xosc::RelativeDistanceCondition>) {
          return make_relative_distance(c, state);
        } else if constexpr (std::is_same_v<T, xosc::RelativeClearanceCondition>) {
          return make_relative_clearance(c, state);
        } else if constexpr (std::is_same_v<T, xosc::AngleCondition>) {
          return make_angle(c, state);
        } else {
          return make_relative_angle(c, state);
        }
      },
      condition);
}

std::unique_ptr<ValueCondition> make_value_condition(const xosc::ByValueCondition& condition,
                                                     const SimState& state) {
  return std::visit(
      [&](const auto& c) -> std::unique_ptr<ValueCondition> {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, xosc::SimulationTimeCondition>) {
          return make_simulation_time(c, state);
        } else if constexpr (std::is_same_v<T, xosc::StoryboardElementStateCondition>) {
          return make_storyboard_element_state(c, state);
        } else if constexpr (std::is_same_v<T, xosc::ParameterCondition>) {
          return make_parameter(c, state);
        } else if constexpr (std::is_same_v<T, xosc::VariableCondition>) {
          return make_variable(c, state);
        } else if constexpr (std::is_same_v<T, xosc::TimeOfDayCondition>) {
          return make_time_of_day(c, state);
        } else if constexpr (std::is_same_v<T, xosc::UserDefinedValueCondition>) {
          return make_user_defined_value(c, state);
        } else if constexpr (std::is_same_v<T, xosc::TrafficSignalCondition>) {
          return make_traffic_signal_condition(c, state);
        } else {
          return make_traffic_signal_controller_condition(c, state);
        }
      },
      condition);
}

}  // namespace corsa::engine::detail
