// AccelerationCondition (OpenSCENARIO 1.3 §8.3.1): the entity's acceleration over the last step
// compared with a value; with a direction, that component (longitudinal, lateral; vertical 0);
// without, the magnitude.

#include <cmath>

#include "conditions/condition_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class AccelerationCheck final : public EntityCondition {
 public:
  explicit AccelerationCheck(const xosc::AccelerationCondition& c) : c_(c) {}
  bool holds(const SimState& state, uint32_t entity) override {
    const Entity& e = state.world.entities[entity];
    double value = std::hypot(e.state().acceleration, e.lateral_acceleration);
    if (c_.direction) {
      switch (*c_.direction) {
        case xosc::DirectionalDimension::kLongitudinal:
          value = e.state().acceleration;
          break;
        case xosc::DirectionalDimension::kLateral:
          value = e.lateral_acceleration;
          break;
        case xosc::DirectionalDimension::kVertical:
          value = 0.0;
          break;
      }
    }
    return compare(value, c_.rule, c_.value);
  }

 private:
  const xosc::AccelerationCondition& c_;
};

}  // namespace

std::unique_ptr<EntityCondition> make_acceleration(const xosc::AccelerationCondition& c,
                                                   const SimState&) {
  return std::make_unique<AccelerationCheck>(c);
}

}  // namespace corsa::engine::detail
