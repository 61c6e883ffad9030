// SpeedCondition (OpenSCENARIO 1.3 §8.3.1): the entity's speed compared with a value; with a
// direction, only that component (longitudinal along the heading, lateral across it, vertical
// not modelled: 0); without, the magnitude of the velocity.

#include <cmath>

#include "conditions/condition_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

double directional_speed(const EntityState& state,
                         const std::optional<xosc::DirectionalDimension>& direction) {
  if (!direction) {
    return std::hypot(state.speed, state.lateral_speed);
  }
  switch (*direction) {
    case xosc::DirectionalDimension::kLongitudinal:
      return state.speed;
    case xosc::DirectionalDimension::kLateral:
      return state.lateral_speed;
    case xosc::DirectionalDimension::kVertical:
      return 0.0;
  }
  return state.speed;
}

class SpeedCheck final : public EntityCondition {
 public:
  explicit SpeedCheck(const xosc::SpeedCondition& c) : c_(c) {}
  bool holds(const SimState& state, uint32_t entity) override {
    return compare(directional_speed(state.world.entities[entity].state(), c_.direction), c_.rule,
                   c_.value);
  }
  ConditionInputs inputs() const override { return ConditionInputs::kOwnState; }

 private:
  const xosc::SpeedCondition& c_;
};

}  // namespace

std::unique_ptr<EntityCondition> make_speed(const xosc::SpeedCondition& c, const SimState&) {
  return std::make_unique<SpeedCheck>(c);
}

}  // namespace corsa::engine::detail
