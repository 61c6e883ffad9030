// TraveledDistanceCondition (OpenSCENARIO 1.3 §8.3.1): holds once the entity has travelled at
// least `value` metres since the start. The standard does not say how a stepped simulation
// measures the distance travelled; as esmini does, it is the sum of the straight distances
// between the entity's places at the ends of successive steps (Entity::straight_travel), jumps
// to a new place left out. Along a curve that is a little less than the distance along the lane
// (esmini's pedestrian: 4.998 m after five 1 m steps on its curved road), so the condition may
// hold a step later than the odometer (EntityState::odometer, the distance along the path) says.

#include "conditions/condition_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class TraveledDistanceCheck final : public EntityCondition {
 public:
  explicit TraveledDistanceCheck(double value) : value_(value) {}
  bool holds(const SimState& state, uint32_t entity) override {
    return compare(state.world.entities[entity].straight_travel, xosc::Rule::kGreaterOrEqual,
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
