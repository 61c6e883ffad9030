// The duration conditions (OpenSCENARIO 1.3 §8.3.1): StandStillCondition (slower than 1e-3 m/s,
// esmini's threshold, for at least `duration` s), OffroadCondition (off every lane, or on a lane
// of type none, for at least `duration` s) and EndOfRoadCondition (stuck at a lane end without
// successor for at least `duration` s). The timers are kept per entity and advanced every step
// (state/world_update.cpp).

#include "conditions/condition_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

// A timer reaches a duration when it is within half a step of it (timers grow by dt).
bool reached(const SimState& state, double timer, double duration) {
  return timer + 0.5 * state.time.dt() >= duration;
}

class StandStillCheck final : public EntityCondition {
 public:
  explicit StandStillCheck(double duration) : duration_(duration) {}
  bool holds(const SimState& state, uint32_t entity) override {
    const Entity& e = state.world.entities[entity];
    return e.standing_still && reached(state, e.standstill_time, duration_);
  }

 private:
  double duration_;
};

class OffroadCheck final : public EntityCondition {
 public:
  explicit OffroadCheck(double duration) : duration_(duration) {}
  bool holds(const SimState& state, uint32_t entity) override {
    const Entity& e = state.world.entities[entity];
    // was_offroad: off the road at the last timer update (state/world_update.cpp).
    return e.was_offroad && state.map != nullptr && reached(state, e.offroad_time, duration_);
  }

 private:
  double duration_;
};

class EndOfRoadCheck final : public EntityCondition {
 public:
  explicit EndOfRoadCheck(double duration) : duration_(duration) {}
  bool holds(const SimState& state, uint32_t entity) override {
    const Entity& e = state.world.entities[entity];
    return e.end_of_road && reached(state, e.end_of_road_time, duration_);
  }

 private:
  double duration_;
};

}  // namespace

std::unique_ptr<EntityCondition> make_stand_still(const xosc::StandStillCondition& c,
                                                  const SimState&) {
  return std::make_unique<StandStillCheck>(c.duration);
}

std::unique_ptr<EntityCondition> make_offroad(const xosc::OffroadCondition& c, const SimState&) {
  return std::make_unique<OffroadCheck>(c.duration);
}

std::unique_ptr<EntityCondition> make_end_of_road(const xosc::EndOfRoadCondition& c,
                                                  const SimState&) {
  return std::make_unique<EndOfRoadCheck>(c.duration);
}

}  // namespace corsa::engine::detail
