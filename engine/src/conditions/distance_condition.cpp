// DistanceCondition (OpenSCENARIO 1.3 §8.3.1): the distance from the triggering entity to a
// position (resolved anew each time: it may be relative to a moving entity), in a coordinate
// system, of a type, optionally free space, compared with a value. Distances compare as
// magnitudes: a longitudinal distance of 20 m behind is "greater than 10".

#include <cmath>

#include "conditions/condition_makers.h"
#include "positions/relative_distance.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class DistanceCheck final : public EntityCondition {
 public:
  explicit DistanceCheck(const xosc::DistanceCondition& c) : c_(c) {
    spec_.system = coordinate_system(c.coordinate_system, c.along_route);
    spec_.type = c.relative_distance_type.value_or(xosc::RelativeDistanceType::kEuclidianDistance);
    spec_.freespace = c.freespace;
  }
  bool holds(const SimState& state, uint32_t entity) override {
    const ResolvedPosition target = resolve_position(c_.position, state, entity);
    const double d = position_distance(state, state.world.entities[entity], target, spec_);
    return compare(std::abs(d), c_.rule, c_.value);
  }

 private:
  const xosc::DistanceCondition& c_;
  DistanceSpec spec_;
};

}  // namespace

std::unique_ptr<EntityCondition> make_distance(const xosc::DistanceCondition& c, const SimState&) {
  return std::make_unique<DistanceCheck>(c);
}

}  // namespace corsa::engine::detail
