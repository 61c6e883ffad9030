#include "corsa/sweep/metrics.h"

#include <algorithm>
#include <cmath>

#include "corsa/core/strings.h"
#include "corsa/engine/oriented_box.h"

namespace corsa::sweep {
namespace {

// Records `value` when it beats the current extreme (strictly, so the first time is kept).
void lower(Extreme& extreme, double value, double time, const std::string& other) {
  if (!extreme.value || value < *extreme.value) {
    extreme = Extreme{value, time, other};
  }
}

void raise(Extreme& extreme, double value, double time) {
  if (!extreme.value || value > *extreme.value) {
    extreme = Extreme{value, time, {}};
  }
}

// An entity's box seen from above and its velocity: what the distance and contact metrics
// measure.
struct Moving {
  engine::OrientedBox box;
  Vec2 velocity;  ///< m/s, map frame
};

Moving moving(const engine::Simulation& simulation, size_t entity) {
  const engine::EntityState& state = simulation.state(entity);
  return {engine::box_of(simulation.entity(entity).box, state.pose), engine::velocity_of(state)};
}

// Whether two boxes at least `gap` apart (m, a lower bound of their free distance) cannot touch
// within `horizon` seconds: the gap closes no faster than their relative speed.
bool cannot_contact_before(const Moving& a, const Moving& b, double gap, double horizon) {
  if (gap <= 0.0) {
    return false;
  }
  // Relative speed (m/s).
  const double speed = std::hypot(b.velocity.x - a.velocity.x, b.velocity.y - a.velocity.y);
  return speed == 0.0 || gap / speed >= horizon;
}

}  // namespace

std::optional<size_t> choose_ego(const engine::Simulation& simulation, std::string_view requested) {
  if (!requested.empty()) {
    return simulation.find_entity(requested);
  }
  for (const std::string_view name : {"ego", "hero"}) {
    for (size_t i = 0; i < simulation.entity_count(); ++i) {
      if (iequals(simulation.entity(i).name, name)) return i;
    }
  }
  if (simulation.entity_count() > 0) return 0;
  return std::nullopt;
}

void MetricsObserver::on_step(const engine::Simulation& simulation) {
  if (!ego_) {
    return;
  }
  const size_t ego = *ego_;
  const engine::EntityState& self = simulation.state(ego);
  if (!self.placed) {
    return;
  }
  const double time = simulation.time();
  if (metrics_.ego.empty()) {
    metrics_.ego = simulation.entity(ego).name;
  }
  // Accelerations are over the last step, so the first tick (the initial state) has none yet.
  if (simulation.steps() > 0) {
    raise(metrics_.max_deceleration, std::max(0.0, -self.acceleration), time);
    raise(metrics_.max_acceleration, std::max(0.0, self.acceleration), time);
  }
  raise(metrics_.max_speed, self.speed, time);
  const Moving mine = moving(simulation, ego);
  for (size_t i = 0; i < simulation.entity_count(); ++i) {
    const engine::EntityState& state = simulation.state(i);
    if (i == ego || !state.placed || simulation.is_ghost(i)) {
      continue;
    }
    const Moving theirs = moving(simulation, i);
    const std::string& name = simulation.entity(i).name;
    // Broad phase: a pair whose lower bound cannot beat the extremes so far is not measured
    // exactly (lower() keeps only strictly smaller values, so the results are the same).
    const double bound = engine::box_distance_lower_bound(mine.box, theirs.box);
    if (!metrics_.min_distance.value || bound < *metrics_.min_distance.value) {
      lower(metrics_.min_distance, engine::box_distance(mine.box, theirs.box), time, name);
    }
    if (!metrics_.min_ttc.value ||
        !cannot_contact_before(mine, theirs, bound, *metrics_.min_ttc.value)) {
      if (const auto ttc =
              engine::time_to_contact(mine.box, mine.velocity, theirs.box, theirs.velocity)) {
        lower(metrics_.min_ttc, *ttc, time, name);
      }
    }
  }
}

}  // namespace corsa::sweep
