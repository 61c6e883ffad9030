// TimeToCollisionCondition (OpenSCENARIO 1.3 §8.3.1): the time until the triggering entity
// reaches a target entity or position if both keep their velocities: distance divided by the
// closing speed (the relative velocity along the line between them, or along the triggering
// entity's heading for a longitudinal distance). Not closing in: infinite.

#include <cmath>
#include <limits>
#include <numbers>

#include "conditions/condition_makers.h"
#include "corsa/engine/oriented_box.h"
#include "positions/relative_distance.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class TimeToCollisionCheck final : public EntityCondition {
 public:
  TimeToCollisionCheck(const xosc::TimeToCollisionCondition& c, std::optional<uint32_t> target)
      : c_(c), target_(target) {
    spec_.system = coordinate_system(c.coordinate_system, c.along_route);
    spec_.type = c.relative_distance_type.value_or(xosc::RelativeDistanceType::kEuclidianDistance);
    spec_.freespace = c.freespace;
  }
  bool holds(const SimState& state, uint32_t entity) override {
    if (target_ && *target_ == entity) {
      return false;
    }
    const Entity& from = state.world.entities[entity];
    double distance = 0.0;
    double tx = 0.0, ty = 0.0;
    Vec2 vt;
    if (target_) {
      const Entity& to = state.world.entities[*target_];
      distance = entity_distance(state, from, to, spec_);
      tx = to.state().pose.x;
      ty = to.state().pose.y;
      vt = velocity_of(to.state());
    } else {
      const ResolvedPosition at = resolve_position(*c_.target_position, state, entity);
      distance = position_distance(state, from, at, spec_);
      tx = at.pose.x;
      ty = at.pose.y;
    }
    const Vec2 vf = velocity_of(from.state());
    // The direction along which the distance shrinks.
    double ux = tx - from.state().pose.x, uy = ty - from.state().pose.y;
    if (spec_.type != xosc::RelativeDistanceType::kEuclidianDistance) {
      const double h =
          from.state().pose.h +
          (spec_.type == xosc::RelativeDistanceType::kLateral ? 0.5 * std::numbers::pi : 0.0);
      const double sign = distance >= 0.0 ? 1.0 : -1.0;
      ux = sign * std::cos(h);
      uy = sign * std::sin(h);
    }
    const double norm = std::hypot(ux, uy);
    const double closing = norm > 0.0 ? ((vf.x - vt.x) * ux + (vf.y - vt.y) * uy) / norm : 0.0;
    const double ttc =
        closing > 0.0 ? std::abs(distance) / closing : std::numeric_limits<double>::infinity();
    return compare(ttc, c_.rule, c_.value);
  }

 private:
  const xosc::TimeToCollisionCondition& c_;
  std::optional<uint32_t> target_;
  DistanceSpec spec_;
};

}  // namespace

std::unique_ptr<EntityCondition> make_time_to_collision(const xosc::TimeToCollisionCondition& c,
                                                        const SimState& state) {
  std::optional<uint32_t> target;
  if (c.target_entity_ref) {
    target = need_entity_index(state, *c.target_entity_ref, c.source);
  } else if (!c.target_position) {
    throw InputError(c.source.error("TimeToCollisionCondition needs a target entity or position"));
  }
  return std::make_unique<TimeToCollisionCheck>(c, target);
}

}  // namespace corsa::engine::detail
