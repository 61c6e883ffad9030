// RelativeDistanceCondition (OpenSCENARIO 1.3 §8.3.1): the distance from the triggering entity
// to a reference entity (longitudinal, lateral or euclidean; in the entity frame, or road /
// lane coordinates; between reference points or, with freespace, bounding boxes), compared as a
// magnitude with a value.
//
// While what the distance reads (EntityDistanceInputs) holds the same bits as at the last
// evaluation for the same triggering entity, the condition holds as it did then and is not
// measured again (entities standing still ask the same every step).

#include <cmath>
#include <cstdint>
#include <vector>

#include "conditions/condition_makers.h"
#include "positions/relative_distance.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

// The last evaluation for one triggering entity: its inputs and its result.
struct RelativeDistanceMemo {
  EntityDistanceInputs inputs;
  bool held = false;
};

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
    const Entity& from = state.world.entities[entity];
    const Entity& to = state.world.entities[reference_];
    if (entity >= slot_of_.size()) {
      slot_of_.resize(entity + 1, kNoSlot);
    }
    uint32_t& slot = slot_of_[entity];
    if (slot != kNoSlot) {
      const RelativeDistanceMemo& memo = memos_[slot];
      if (memo.inputs.same_as(from, to)) {
        return memo.held;
      }
    } else {
      slot = static_cast<uint32_t>(memos_.size());
      memos_.emplace_back();
    }
    const double d = entity_distance(state, from, to, spec_);
    RelativeDistanceMemo& memo = memos_[slot];
    memo.inputs.take(from, to);
    memo.held = compare(std::abs(d), c_.rule, c_.value);
    return memo.held;
  }

 private:
  static constexpr uint32_t kNoSlot = UINT32_MAX;

  const xosc::RelativeDistanceCondition& c_;
  uint32_t reference_;
  DistanceSpec spec_;
  /// Per triggering entity (by index): its memo's place in memos_, or kNoSlot.
  std::vector<uint32_t> slot_of_;
  std::vector<RelativeDistanceMemo> memos_;
};

}  // namespace

std::unique_ptr<EntityCondition> make_relative_distance(const xosc::RelativeDistanceCondition& c,
                                                        const SimState& state) {
  return std::make_unique<RelativeDistanceCheck>(c,
                                                 need_entity_index(state, c.entity_ref, c.source));
}

}  // namespace corsa::engine::detail
