// CollisionCondition (OpenSCENARIO 1.3 §8.3.1): the triggering entity's bounding box overlaps
// that of a named entity, or of any entity of a type (ByType).

#include "conditions/condition_makers.h"
#include "state/entity_builder.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class CollisionCheck final : public EntityCondition {
 public:
  CollisionCheck(std::optional<uint32_t> other, std::optional<ObjectKind> kind)
      : other_(other), kind_(kind) {}
  bool holds(const SimState& state, uint32_t entity) override {
    if (other_) {
      return *other_ != entity && state.contacts.get(entity, *other_);
    }
    for (const auto& [first, second] : state.contacts.pairs) {
      const uint32_t other = first == entity ? second : second == entity ? first : entity;
      if (other != entity && (!kind_ || state.world.entities[other].info.kind == *kind_)) {
        return true;
      }
    }
    return false;
  }

 private:
  std::optional<uint32_t> other_;
  std::optional<ObjectKind> kind_;
};

}  // namespace

std::unique_ptr<EntityCondition> make_collision(const xosc::CollisionCondition& c,
                                                const SimState& state) {
  std::optional<uint32_t> other;
  std::optional<ObjectKind> kind;
  if (c.entity_ref) {
    other = need_entity_index(state, *c.entity_ref, c.source);
  } else if (c.by_type) {
    kind = object_kind(*c.by_type);
  }
  return std::make_unique<CollisionCheck>(other, kind);
}

}  // namespace corsa::engine::detail
