// RelativeSpeedCondition (OpenSCENARIO 1.3 §8.3.1): the triggering entity's speed minus the
// reference entity's, compared with a value; with a direction, the components in the
// triggering entity's frame. esmini's reading (Semantics::kEsmini): the components in the
// reference entity's frame (its direction_dimension_trig: a crossing car's longitudinal
// relative speed reaches -8 m/s at 2.68 s only so).

#include <cmath>

#include "conditions/condition_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

// The relative velocity's component along a direction (vertical: none, entities move in the
// road plane).
double relative_speed_component(xosc::DirectionalDimension direction, double along, double across) {
  switch (direction) {
    case xosc::DirectionalDimension::kLongitudinal:
      return along;
    case xosc::DirectionalDimension::kLateral:
      return across;
    case xosc::DirectionalDimension::kVertical:
      return 0.0;
  }
  return 0.0;
}

class RelativeSpeedCheck final : public EntityCondition {
 public:
  RelativeSpeedCheck(const xosc::RelativeSpeedCondition& c, uint32_t reference)
      : c_(c), reference_(reference) {}
  bool holds(const SimState& state, uint32_t entity) override {
    const EntityState& a = state.world.entities[entity].state();
    const EntityState& b = state.world.entities[reference_].state();
    double difference = 0.0;
    if (!c_.direction) {
      difference = a.speed - b.speed;
    } else if (state.options.semantics == Semantics::kEsmini) {
      // a's velocity in b's frame, less b's own.
      const double dh = a.pose.h - b.pose.h;
      const double a_along = a.speed * std::cos(dh) - a.lateral_speed * std::sin(dh);
      const double a_across = a.speed * std::sin(dh) + a.lateral_speed * std::cos(dh);
      difference =
          relative_speed_component(*c_.direction, a_along - b.speed, a_across - b.lateral_speed);
    } else {
      // b's velocity in a's frame.
      const double dh = b.pose.h - a.pose.h;
      const double b_along = b.speed * std::cos(dh) - b.lateral_speed * std::sin(dh);
      const double b_across = b.speed * std::sin(dh) + b.lateral_speed * std::cos(dh);
      difference =
          relative_speed_component(*c_.direction, a.speed - b_along, a.lateral_speed - b_across);
    }
    return compare(difference, c_.rule, c_.value);
  }

 private:
  const xosc::RelativeSpeedCondition& c_;
  uint32_t reference_;
};

}  // namespace

std::unique_ptr<EntityCondition> make_relative_speed(const xosc::RelativeSpeedCondition& c,
                                                     const SimState& state) {
  return std::make_unique<RelativeSpeedCheck>(c, need_entity_index(state, c.entity_ref, c.source));
}

}  // namespace corsa::engine::detail
