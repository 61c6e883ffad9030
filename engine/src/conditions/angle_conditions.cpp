// AngleCondition and RelativeAngleCondition (OpenSCENARIO 1.3 §8.3.1): the entity's heading,
// pitch or roll (in the world, or relative to the road in road / lane coordinates), or its
// difference to another entity's, equals `angle` within `angleTolerance` (radians, wrapped).

#include <cmath>

#include "conditions/condition_makers.h"
#include "corsa/xodr/map.h"
#include "geometry/angle.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

double angle_of(const Pose& pose, xosc::AngleType type) {
  switch (type) {
    case xosc::AngleType::kHeading:
      return pose.h;
    case xosc::AngleType::kPitch:
      return pose.p;
    case xosc::AngleType::kRoll:
      return pose.r;
  }
  return pose.h;
}

class AngleCheck final : public EntityCondition {
 public:
  explicit AngleCheck(const xosc::AngleCondition& c) : c_(c) {}
  bool holds(const SimState& state, uint32_t entity) override {
    const Entity& e = state.world.entities[entity];
    double angle = angle_of(e.state().pose, c_.angle_type);
    const bool road_frame = c_.coordinate_system == xosc::CoordinateSystem::kRoad ||
                            c_.coordinate_system == xosc::CoordinateSystem::kLane;
    if (road_frame && c_.angle_type == xosc::AngleType::kHeading && e.state().road &&
        state.map != nullptr) {
      angle -= state.map->reference(e.state().road->road, e.state().road->s).hdg;
    }
    return std::abs(wrap_angle(angle - c_.angle)) <= c_.angle_tolerance;
  }

 private:
  const xosc::AngleCondition& c_;
};

class RelativeAngleCheck final : public EntityCondition {
 public:
  RelativeAngleCheck(const xosc::RelativeAngleCondition& c, uint32_t reference)
      : c_(c), reference_(reference) {}
  bool holds(const SimState& state, uint32_t entity) override {
    const double difference =
        angle_of(state.world.entities[entity].state().pose, c_.angle_type) -
        angle_of(state.world.entities[reference_].state().pose, c_.angle_type);
    return std::abs(wrap_angle(difference - c_.angle)) <= c_.angle_tolerance;
  }

 private:
  const xosc::RelativeAngleCondition& c_;
  uint32_t reference_;
};

}  // namespace

std::unique_ptr<EntityCondition> make_angle(const xosc::AngleCondition& c, const SimState&) {
  return std::make_unique<AngleCheck>(c);
}

std::unique_ptr<EntityCondition> make_relative_angle(const xosc::RelativeAngleCondition& c,
                                                     const SimState& state) {
  return std::make_unique<RelativeAngleCheck>(c, need_entity_index(state, c.entity_ref, c.source));
}

}  // namespace corsa::engine::detail
