// `corsa run --npc vehicles=N,pedestrians=M`: seeded random NPCs as engine entities,
// placed once at tick 0 after the Init actions. Vehicles stand on the centre of a random driving
// lane, facing its direction of travel (OpenDRIVE 1.8 §8.3 traffic rule), and drive at a speed
// drawn per lane (8-14 m/s) under the car-following controller (or `--controller`);
// pedestrians walk along a random sidewalk, either way, at 1.0-1.6 m/s. Places are drawn by
// lane length over the whole map (vehicles off junction roads), at least 10 m (vehicles; 6 m
// once the lanes are full at 10 m) or 2 m (pedestrians) from every entity, their boxes at least
// 1 m (0.5 m) clear of every other box, and vehicles not in the 60 m ahead of a scenario vehicle
// driving their way (its path). A vehicle is not placed where it could not stop, braking at
// kComfort, before a crossing in a junction ahead that a vehicle placed before it claims the
// other side of (controllers/give_way.h): giving way can then settle every crossing from the
// first step. They are entities like any other: trajectory rows, collisions, conditions,
// sensors. Generated traffic drives and walks with the precautions of controllers/npc_caution.h
// and gives way in junctions.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "controllers/give_way.h"
#include "corsa/engine/oriented_box.h"
#include "corsa/xodr/map.h"
#include "lanes/lane_follow.h"
#include "state/entity_builder.h"
#include "state/sim_state.h"
#include "traffic/spawner.h"
#include "traffic/traffic_generators.h"

namespace corsa::engine::detail {
namespace {

constexpr double kVehicleClearance = 10.0;      // m
constexpr double kVehicleTightClearance = 6.0;  // m, once the lanes are full at kVehicleClearance
constexpr double kWalkerClearance = 2.0;        // m
constexpr int kTriesPerNpc = 50;
constexpr double kGridCell = 16.0;         // m, cells of the grid the clearances are looked up in
constexpr double kVehicleBoxMargin = 1.0;  // m between boxes at the start
constexpr double kWalkerBoxMargin = 0.5;   // m
constexpr double kPathAhead = 60.0;        // m ahead of a scenario vehicle kept free

// The placed entities around a new NPC: their reference points in a grid, how far their boxes
// reach from them, and the scenario's own vehicles (few; their paths are kept free).
struct Placed {
  PointGrid grid{kGridCell};
  double reach = 0.0;  ///< m, the greatest box_reach of a placed entity
  std::vector<uint32_t> scenario_vehicles;
  std::vector<uint32_t> near;  ///< scratch

  explicit Placed(const SimState& state) : grid(placed_entities_grid(state, kGridCell)) {
    for (uint32_t i = 0; i < state.world.entities.size(); ++i) {
      const Entity& entity = state.world.entities[i];
      if (!entity.state().placed) {
        continue;
      }
      reach = std::max(reach, box_reach(entity.info.box));
      if (entity.info.kind == ObjectKind::kVehicle && state.traffic.lifetimes.count(i) == 0) {
        scenario_vehicles.push_back(i);
      }
    }
  }

  void add(const Entity& entity, uint32_t index) {
    grid.add(entity.state().pose.x, entity.state().pose.y, index);
    reach = std::max(reach, box_reach(entity.info.box));
  }
};

// Whether an NPC with box `box` at `pose` starts clear of everyone: its box `margin` metres from
// every placed entity's box, and (vehicles) not in the path just ahead of a scenario vehicle
// going its way, which would not brake for it. Only the entities whose boxes can be that near
// are looked at.
bool starts_clear(const SimState& state, Placed& placed, const Box& box, const Pose& pose,
                  bool walks, double margin) {
  const OrientedBox mine = box_of(box, pose);
  placed.near.clear();
  placed.grid.query(pose.x, pose.y, margin + box_reach(box) + placed.reach, placed.near);
  for (const uint32_t i : placed.near) {
    const Entity& other = state.world.entities[i];
    if (other.state().placed &&
        box_distance(mine, box_of(other.info.box, other.state().pose)) < margin) {
      return false;
    }
  }
  if (walks) {
    return true;
  }
  for (const uint32_t i : placed.scenario_vehicles) {
    const Entity& other = state.world.entities[i];
    if (!other.state().placed || std::cos(other.state().pose.h - pose.h) < 0.7) {
      continue;
    }
    // Ahead of it within its width: in its path.
    const double c = std::cos(other.state().pose.h), s = std::sin(other.state().pose.h);
    const double dx = pose.x - other.state().pose.x, dy = pose.y - other.state().pose.y;
    const double along = dx * c + dy * s;
    const double across = -dx * s + dy * c;
    if (along > 0.0 && along < kPathAhead &&
        std::abs(across) < 0.5 * (other.info.box.width + box.width) + 0.5) {
      return false;
    }
  }
  return true;
}

// The crossings in junctions (controllers/junction_conflicts.h) the placed vehicles claim, as
// the claims pass of giving way will see them at the first step: which sides of each conflict.
class Crossings {
 public:
  explicit Crossings(const JunctionConflicts& conflicts)
      : conflicts_(conflicts), sides_(conflicts.conflict_count(), 0) {}

  // Whether a vehicle with box `box`, held at `lane` at `speed`, could stop braking at kComfort
  // before every crossing ahead whose other side a placed vehicle claims. Two placed where
  // neither can stop before the crossing they share would both be committed to it.
  bool clear(const xodr::Map& map, const LaneFollow& lane, const Box& box, double speed) {
    path_ = lane_path_of(map, lane);
    const double front = box.center_x + 0.5 * box.length;
    const double rear = box.center_x - 0.5 * box.length;
    approach_.count = collect_claims(conflicts_, path_, front, rear, speed, approach_);
    const double comfortable = speed * speed / (2.0 * kComfort);
    for (uint32_t k = 0; k < approach_.count; ++k) {
      const Claim& c = approach_.claims[k];
      if ((sides_[c.conflict] & (1u << (1 - c.side))) != 0 && !can_stop(c.to_enter, comfortable)) {
        return false;
      }
    }
    return true;
  }

  // The last vehicle `clear` was asked about is placed: its claims are taken.
  void take() {
    for (uint32_t k = 0; k < approach_.count; ++k) {
      sides_[approach_.claims[k].conflict] |= static_cast<uint8_t>(1u << approach_.claims[k].side);
    }
  }

 private:
  const JunctionConflicts& conflicts_;  ///< NpcPlacement::conflicts
  std::vector<uint8_t> sides_;  ///< by conflict: bit `side` set when a placed vehicle claims it
  LanePath path_;
  Approach approach_;
};

struct Candidate {
  uint32_t road = 0;
  int lane = 0;
  double s_begin = 0.0;
  double s_end = 0.0;
};

// The lanes places are drawn on, and the table that draws them by length.
struct Lanes {
  const std::vector<Candidate>& candidates;  ///< not empty
  WeightedTable by_length;
};

std::vector<Candidate> lanes_of(const xodr::Map& map, bool walks) {
  std::vector<Candidate> out;
  for (size_t r = 0; r < map.road_count(); ++r) {
    const xodr::Road& road = map.road(r);
    if (!walks && road.in_junction()) {
      continue;  // a vehicle placed in a junction might stand in another's way through it
    }
    for (size_t k = 0; k < road.lane_sections.size(); ++k) {
      const double begin = road.lane_sections[k].s;
      const double end = map.section_end(r, k);
      for (const xodr::Lane& lane : road.lane_sections[k].lanes) {
        const bool usable =
            walks ? lane.type == xodr::LaneType::kSidewalk : lane.type == xodr::LaneType::kDriving;
        if (lane.id != 0 && usable && end - begin > 10.0) {
          out.push_back({static_cast<uint32_t>(r), lane.id, begin, end});
        }
      }
    }
  }
  return out;
}

xosc::ScenarioObject prototype(bool walks) {
  xosc::ScenarioObject object;
  if (walks) {
    object.object = pedestrian_model();
  } else {
    object.object = vehicle_model(xosc::VehicleCategory::kCar);
  }
  return object;
}

class Npcs final : public GeneratorBase, public NpcPlacement {
 public:
  Npcs(uint64_t seed, Diagnostics& diagnostics)
      : GeneratorBase(std::string("corsa:npc"), "npc", seed),
        vehicles_(prototype(false)),
        walkers_(prototype(true)),
        vehicle_box_(describe_object(vehicles_.prototype(0), diagnostics).box),
        walker_box_(describe_object(walkers_.prototype(0), diagnostics).box) {}

  // NPCs are placed once; afterwards they drive and walk on their own.
  void step(SimState&) override {}

  // Places up to `count` NPCs of one kind; returns how many fitted. When the lanes are full
  // with vehicles kVehicleClearance apart, the rest go between them, kVehicleTightClearance
  // apart (still off junctions, their boxes kVehicleBoxMargin clear). Both passes draw from one
  // table of the lanes' lengths, made here.
  uint32_t place(SimState& state, bool walks, uint32_t count) {
    const std::vector<Candidate> lanes = lanes_of(*state.map, walks);
    if (lanes.empty()) {
      return 0;
    }
    std::vector<double> weights;
    for (const Candidate& c : lanes) {
      weights.push_back(c.s_end - c.s_begin);
    }
    const Lanes drawn{lanes, WeightedTable(weights)};
    Placed others(state);
    if (walks) {
      return place_on(state, others, nullptr, drawn, kWalkerClearance, count, 0);
    }
    if (!conflicts_) {
      conflicts_ = std::make_shared<const JunctionConflicts>(JunctionConflicts::build(*state.map));
    }
    Crossings crossings(*conflicts_);
    const uint32_t placed = place_on(state, others, &crossings, drawn, kVehicleClearance, count, 0);
    if (placed == count) {
      return placed;
    }
    return place_on(state, others, &crossings, drawn, kVehicleTightClearance, count, placed);
  }

 private:
  // Draws places on `lanes` (by length), `clearance` from every entity, until `count` NPCs are
  // placed (`placed` of them already) or kTriesPerNpc tries per NPC still to place have
  // failed; returns how many are placed. Vehicles are placed with their `crossings`, walkers
  // without.
  uint32_t place_on(SimState& state, Placed& others, Crossings* crossings, const Lanes& lanes,
                    double clearance, uint32_t count, uint32_t placed) {
    const xodr::Map& map = *state.map;
    const bool walks = crossings == nullptr;
    const uint32_t tries = kTriesPerNpc * (count - placed);
    for (uint32_t attempt = 0; placed < count && attempt < tries; ++attempt) {
      const Candidate& c = lanes.candidates[lanes.by_length.draw(random_)];
      const double s = random_.uniform(c.s_begin + 2.0, c.s_end - 2.0);
      const bool right_hand = map.road(c.road).rule == xodr::TrafficRule::kRightHand;
      int dir = (c.lane < 0) == right_hand ? 1 : -1;
      if (walks && random_.uniform01() < 0.5) {
        dir = -dir;
      }
      const double speed =
          walks ? random_.uniform(1.0, 1.6)
                : 8.0 + 6.0 * RandomStream::derive(
                                  c.road * 131 + static_cast<uint64_t>(c.lane + 64), "npc-lane")
                                  .uniform01();
      const auto t = lane_center_t(map, c.road, s, c.lane);
      if (!t) {
        continue;
      }
      ResolvedPosition at;
      at.pose = map.world_pose(c.road, s, *t);
      at.pose.h = travel_heading(map, c.road, s, dir);
      at.road = RoadPoint{c.road, s, *t, c.lane};
      if (!clear_of_others(state, at.pose.x, at.pose.y, clearance, &others.grid) ||
          !starts_clear(state, others, walks ? walker_box_ : vehicle_box_,
                        Pose{at.pose.x, at.pose.y, at.pose.z, at.pose.h, at.pose.p, at.pose.r},
                        walks, walks ? kWalkerBoxMargin : kVehicleBoxMargin)) {
        continue;
      }
      if (!walks) {
        LaneFollow lane;
        if (!attach_to_lane(map, lane, c.road, s, *t, c.lane, at.pose.h) ||
            !crossings->clear(map, lane, vehicle_box_, speed)) {
          continue;
        }
        crossings->take();
      }
      const std::string name =
          std::string(walks ? "npc_pedestrian_" : "npc_vehicle_") + std::to_string(placed);
      const uint32_t index = spawn(state, walks ? walkers_ : vehicles_, 0, at, speed, name);
      if (!walks) {
        vehicle_flags_.resize(std::max<size_t>(vehicle_flags_.size(), index + 1), 0);
        vehicle_flags_[index] = 1;
      }
      others.add(state.world.entities[index], index);
      ++placed;
    }
    return placed;
  }

  TrafficMix vehicles_;
  TrafficMix walkers_;
  Box vehicle_box_;
  Box walker_box_;
};

}  // namespace

void place_npcs(SimState& state) {
  const auto& npc = state.options.npc;
  if (npc.vehicles == 0 && npc.pedestrians == 0) {
    return;
  }
  if (state.map == nullptr) {
    state.diagnostics.add(make_warning("", 0, "--npc: the scenario has no road network; no NPCs"));
    return;
  }
  auto npcs = std::make_unique<Npcs>(derive_seed(state.options.seed, "npc"), state.diagnostics);
  const uint32_t vehicles = npcs->place(state, false, npc.vehicles);
  const uint32_t walkers = npcs->place(state, true, npc.pedestrians);
  if (vehicles < npc.vehicles || walkers < npc.pedestrians) {
    state.diagnostics.add(make_warning(
        "", 0,
        "--npc: placed " + std::to_string(vehicles) + " of " + std::to_string(npc.vehicles) +
            " vehicles and " + std::to_string(walkers) + " of " + std::to_string(npc.pedestrians) +
            " pedestrians (not enough free driving lanes / sidewalks on the map)"));
  }
  state.traffic.generators.push_back(std::move(npcs));
}

}  // namespace corsa::engine::detail
