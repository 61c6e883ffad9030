// ReachPositionCondition (OpenSCENARIO 1.3 §8.3.1, deprecated for DistanceCondition): the
// entity's reference point is within `tolerance` metres of a position.
//
// The standard's tolerance is a radius (m) and the condition checks that the entity "has reached
// a given position": an Orientation of that position is not compared (it has no angular
// tolerance). esmini's reading (Semantics::kEsmini; its TrigByReachPosition): a position with an
// Orientation element is reached only while the entity's heading, pitch and roll are also within
// kEsminiAngularTolerance of the position's (esmini's traj-heading-trig waits so for a lane
// change's heading). A WorldPosition's h, p and r are attributes, not an Orientation: esmini's
// reader turns the check on only for an <Orientation> child of the position, so a WorldPosition
// is compared by its place alone there too (its pedestrian_traj_synch stops so).

#include <cmath>
#include <optional>
#include <type_traits>
#include <variant>

#include "conditions/condition_makers.h"
#include "geometry/angle.h"
#include "positions/position_resolver.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

constexpr double kEsminiAngularTolerance = 0.05;  // rad

// Whether the position has an Orientation element (a WorldPosition has none: its h, p and r are
// attributes).
bool has_orientation_element(const xosc::Position& position) {
  return std::visit(
      [](const auto& kind) {
        using Kind = std::decay_t<decltype(kind)>;
        if constexpr (std::is_same_v<Kind, xosc::WorldPosition>) {
          return false;
        } else {
          return kind.orientation.has_value();
        }
      },
      position.kind);
}

// Whether the position is a place on the map alone (no entity, route or trajectory to read):
// the scenario and the map do not change during a run, so it resolves to the same pose always.
bool fixed_on_map(const xosc::Position& position) {
  return std::holds_alternative<xosc::WorldPosition>(position.kind) ||
         std::holds_alternative<xosc::LanePosition>(position.kind) ||
         std::holds_alternative<xosc::RoadPosition>(position.kind);
}

class ReachPositionCheck final : public EntityCondition {
 public:
  ReachPositionCheck(const xosc::ReachPositionCondition& c, const SimState& state)
      : c_(c),
        check_orientation_(state.options.semantics == Semantics::kEsmini &&
                           has_orientation_element(c.position)),
        fixed_(fixed_on_map(c.position)) {}

  [[gnu::hot]] bool holds(const SimState& state, uint32_t entity) override {
    // A place on the map is resolved once; it was resolved every step, for every entity.
    if (fixed_ && !target_) target_ = resolve_position(c_.position, state, entity);
    const ResolvedPosition target =
        fixed_ ? *target_ : resolve_position(c_.position, state, entity);
    const Pose& p = state.world.entities[entity].state().pose;
    const double dx = target.pose.x - p.x;
    const double dy = target.pose.y - p.y;
    // hypot is at least the larger of |dx| and |dy| (a double, below the exact length, which a
    // rounding within an ulp cannot pass): farther than the tolerance along one axis is farther
    // in hypot too, without the call. NaNs fail this test and take hypot's.
    if (std::abs(dx) > c_.tolerance || std::abs(dy) > c_.tolerance ||
        std::hypot(dx, dy) > c_.tolerance) {
      return false;
    }
    if (!check_orientation_) {
      return true;
    }
    return std::abs(wrap_angle(p.h - target.pose.h)) < kEsminiAngularTolerance &&
           std::abs(wrap_angle(p.p - target.pose.p)) < kEsminiAngularTolerance &&
           std::abs(wrap_angle(p.r - target.pose.r)) < kEsminiAngularTolerance;
  }

 private:
  const xosc::ReachPositionCondition& c_;
  bool check_orientation_ = false;
  bool fixed_ = false;
  std::optional<ResolvedPosition> target_;  ///< the resolved place, when fixed_
};

}  // namespace

std::unique_ptr<EntityCondition> make_reach_position(const xosc::ReachPositionCondition& c,
                                                     const SimState& state) {
  return std::make_unique<ReachPositionCheck>(c, state);
}

}  // namespace corsa::engine::detail
