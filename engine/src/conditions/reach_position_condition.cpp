// ReachPositionCondition (OpenSCENARIO 1.3 §8.3.1, deprecated for DistanceCondition): the
// entity's reference point is within `tolerance` metres of a position.

#include <cmath>

#include "conditions/condition_makers.h"
#include "positions/position_resolver.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class ReachPositionCheck final : public EntityCondition {
 public:
  explicit ReachPositionCheck(const xosc::ReachPositionCondition& c) : c_(c) {}
  bool holds(const SimState& state, uint32_t entity) override {
    const ResolvedPosition target = resolve_position(c_.position, state, entity);
    const Pose& p = state.world.entities[entity].state.pose;
    return std::hypot(target.pose.x - p.x, target.pose.y - p.y) <= c_.tolerance;
  }

 private:
  const xosc::ReachPositionCondition& c_;
};

}  // namespace

std::unique_ptr<EntityCondition> make_reach_position(const xosc::ReachPositionCondition& c,
                                                     const SimState&) {
  return std::make_unique<ReachPositionCheck>(c);
}

}  // namespace corsa::engine::detail
