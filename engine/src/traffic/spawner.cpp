#include "traffic/spawner.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "controllers/controllers.h"
#include "corsa/core/diagnostic.h"
#include "corsa/xodr/map.h"
#include "lanes/lane_follow.h"
#include "motion/placement.h"
#include "state/entity_builder.h"
#include "state/sim_state.h"
#include "traffic/traffic_update.h"

namespace corsa::engine::detail {
namespace {

xosc::ScenarioObject vehicle_prototype(xosc::VehicleCategory category) {
  xosc::ScenarioObject object;
  object.object = vehicle_model(category);
  return object;
}

// The corsa controller a prototype asks for; otherwise `--controller` or the car-following
// controller for vehicles (so that generated traffic does not run into itself), the default
// controller for pedestrians.
ControllerKind controller_for(SimState& state, const xosc::ScenarioObject& object,
                              ObjectKind kind) {
  for (const xosc::ObjectController& oc : object.controllers) {
    ControllerKind chosen = ControllerKind::kDefault;
    if (controller_kind_of(oc.controller, state.diagnostics, chosen)) {
      return chosen;
    }
  }
  if (kind != ObjectKind::kVehicle) {
    return ControllerKind::kDefault;
  }
  ControllerKind chosen = ControllerKind::kAcc;
  if (!state.options.controller.empty()) {
    parse_controller_kind(state.options.controller, chosen);
  }
  return chosen;
}

}  // namespace

TrafficMix::TrafficMix(const std::optional<xosc::TrafficDefinition>& definition,
                       const xosc::TrafficDistribution* distribution) {
  if (distribution != nullptr) {
    double entries = 0.0;
    for (const auto& entry : distribution->entries) {
      entries += entry.weight;
    }
    for (const auto& entry : distribution->entries) {
      double within = 0.0;
      for (const auto& item : entry.entities) {
        within += item.weight;
      }
      for (const auto& item : entry.entities) {
        xosc::ScenarioObject object;
        object.object = item.object.object;
        object.controllers = item.object.controllers;
        object.source = item.object.source;
        prototypes_.push_back(std::move(object));
        entry_properties_.push_back(&entry.properties);
        // All weights zero: equally likely (the parser rejects negative ones).
        const double a = entries > 0.0 ? entry.weight / entries : 1.0;
        const double b = within > 0.0 ? item.weight / within : 1.0;
        weights_.push_back(a * b);
      }
    }
  } else if (definition) {
    for (const auto& entry : definition->vehicle_categories) {
      prototypes_.push_back(vehicle_prototype(entry.category));
      weights_.push_back(std::max(0.0, entry.weight));
    }
  }
  if (prototypes_.empty()) {
    prototypes_.push_back(vehicle_prototype(xosc::VehicleCategory::kCar));
    weights_.assign(1, 1.0);
  }
  if (std::none_of(weights_.begin(), weights_.end(), [](double w) { return w > 0.0; })) {
    weights_.assign(weights_.size(), 1.0);
  }
}

TrafficMix::TrafficMix(xosc::ScenarioObject prototype) {
  prototypes_.push_back(std::move(prototype));
  weights_.assign(1, 1.0);
}

size_t TrafficMix::draw(RandomStream& random) const {
  return prototypes_.size() == 1 ? 0 : random.weighted_index(weights_);
}

bool TrafficMix::walks(size_t index) const {
  return std::holds_alternative<xosc::Pedestrian>(prototypes_[index].object);
}

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

xosc::Pedestrian pedestrian_model() {
  xosc::Pedestrian p;
  p.name = "traffic_pedestrian";
  p.mass = 75.0;
  p.bounding_box.center_z = 0.9;
  p.bounding_box.length = 0.5;
  p.bounding_box.width = 0.6;
  p.bounding_box.height = 1.8;
  return p;
}

std::optional<ResolvedPosition> lane_spot(const xodr::Map& map, double x, double y, bool walks,
                                          bool flip, double reach) {
  xodr::LocateOptions options;
  options.max_distance = reach;
  options.drivable_only = !walks;
  const auto located = map.locate(x, y, options);
  if (!located || located->lane == 0) {
    return std::nullopt;
  }
  if (walks) {
    const auto span = map.lane_span(located->road, located->s, located->lane);
    if (!span || map.road(located->road).lane_sections.empty()) {
      return std::nullopt;
    }
    // Only sidewalks: the locate above answers for any lane type.
    const auto& section = map.road(located->road).lane_sections[located->section];
    const auto lane = std::find_if(section.lanes.begin(), section.lanes.end(),
                                   [&](const xodr::Lane& l) { return l.id == located->lane; });
    if (lane == section.lanes.end() || lane->type != xodr::LaneType::kSidewalk) {
      return std::nullopt;
    }
  }
  const auto t = lane_center_t(map, located->road, located->s, located->lane);
  if (!t) {
    return std::nullopt;
  }
  int dir = located->lane < 0 ? 1 : -1;
  if (flip) {
    dir = -dir;
  }
  ResolvedPosition at;
  at.pose = map.world_pose(located->road, located->s, *t);
  at.pose.h = travel_heading(map, located->road, located->s, dir);
  at.road = RoadPoint{located->road, located->s, *t, located->lane};
  return at;
}

namespace {

bool too_close(const Entity& other, double x, double y, double clearance) {
  return other.state().placed &&
         std::hypot(other.state().pose.x - x, other.state().pose.y - y) < clearance;
}

}  // namespace

bool clear_of_others(const SimState& state, double x, double y, double clearance,
                     const PointGrid* grid) {
  if (grid == nullptr) {
    for (const Entity& other : state.world.entities) {
      if (too_close(other, x, y, clearance)) {
        return false;
      }
    }
    return true;
  }
  std::vector<uint32_t> near;
  grid->query(x, y, clearance, near);
  for (const uint32_t index : near) {
    if (too_close(state.world.entities[index], x, y, clearance)) {
      return false;
    }
  }
  return true;
}

PointGrid placed_entities_grid(const SimState& state, double cell) {
  PointGrid grid(cell);
  for (uint32_t i = 0; i < state.world.entities.size(); ++i) {
    const Entity& entity = state.world.entities[i];
    if (entity.state().placed) {
      grid.add(entity.state().pose.x, entity.state().pose.y, i);
    }
  }
  return grid;
}

namespace {

// A generated entity's name, unless an entity already has it (the scenario's own, named as a
// generator names its objects): then the first free `<name>_<k>`, k from 2, with a warning. Two
// entities under one name would share their rows in the trajectory and every lookup by name.
std::string free_name(SimState& state, std::string name) {
  if (!state.world.by_name.contains(name)) {
    return name;
  }
  std::string taken = std::move(name);
  for (size_t k = 2;; ++k) {
    name = taken + "_" + std::to_string(k);
    if (!state.world.by_name.contains(name)) {
      break;
    }
  }
  state.diagnostics.add(make_warning(
      "", 0,
      "generated entity '" + taken + "': an entity of that name exists; called '" + name + "'"));
  return name;
}

}  // namespace

uint32_t GeneratorBase::spawn(SimState& state, const TrafficMix& mix, size_t kind,
                              const ResolvedPosition& at, double speed, const std::string& name) {
  uint32_t index = 0;
  const auto reuse = std::find_if(free_.begin(), free_.end(), [&](const FreeSlot& slot) {
    return slot.mix == &mix && slot.kind == kind;
  });
  if (reuse != free_.end()) {
    index = reuse->index;
    free_.erase(reuse);
  } else {
    xosc::ScenarioObject object = mix.prototype(kind);
    ++state.traffic.spawned_count;
    object.name = free_name(state, !name.empty() ? name
                                                 : (name_ ? *name_ : stem_) + "_" +
                                                       std::to_string(state.traffic.spawned_count));
    state.traffic.spawned_objects.push_back(std::move(object));
    const xosc::ScenarioObject& stored = state.traffic.spawned_objects.back();
    Entity entity(describe_object(stored, state.diagnostics));
    entity.object = &stored;
    index = static_cast<uint32_t>(state.world.entities.size());
    state.world.by_name.emplace(stored.name, index);
    state.world.entities.push_back(std::move(entity));
    control_of(state, index).kind =
        controller_for(state, stored, state.world.entities[index].info.kind);
  }
  Entity& entity = state.world.entities[index];
  place_entity(state, entity, at, xosc::Source{}, false);
  entity.write_state().speed = speed;
  entity.speed_command = speed;
  control_of(state, index).dynamics.reset();
  mine_.push_back(index);
  kinds_.push_back({index, &mix, kind});
  note_spawned(state, index);
  return index;
}

void GeneratorBase::prune(const SimState& state) {
  for (const uint32_t index : std::vector<uint32_t>(mine_)) {
    if (!state.world.entities[index].state().placed) {
      mine_.erase(std::remove(mine_.begin(), mine_.end(), index), mine_.end());
      const auto slot = std::find_if(kinds_.begin(), kinds_.end(),
                                     [&](const FreeSlot& s) { return s.index == index; });
      if (slot != kinds_.end()) {
        free_.push_back(*slot);
        kinds_.erase(slot);
      }
    }
  }
}

void GeneratorBase::despawn(SimState& state, uint32_t index) {
  remove_entity(state, index);
  prune(state);
}

}  // namespace corsa::engine::detail
