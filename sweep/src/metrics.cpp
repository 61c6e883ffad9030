#include "corsa/sweep/metrics.h"

#include <algorithm>
#include <cmath>

#include "corsa/core/strings.h"
#include "footprint.h"

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

// Whether two footprints at least `gap` apart (m, a lower bound of their free distance) cannot
// touch within `horizon` seconds: the gap closes no faster than their relative speed.
bool cannot_contact_before(const detail::Footprint& a, const detail::Footprint& b, double gap,
                           double horizon) {
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
  // Accelerations are over the last step, so tick 0 (the initial state) has none yet.
  if (simulation.tick() > 0) {
    raise(metrics_.max_deceleration, std::max(0.0, -self.acceleration), time);
    raise(metrics_.max_acceleration, std::max(0.0, self.acceleration), time);
  }
  raise(metrics_.max_speed, self.speed, time);
  const detail::Footprint mine = detail::footprint_of(simulation.entity(ego), self);
  for (size_t i = 0; i < simulation.entity_count(); ++i) {
    const engine::EntityState& state = simulation.state(i);
    if (i == ego || !state.placed) {
      continue;
    }
    const detail::Footprint theirs = detail::footprint_of(simulation.entity(i), state);
    const std::string& name = simulation.entity(i).name;
    // Broad phase: a pair whose lower bound cannot beat the extremes so far is not measured
    // exactly (lower() keeps only strictly smaller values, so the results are the same).
    const double bound = detail::free_distance_bound(mine, theirs);
    if (!metrics_.min_distance.value || bound < *metrics_.min_distance.value) {
      lower(metrics_.min_distance, detail::free_distance(mine, theirs), time, name);
    }
    if (!metrics_.min_ttc.value ||
        !cannot_contact_before(mine, theirs, bound, *metrics_.min_ttc.value)) {
      if (const auto ttc = detail::time_to_contact(mine, theirs)) {
        lower(metrics_.min_ttc, *ttc, time, name);
      }
    }
  }
}

}  // namespace corsa::sweep
