#pragma once

// Factories of the traffic signal conditions (traffic_signal_conditions.cpp).

#include <memory>

#include "conditions/condition.h"

namespace corsa::engine::detail {

std::unique_ptr<ValueCondition> make_traffic_signal_condition(const xosc::TrafficSignalCondition& c,
                                                              const SimState& state);
std::unique_ptr<ValueCondition> make_traffic_signal_controller_condition(
    const xosc::TrafficSignalControllerCondition& c, const SimState& state);

}  // namespace corsa::engine::detail
