// TimeHeadwayCondition (OpenSCENARIO 1.3 §8.3.1): the time the triggering entity needs, at its
// current speed, to cover the longitudinal distance to a reference entity ahead of it
// (distance / speed). With the reference behind, or when standing, no headway is defined, and
// what the condition then says the standard leaves open: it does not hold, whatever its rule, as
// esmini reads it (its multi_lane_changes waits with `greaterThan` until the car has passed the
// one it watches).

#include <cmath>

#include "conditions/condition_makers.h"
#include "positions/relative_distance.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class TimeHeadwayCheck final : public EntityCondition {
 public:
  TimeHeadwayCheck(const xosc::TimeHeadwayCondition& c, uint32_t reference)
      : c_(c), reference_(reference) {
    spec_.system = coordinate_system(c.coordinate_system, c.along_route);
    spec_.type = xosc::RelativeDistanceType::kLongitudinal;
    spec_.freespace = c.freespace;
  }
  bool holds(const SimState& state, uint32_t entity) override {
    const Entity& from = state.world.entities[entity];
    const double d = entity_distance(state, from, state.world.entities[reference_], spec_);
    const double speed = from.state().speed;
    if (d < 0.0 || speed <= 0.0) {
      return false;  // no headway is defined, and the condition does not hold
    }
    return entity != reference_ && compare(d / speed, c_.rule, c_.value);
  }

 private:
  const xosc::TimeHeadwayCondition& c_;
  uint32_t reference_;
  DistanceSpec spec_;
};

}  // namespace

std::unique_ptr<EntityCondition> make_time_headway(const xosc::TimeHeadwayCondition& c,
                                                   const SimState& state) {
  return std::make_unique<TimeHeadwayCheck>(c, need_entity_index(state, c.entity_ref, c.source));
}

}  // namespace corsa::engine::detail
