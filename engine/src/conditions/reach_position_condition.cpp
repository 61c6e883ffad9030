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

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
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

// Appends a double's bits (hex) to `key`: values that key alike are the same to the bit.
void key_bits(std::string& key, double value) {
  char text[20];
  const auto bits = std::bit_cast<uint64_t>(value);
  key.append(text, static_cast<size_t>(std::snprintf(text, sizeof text, "%llx;",
                                                     static_cast<unsigned long long>(bits))));
}
void key_bits(std::string& key, const std::optional<double>& value) {
  if (value) {
    key_bits(key, *value);
  } else {
    key += "-;";
  }
}
void key_text(std::string& key, const std::string& text) {
  key += std::to_string(text.size()) + ":" + text + ";";
}
void key_orientation(std::string& key, const std::optional<xosc::Orientation>& orientation) {
  if (!orientation) {
    key += "-;";
    return;
  }
  key_bits(key, orientation->h);
  key_bits(key, orientation->p);
  key_bits(key, orientation->r);
  key += orientation->type ? std::to_string(static_cast<int>(*orientation->type)) + ";" : "-;";
}

// The fields a place on the map (fixed_on_map) is resolved from, as text: two positions of one
// key resolve to the same pose (their sources, which only locate messages, are left out).
std::string fixed_position_key(const xosc::Position& position) {
  std::string key;
  if (const auto* world = std::get_if<xosc::WorldPosition>(&position.kind)) {
    key = "world;";
    key_bits(key, world->x);
    key_bits(key, world->y);
    key_bits(key, world->z);
    key_bits(key, world->h);
    key_bits(key, world->p);
    key_bits(key, world->r);
  } else if (const auto* lane = std::get_if<xosc::LanePosition>(&position.kind)) {
    key = "lane;";
    key_text(key, lane->road_id);
    key_text(key, lane->lane_id);
    key_bits(key, lane->s);
    key_bits(key, lane->offset);
    key_orientation(key, lane->orientation);
  } else {
    const auto& road = std::get<xosc::RoadPosition>(position.kind);
    key = "road;";
    key_text(key, road.road_id);
    key_bits(key, road.s);
    key_bits(key, road.t);
    key_orientation(key, road.orientation);
  }
  return key;
}

class ReachPositionCheck final : public EntityCondition {
 public:
  ReachPositionCheck(const xosc::ReachPositionCondition& c, const SimState& state)
      : c_(c),
        check_orientation_(state.options.semantics == Semantics::kEsmini &&
                           has_orientation_element(c.position)),
        fixed_(fixed_on_map(c.position)) {}

  [[gnu::hot]] bool holds(const SimState& state, uint32_t entity) override {
    // A place on the map, once resolved, that other conditions of this definition share
    // (share_values): the value is a function of the entity's state alone, and while its count
    // of writes stands it is the one the shared memo holds. A condition of its own keeps none:
    // its test is about as cheap as the memo's.
    if (shared_ && target_) {
      const Memo& memo = *memo_;
      if (memo.valid && memo.entity == entity &&
          memo.changes == state.world.entities[entity].state_changes()) {
        return memo.value;
      }
      return remember(state, entity);
    }
    return evaluate(state, entity);
  }

  // A place on the map is compared with the entity's pose alone.
  ConditionInputs inputs() const override {
    return fixed_ ? ConditionInputs::kOwnState : ConditionInputs::kAnything;
  }

  std::string value_key() const override {
    if (!fixed_) return {};
    std::string key = "reach;";
    key_bits(key, c_.tolerance);
    key += check_orientation_ ? "o;" : "-;";
    return key + fixed_position_key(c_.position);
  }
  void share_values(EntityCondition& other) override {
    auto& first = static_cast<ReachPositionCheck&>(other);
    memo_ = first.memo_;
    shared_ = true;
    first.shared_ = true;
  }

 private:
  // The value when the shared memo does not hold it, kept in the memo (out of line: the memo's
  // test is the common path).
  [[gnu::noinline]] bool remember(const SimState& state, uint32_t entity) {
    const bool value = reached(*target_, state, entity);
    *memo_ = Memo{true, entity, state.world.entities[entity].state_changes(), value};
    return value;
  }

  // The value without the memo. Out of line, as remember: the memo's test above then needs no
  // registers saved.
  [[gnu::noinline]] bool evaluate(const SimState& state, uint32_t entity) {
    // A place on the map is resolved once; it was resolved every step, for every entity.
    if (fixed_ && !target_) target_ = resolve_position(c_.position, state, entity);
    return fixed_ ? reached(*target_, state, entity)
                  : reached(resolve_position(c_.position, state, entity), state, entity);
  }

  // Whether `entity` is within the tolerance of `target` now.
  bool reached(const ResolvedPosition& target, const SimState& state, uint32_t entity) const {
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

  /// The value for one entity at one count of its state's writes (fixed_ and shared_ alone).
  struct Memo {
    bool valid = false;
    uint32_t entity = 0;
    uint32_t changes = 0;
    bool value = false;
  };

  const xosc::ReachPositionCondition& c_;
  bool check_orientation_ = false;
  bool fixed_ = false;
  bool shared_ = false;  ///< memo_ is shared with other conditions of this definition
  std::optional<ResolvedPosition> target_;  ///< the resolved place, when fixed_
  std::shared_ptr<Memo> memo_ = std::make_shared<Memo>();
};

}  // namespace

std::unique_ptr<EntityCondition> make_reach_position(const xosc::ReachPositionCondition& c,
                                                     const SimState& state) {
  return std::make_unique<ReachPositionCheck>(c, state);
}

}  // namespace corsa::engine::detail
