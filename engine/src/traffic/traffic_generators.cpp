#include "traffic/traffic_generators.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "controllers/controllers.h"
#include "corsa/core/random.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"
#include "motion/placement.h"
#include "positions/position_resolver.h"
#include "state/sim_state.h"
#include "traffic/spawn_speed.h"
#include "traffic/spawner.h"
#include "traffic/traffic_update.h"

namespace corsa::engine::detail {
namespace {

constexpr double kSpawnClearance = 12.0;  // m from any other entity's reference point
constexpr int kTriesPerStep = 8;

const xosc::TrafficDistribution* distribution_of(
    const std::optional<xosc::TrafficDistribution>& distribution) {
  return distribution ? &*distribution : nullptr;
}

// TrafficSwarmAction: numberOfVehicles kept between the inner circle and the outer ellipse
// (semi-major axis along the central entity's heading, centre `offset` metres ahead of it);
// vehicles that leave the ellipse are removed and new ones spawn in the ring.
class Swarm final : public GeneratorBase {
 public:
  Swarm(const xosc::TrafficSwarmAction& action, SimState& state, uint32_t central)
      : GeneratorBase(action.traffic_name, "swarm",
                      derive_seed(state.options.seed, "swarm:" + action.central_object +
                                                          std::to_string(action.source.line))),
        action_(action),
        mix_(action.traffic_definition, distribution_of(action.traffic_distribution)),
        central_(central) {}

  void step(SimState& state) override {
    prune(state);
    // A copy: spawning appends entities, which may move the world's storage.
    const EntityState centre = state.world.entities[central_].state();
    if (!centre.placed || state.map == nullptr) {
      return;
    }
    const double c = std::cos(centre.pose.h), s = std::sin(centre.pose.h);
    const double cx = centre.pose.x + action_.offset * c;
    const double cy = centre.pose.y + action_.offset * s;
    const double a = std::max(action_.semi_major_axis, 1.0);
    const double b = std::max(action_.semi_minor_axis, 1.0);
    // Leave: outside the ellipse.
    for (const uint32_t index : std::vector<uint32_t>(mine_)) {
      const EntityState& e = state.world.entities[index].state();
      const double dx = e.pose.x - cx, dy = e.pose.y - cy;
      const double u = dx * c + dy * s, v = -dx * s + dy * c;
      if ((u * u) / (a * a) + (v * v) / (b * b) > 1.0) {
        despawn(state, index);
      }
    }
    // Fill up to numberOfVehicles, a few attempts per step.
    for (int tries = 0; tries < kTriesPerStep && mine_.size() < action_.number_of_vehicles;
         ++tries) {
      const double angle = random_.uniform(0.0, 2.0 * std::numbers::pi);
      const double ca = std::cos(angle), sa = std::sin(angle);
      // Distance to the ellipse along the direction, then uniform between inner and that.
      const double outer = 1.0 / std::sqrt((ca * ca) / (a * a) + (sa * sa) / (b * b));
      const double inner = std::min(action_.inner_radius, outer);
      const double r = random_.uniform(inner, outer);
      const double x = cx + r * (ca * c - sa * s), y = cy + r * (ca * s + sa * c);
      const size_t kind = mix_.draw(random_);
      const auto at = lane_spot(*state.map, x, y, mix_.walks(kind));
      if (!at || !clear_of_others(state, at->pose.x, at->pose.y, kSpawnClearance)) {
        continue;
      }
      const double dx = at->pose.x - centre.pose.x, dy = at->pose.y - centre.pose.y;
      if (std::hypot(dx, dy) < action_.inner_radius || !direction_wanted(at->pose.h, centre)) {
        continue;
      }
      const std::optional<double> given = draw_speed(centre);
      spawn(state, mix_, kind, *at, spawn_speed(state, random_, mix_, kind, *at, given));
    }
  }

 private:
  // DirectionOfTravelDistribution: the spot's direction of travel (same as the central
  // entity's heading, or opposite) is kept with the probability its weight gives.
  bool direction_wanted(double heading, const EntityState& centre) {
    if (!action_.direction_same || !action_.direction_opposite) {
      return true;
    }
    const double same = std::max(0.0, *action_.direction_same);
    const double opposite = std::max(0.0, *action_.direction_opposite);
    if (!(same + opposite > 0.0)) {
      return true;
    }
    const bool is_same = std::cos(heading - centre.pose.h) >= 0.0;
    const double p = (is_same ? same : opposite) / std::max(same, opposite);
    return random_.uniform01() < p;
  }

  // The swarm's own speed: InitialSpeedRange, else the deprecated velocity, else the central
  // entity's (when it moves); nothing: spawn_speed's other sources.
  std::optional<double> draw_speed(const EntityState& centre) {
    if (action_.initial_speed_range) {
      return random_.uniform(action_.initial_speed_range->lower_limit,
                             action_.initial_speed_range->upper_limit);
    }
    if (action_.velocity) {
      return *action_.velocity;
    }
    return centre.speed > 0.0 ? std::optional<double>(centre.speed) : std::nullopt;
  }

  const xosc::TrafficSwarmAction& action_;
  TrafficMix mix_;
  uint32_t central_;
};

// TrafficSourceAction: `rate` vehicles per second appear within `radius` of the position.
class Source final : public GeneratorBase {
 public:
  Source(const xosc::TrafficSourceAction& action, SimState& state, ResolvedPosition at)
      : GeneratorBase(
            action.traffic_name, "source",
            derive_seed(state.options.seed, "source:" + std::to_string(action.source.line))),
        action_(action),
        mix_(action.traffic_definition, distribution_of(action.traffic_distribution)),
        at_(at) {}

  void step(SimState& state) override {
    if (state.map == nullptr) {
      return;
    }
    prune(state);
    due_ += action_.rate * state.time.dt();
    for (int tries = 0; tries < kTriesPerStep && due_ >= 1.0; ++tries) {
      const double angle = random_.uniform(0.0, 2.0 * std::numbers::pi);
      const double r = action_.radius * std::sqrt(random_.uniform01());
      const size_t kind = mix_.draw(random_);
      const auto spot = lane_spot(*state.map, at_.pose.x + r * std::cos(angle),
                                  at_.pose.y + r * std::sin(angle), mix_.walks(kind));
      if (!spot || !clear_of_others(state, spot->pose.x, spot->pose.y, kSpawnClearance)) {
        continue;
      }
      spawn(state, mix_, kind, *spot,
            spawn_speed(state, random_, mix_, kind, *spot, action_.speed));
      due_ -= 1.0;
    }
    due_ = std::min(due_, 2.0);  // no burst after a long blocked spell
  }

 private:
  const xosc::TrafficSourceAction& action_;
  TrafficMix mix_;
  ResolvedPosition at_;
  double due_ = 1.0;  ///< the first vehicle comes at once
};

// TrafficSinkAction: generated vehicles within `radius` of the position disappear, at most
// `rate` per second (unlimited without a rate). The scenario's own entities are not traffic.
class Sink final : public GeneratorBase {
 public:
  Sink(const xosc::TrafficSinkAction& action, SimState& state, ResolvedPosition at)
      : GeneratorBase(action.traffic_name, "sink", state.options.seed), action_(action), at_(at) {}

  void step(SimState& state) override {
    budget_ = action_.rate
                  ? std::min(budget_ + *action_.rate * state.time.dt(), 1.0 + *action_.rate)
                  : 1e18;
    const size_t own = state.scenario.entities.objects.size();
    for (size_t i = own; i < state.world.entities.size() && budget_ >= 1.0; ++i) {
      const EntityState& e = state.world.entities[i].state();
      if (e.placed && std::hypot(e.pose.x - at_.pose.x, e.pose.y - at_.pose.y) <= action_.radius) {
        remove_entity(state, static_cast<uint32_t>(i));
        budget_ -= 1.0;
      }
    }
  }

 private:
  const xosc::TrafficSinkAction& action_;
  ResolvedPosition at_;
  double budget_ = 0.0;
};

}  // namespace

std::unique_ptr<TrafficGenerator> make_swarm(const xosc::TrafficSwarmAction& action,
                                             SimState& state) {
  const auto central = state.world.find(action.central_object);
  if (!central) {
    throw InputError(action.source.error("unknown central entity '" + action.central_object + "'"));
  }
  return std::make_unique<Swarm>(action, state, *central);
}

std::unique_ptr<TrafficGenerator> make_source(const xosc::TrafficSourceAction& action,
                                              SimState& state) {
  return std::make_unique<Source>(action, state,
                                  resolve_position(action.position, state, std::nullopt));
}

std::unique_ptr<TrafficGenerator> make_sink(const xosc::TrafficSinkAction& action,
                                            SimState& state) {
  return std::make_unique<Sink>(action, state,
                                resolve_position(action.position, state, std::nullopt));
}

}  // namespace corsa::engine::detail
