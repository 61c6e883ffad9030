// RelativeSpeedCondition (OpenSCENARIO 1.3 §8.3.1): the triggering entity's speed minus the
// reference entity's, compared with a value; with a direction, the components in the
// triggering entity's frame.

#include <cmath>

#include "conditions/condition_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class RelativeSpeedCheck final : public EntityCondition {
 public:
  RelativeSpeedCheck(const xosc::RelativeSpeedCondition& c, uint32_t reference)
      : c_(c), reference_(reference) {}
  bool holds(const SimState& state, uint32_t entity) override {
    const EntityState& a = state.world.entities[entity].state;
    const EntityState& b = state.world.entities[reference_].state;
    double difference = 0.0;
    if (!c_.direction) {
      difference = a.speed - b.speed;
    } else {
      // b's velocity in a's frame.
      const double dh = b.pose.h - a.pose.h;
      const double b_along = b.speed * std::cos(dh) - b.lateral_speed * std::sin(dh);
      const double b_across = b.speed * std::sin(dh) + b.lateral_speed * std::cos(dh);
      switch (*c_.direction) {
        case xosc::DirectionalDimension::kLongitudinal:
          difference = a.speed - b_along;
          break;
        case xosc::DirectionalDimension::kLateral:
          difference = a.lateral_speed - b_across;
          break;
        case xosc::DirectionalDimension::kVertical:
          difference = 0.0;
          break;
      }
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
