// TraveledDistanceCondition (OpenSCENARIO 1.3 §8.3.1): holds once the entity has driven at least
// `value` metres since the start (its odometer).

#include "conditions/condition_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class TraveledDistanceCheck final : public EntityCondition {
 public:
  explicit TraveledDistanceCheck(double value) : value_(value) {}
  bool holds(const SimState& state, uint32_t entity) override {
    return compare(state.world.entities[entity].state.odometer, xosc::Rule::kGreaterOrEqual,
                   value_);
  }

 private:
  double value_;
};

}  // namespace

std::unique_ptr<EntityCondition> make_traveled_distance(const xosc::TraveledDistanceCondition& c,
                                                        const SimState&) {
  return std::make_unique<TraveledDistanceCheck>(c.value);
}

}  // namespace corsa::engine::detail
