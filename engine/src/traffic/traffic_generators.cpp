#include "traffic/traffic_generators.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "actions/placement.h"
#include "controllers/controllers.h"
#include "core/sim_state.h"
#include "corsa/core/random.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"
#include "motion/lane_follow.h"
#include "positions/position_resolver.h"

namespace corsa::engine::detail {
namespace {

constexpr double kDefaultSpeed = 13.9;    // m/s (50 km/h) when the action gives none
constexpr double kSpawnClearance = 12.0;  // m from any other entity's reference point
constexpr int kTriesPerStep = 8;

xosc::VehicleCategory draw_category(const std::optional<xosc::TrafficDefinition>& definition,
                                    RandomStream& random) {
  if (!definition || definition->vehicle_categories.empty()) {
    return xosc::VehicleCategory::kCar;
  }
  std::vector<double> weights;
  double sum = 0.0;
  for (const auto& entry : definition->vehicle_categories) {
    weights.push_back(std::max(0.0, entry.weight));
    sum += weights.back();
  }
  if (!(sum > 0.0)) {
    return definition->vehicle_categories.front().category;
  }
  return definition->vehicle_categories[random.weighted_index(weights)].category;
}

// Box and performance by category: a car, a truck or bus, a motorbike or bicycle.
xosc::Vehicle vehicle_model(xosc::VehicleCategory category) {
  xosc::Vehicle v;
  v.category = category;
  double length = 4.5, width = 1.8, height = 1.5, wheelbase = 2.8;
  switch (category) {
    case xosc::VehicleCategory::kTruck:
    case xosc::VehicleCategory::kBus:
    case xosc::VehicleCategory::kSemitrailer:
    case xosc::VehicleCategory::kTrailer:
    case xosc::VehicleCategory::kTrain:
    case xosc::VehicleCategory::kTram:
      length = 12.0, width = 2.5, height = 3.5, wheelbase = 6.5;
      break;
    case xosc::VehicleCategory::kMotorbike:
    case xosc::VehicleCategory::kBicycle:
      length = 2.0, width = 0.8, height = 1.5, wheelbase = 1.4;
      break;
    default:
      break;
  }
  v.name = "traffic_vehicle";
  v.bounding_box.center_x = 0.5 * wheelbase;
  v.bounding_box.center_z = 0.5 * height;
  v.bounding_box.length = length;
  v.bounding_box.width = width;
  v.bounding_box.height = height;
  v.performance.max_speed = 50.0;
  v.performance.max_acceleration = 3.0;
  v.performance.max_deceleration = 8.0;
  xosc::Axle front;
  front.max_steering = 0.5;
  front.position_x = wheelbase;
  v.axles.front_axle = front;
  return v;
}

bool clear_of_others(const SimState& state, double x, double y) {
  for (const Entity& other : state.world.entities) {
    if (other.state.placed &&
        std::hypot(other.state.pose.x - x, other.state.pose.y - y) < kSpawnClearance) {
      return false;
    }
  }
  return true;
}

// A driving lane's centre near (x, y), facing its direction of travel (right-hand traffic:
// lanes right of the reference line drive toward +s); `same_as` (rad) when given picks the
// direction closer to it instead for bidirectional choice of the swarm.
std::optional<ResolvedPosition> lane_spot(const xodr::Map& map, double x, double y) {
  xodr::LocateOptions options;
  options.max_distance = 4.0;
  options.drivable_only = true;
  const auto located = map.locate(x, y, options);
  if (!located || located->lane == 0) {
    return std::nullopt;
  }
  const auto t = lane_center_t(map, located->road, located->s, located->lane);
  if (!t) {
    return std::nullopt;
  }
  const int dir = located->lane < 0 ? 1 : -1;
  ResolvedPosition at;
  const xodr::WorldPose pose = map.world_pose(located->road, located->s, *t);
  at.pose = pose;
  at.pose.h = travel_heading(map, located->road, located->s, dir);
  at.road = RoadPoint{located->road, located->s, *t, located->lane};
  return at;
}

class GeneratorBase : public TrafficGenerator {
 public:
  GeneratorBase(std::optional<std::string> name, std::string stem, uint64_t seed)
      : name_(std::move(name)), stem_(std::move(stem)), random_(seed) {}
  const std::optional<std::string>& name() const override { return name_; }

 protected:
  // A new vehicle (or a despawned one of ours reused) at `at`, driving at `speed`.
  uint32_t spawn(SimState& state, const ResolvedPosition& at, double speed,
                 xosc::VehicleCategory category) {
    uint32_t index = 0;
    if (!free_.empty()) {
      index = free_.back();
      free_.pop_back();
    } else {
      xosc::ScenarioObject object;
      object.name = (name_ ? *name_ : stem_) + "_" + std::to_string(++state.traffic.spawned_count);
      object.object = vehicle_model(category);
      state.traffic.spawned_objects.push_back(std::move(object));
      const xosc::ScenarioObject& stored = state.traffic.spawned_objects.back();
      const xosc::Vehicle& vehicle = std::get<xosc::Vehicle>(stored.object);
      Entity entity;
      entity.object = &stored;
      entity.info.name = stored.name;
      entity.info.kind = ObjectKind::kVehicle;
      entity.info.category = category == xosc::VehicleCategory::kTruck ? EntityCategory::kTruck
                             : category == xosc::VehicleCategory::kBus ? EntityCategory::kBus
                                                                       : EntityCategory::kCar;
      const xosc::BoundingBox& b = vehicle.bounding_box;
      entity.info.box = Box{b.center_x, b.center_y, b.center_z, b.length, b.width, b.height};
      entity.info.max_speed = vehicle.performance.max_speed;
      entity.info.max_acceleration = vehicle.performance.max_acceleration;
      entity.info.max_deceleration = vehicle.performance.max_deceleration;
      index = static_cast<uint32_t>(state.world.entities.size());
      state.world.by_name.emplace(stored.name, index);
      state.world.entities.push_back(std::move(entity));
      ControlState& control = control_of(state, index);
      ControllerKind kind = ControllerKind::kAcc;
      if (!state.options.controller.empty()) {
        parse_controller_kind(state.options.controller, kind);
      }
      control.kind = kind;
    }
    Entity& entity = state.world.entities[index];
    place_entity(state, entity, at, xosc::Source{}, false);
    entity.state.speed = speed;
    entity.speed_command = speed;
    control_of(state, index).dynamics.reset();
    mine_.push_back(index);
    return index;
  }

  // Vehicles removed by others (a sink, a DeleteEntityAction) are free again.
  void prune(const SimState& state) {
    for (const uint32_t index : std::vector<uint32_t>(mine_)) {
      if (!state.world.entities[index].state.placed) {
        mine_.erase(std::remove(mine_.begin(), mine_.end(), index), mine_.end());
        free_.push_back(index);
      }
    }
  }

  void despawn(SimState& state, uint32_t index) {
    remove_entity(state, index);
    mine_.erase(std::remove(mine_.begin(), mine_.end(), index), mine_.end());
    free_.push_back(index);
  }

  std::optional<std::string> name_;
  std::string stem_;
  RandomStream random_;
  std::vector<uint32_t> mine_;  ///< present vehicles of this generator
  std::vector<uint32_t> free_;  ///< despawned, reusable
};

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
        central_(central) {}

  void step(SimState& state) override {
    prune(state);
    // A copy: spawning appends entities, which may move the world's storage.
    const EntityState centre = state.world.entities[central_].state;
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
      const EntityState& e = state.world.entities[index].state;
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
      const auto at = lane_spot(*state.map, x, y);
      if (!at || !clear_of_others(state, at->pose.x, at->pose.y)) {
        continue;
      }
      const double dx = at->pose.x - centre.pose.x, dy = at->pose.y - centre.pose.y;
      if (std::hypot(dx, dy) < action_.inner_radius || !direction_wanted(at->pose.h, centre)) {
        continue;
      }
      spawn(state, *at, draw_speed(centre), draw_category(action_.traffic_definition, random_));
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

  double draw_speed(const EntityState& centre) {
    if (action_.initial_speed_range) {
      return random_.uniform(action_.initial_speed_range->lower_limit,
                             action_.initial_speed_range->upper_limit);
    }
    if (action_.velocity) {
      return *action_.velocity;
    }
    return centre.speed > 0.0 ? centre.speed : kDefaultSpeed;
  }

  const xosc::TrafficSwarmAction& action_;
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
      const auto spot =
          lane_spot(*state.map, at_.pose.x + r * std::cos(angle), at_.pose.y + r * std::sin(angle));
      if (!spot || !clear_of_others(state, spot->pose.x, spot->pose.y)) {
        continue;
      }
      spawn(state, *spot, action_.speed.value_or(kDefaultSpeed),
            draw_category(action_.traffic_definition, random_));
      due_ -= 1.0;
    }
    due_ = std::min(due_, 2.0);  // no burst after a long blocked spell
  }

 private:
  const xosc::TrafficSourceAction& action_;
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
      const EntityState& e = state.world.entities[i].state;
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

void warn_distribution(const std::optional<xosc::TrafficDistribution>& distribution,
                       SimState& state) {
  if (distribution) {
    state.diagnostics.add_once(
        "traffic-distribution",
        distribution->source.warning("TrafficDistribution is not used: the generated vehicles "
                                     "are cars (or as a TrafficDefinition's categories say)"));
  }
}

}  // namespace

std::unique_ptr<TrafficGenerator> make_swarm(const xosc::TrafficSwarmAction& action,
                                             SimState& state) {
  const auto central = state.world.find(action.central_object);
  if (!central) {
    throw InputError(action.source.error("unknown central entity '" + action.central_object + "'"));
  }
  warn_distribution(action.traffic_distribution, state);
  return std::make_unique<Swarm>(action, state, *central);
}

std::unique_ptr<TrafficGenerator> make_source(const xosc::TrafficSourceAction& action,
                                              SimState& state) {
  warn_distribution(action.traffic_distribution, state);
  return std::make_unique<Source>(action, state,
                                  resolve_position(action.position, state, std::nullopt));
}

std::unique_ptr<TrafficGenerator> make_sink(const xosc::TrafficSinkAction& action,
                                            SimState& state) {
  return std::make_unique<Sink>(action, state,
                                resolve_position(action.position, state, std::nullopt));
}

}  // namespace corsa::engine::detail
