// RelativeDistanceCondition (OpenSCENARIO 1.3 §8.3.1): the distance from the triggering entity
// to a reference entity (longitudinal, lateral or euclidean; in the entity frame, or road /
// lane coordinates; between reference points or, with freespace, bounding boxes), compared as a
// magnitude with a value.

#include <cmath>

#include "conditions/condition_makers.h"
#include "positions/relative_distance.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class RelativeDistanceCheck final : public EntityCondition {
 public:
  RelativeDistanceCheck(const xosc::RelativeDistanceCondition& c, uint32_t reference)
      : c_(c), reference_(reference) {
    spec_.system = coordinate_system(c.coordinate_system, std::nullopt);
    spec_.type = c.relative_distance_type;
    spec_.freespace = c.freespace;
  }
  bool holds(const SimState& state, uint32_t entity) override {
    if (entity == reference_) {
      return false;
    }
    const double d = entity_distance(state, state.world.entities[entity],
                                     state.world.entities[reference_], spec_);
    return compare(std::abs(d), c_.rule, c_.value);
  }

 private:
  const xosc::RelativeDistanceCondition& c_;
  uint32_t reference_;
  DistanceSpec spec_;
};

}  // namespace

std::unique_ptr<EntityCondition> make_relative_distance(const xosc::RelativeDistanceCondition& c,
                                                        const SimState& state) {
  return std::make_unique<RelativeDistanceCheck>(c,
                                                 need_entity_index(state, c.entity_ref, c.source));
}

}  // namespace corsa::engine::detail
