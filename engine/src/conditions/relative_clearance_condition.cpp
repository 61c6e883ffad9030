// RelativeClearanceCondition (OpenSCENARIO 1.3 §8.3.1): holds when no other entity (of the
// listed ones, or any) occupies the given lanes relative to the triggering entity (counted to the
// left of its direction of travel; all lanes when no range is given) within distanceForward
// ahead and distanceBackward behind (missing distances are 0), between reference points or,
// with freeSpace, bounding boxes. Lanes of the opposite direction only count with
// oppositeLanes.

#include <cmath>

#include "conditions/condition_makers.h"
#include "positions/relative_distance.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

// Lanes from `from` to `to` in the same section, the centre lane not counted.
int lane_delta(int from, int to) {
  int delta = to - from;
  if (from < 0 && to > 0) {
    --delta;
  } else if (from > 0 && to < 0) {
    ++delta;
  }
  return delta;
}

class RelativeClearanceCheck final : public EntityCondition {
 public:
  RelativeClearanceCheck(const xosc::RelativeClearanceCondition& c, std::vector<uint32_t> others)
      : c_(c), others_(std::move(others)) {
    spec_.system = xosc::CoordinateSystem::kRoad;
    spec_.type = xosc::RelativeDistanceType::kLongitudinal;
    spec_.freespace = c.free_space;
  }

  bool holds(const SimState& state, uint32_t entity) override {
    const Entity& from = state.world.entities[entity];
    if (!from.state().road || !from.lane.on_road) {
      return false;
    }
    if (others_.empty()) {
      for (uint32_t i = 0; i < state.world.entities.size(); ++i) {
        if (i != entity && occupies(state, from, state.world.entities[i])) {
          return false;
        }
      }
      return true;
    }
    for (const uint32_t other : others_) {
      if (other != entity && occupies(state, from, state.world.entities[other])) {
        return false;
      }
    }
    return true;
  }

 private:
  bool occupies(const SimState& state, const Entity& from, const Entity& other) const {
    if (!other.state().placed || !other.state().road ||
        other.state().road->road != from.state().road->road) {
      return false;
    }
    const int relative =
        lane_delta(from.state().road->lane, other.state().road->lane) * from.lane.dir;
    const bool opposite = other.lane.on_road && other.lane.dir != from.lane.dir;
    if (opposite && !c_.opposite_lanes) {
      return false;
    }
    if (!c_.lane_ranges.empty()) {
      bool in_range = false;
      for (const auto& range : c_.lane_ranges) {
        in_range = in_range || (relative >= range.from.value_or(relative) &&
                                relative <= range.to.value_or(relative));
      }
      if (!in_range) {
        return false;
      }
    }
    const double d = entity_distance(state, from, other, spec_);
    return d <= c_.distance_forward.value_or(0.0) && d >= -c_.distance_backward.value_or(0.0);
  }

  const xosc::RelativeClearanceCondition& c_;
  std::vector<uint32_t> others_;
  DistanceSpec spec_;
};

}  // namespace

std::unique_ptr<EntityCondition> make_relative_clearance(const xosc::RelativeClearanceCondition& c,
                                                         const SimState& state) {
  std::vector<uint32_t> others;
  for (const std::string& name : c.entity_refs) {
    others.push_back(need_entity_index(state, name, c.source));
  }
  return std::make_unique<RelativeClearanceCheck>(c, std::move(others));
}

}  // namespace corsa::engine::detail
