// Seeded random NPCs (see run_rig_npc.h).

#include "run_rig_npc.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "corsa/core/random.h"
#include "corsa/xodr/map.h"

namespace corsa::cli {
namespace {

constexpr double kPi = std::numbers::pi;

engine::Pose pose_on(const xodr::Map& map, const NpcTrack& track, double time, double& speed) {
  const double length = map.road(track.road).length;
  double s = track.s0 + track.direction * track.speed * time;
  speed = track.speed;
  if (s < 0.0 || s > length) {
    s = std::clamp(s, 0.0, length);  // held at the road's end
    speed = 0.0;
  }
  const auto span = map.lane_span(track.road, s, track.lane);
  const double t = span ? span->t_center() : 0.0;
  const xodr::WorldPose w = map.world_pose(track.road, s, t);
  const double heading = track.direction > 0.0 ? w.h : w.h + kPi;
  return {w.x, w.y, w.z, std::remainder(heading, 2.0 * kPi), 0.0, 0.0};
}

// Candidate lanes of one kind, weighted by road length.
struct Candidate {
  uint32_t road = 0;
  uint32_t section = 0;
  int lane = 0;
  double s_begin = 0.0;
  double s_end = 0.0;
};

std::vector<Candidate> lanes_of(const xodr::Map& map, xodr::LaneType type) {
  std::vector<Candidate> out;
  for (size_t r = 0; r < map.road_count(); ++r) {
    const xodr::Road& road = map.road(r);
    for (size_t k = 0; k < road.lane_sections.size(); ++k) {
      const double end = map.section_end(r, k);
      for (const xodr::Lane& lane : road.lane_sections[k].lanes) {
        if (lane.id != 0 && lane.type == type && end - road.lane_sections[k].s > 10.0) {
          out.push_back({static_cast<uint32_t>(r), static_cast<uint32_t>(k), lane.id,
                         road.lane_sections[k].s, end});
        }
      }
    }
  }
  return out;
}

bool clear_of(const std::vector<engine::Pose>& taken, const engine::Pose& p, double gap) {
  return std::all_of(taken.begin(), taken.end(), [&](const engine::Pose& q) {
    return std::hypot(p.x - q.x, p.y - q.y) >= gap;
  });
}

void place_kind(const xodr::Map& map, bool vehicle, int count, RandomStream& random,
                std::vector<engine::Pose>& taken, NpcSet& out) {
  const std::vector<Candidate> lanes =
      lanes_of(map, vehicle ? xodr::LaneType::kDriving : xodr::LaneType::kSidewalk);
  if (lanes.empty()) {
    return;
  }
  std::vector<double> weights;
  for (const Candidate& c : lanes) {
    weights.push_back(c.s_end - c.s_begin);
  }
  int placed = 0;
  for (int attempt = 0; placed < count && attempt < 50 * count; ++attempt) {
    const Candidate& c = lanes[random.weighted_index(weights)];
    NpcTrack track;
    track.road = c.road;
    track.lane = c.lane;
    track.s0 = random.uniform(c.s_begin + 2.0, c.s_end - 2.0);
    const bool right_hand = map.road(c.road).rule == xodr::TrafficRule::kRightHand;
    // Right-hand traffic drives along s in right lanes (negative ids); pedestrians either way.
    track.direction = vehicle ? ((c.lane < 0) == right_hand ? 1.0 : -1.0)
                              : (random.uniform01() < 0.5 ? 1.0 : -1.0);
    // Vehicles: one speed per lane (no NPC runs into another of its lane), 8-14 m/s.
    track.speed = vehicle ? 8.0 + 6.0 * RandomStream::derive(
                                            c.road * 131 + static_cast<uint64_t>(c.lane + 64),
                                            "npc-lane-speed")
                                            .uniform01()
                          : random.uniform(1.0, 1.6);
    double speed = 0.0;
    const engine::Pose pose = pose_on(map, track, 0.0, speed);
    if (!clear_of(taken, pose, vehicle ? 10.0 : 2.0)) {
      continue;
    }
    taken.push_back(pose);
    engine::EntitySnapshot e;
    e.name = std::string(vehicle ? "npc_vehicle_" : "npc_pedestrian_") + std::to_string(placed);
    e.category = vehicle ? engine::EntityCategory::kCar : engine::EntityCategory::kPedestrian;
    e.box = vehicle ? engine::Box{1.4, 0.0, 0.75, 4.5, 1.85, 1.5}
                    : engine::Box{0.0, 0.0, 0.9, 0.5, 0.6, 1.8};
    e.pose = pose;
    e.speed = speed;
    out.entities.push_back(std::move(e));
    out.tracks.push_back(track);
    ++placed;
  }
}

}  // namespace

NpcSet place_npcs(const engine::Simulation& simulation, int vehicles, int pedestrians,
                  Diagnostics& diagnostics) {
  NpcSet out;
  out.map = simulation.map();
  if (out.map == nullptr) {
    diagnostics.add(make_warning("", 0, "--npc: the scenario has no road network; no NPCs"));
    return out;
  }
  std::vector<engine::Pose> taken;
  for (size_t i = 0; i < simulation.entity_count(); ++i) {
    taken.push_back(simulation.state(i).pose);
  }
  RandomStream random = RandomStream::derive(simulation.options().seed, "npc");
  place_kind(*out.map, true, vehicles, random, taken, out);
  const size_t vehicles_placed = out.entities.size();
  place_kind(*out.map, false, pedestrians, random, taken, out);
  const size_t pedestrians_placed = out.entities.size() - vehicles_placed;
  if (vehicles_placed < static_cast<size_t>(vehicles) ||
      pedestrians_placed < static_cast<size_t>(pedestrians)) {
    diagnostics.add(
        make_warning("", 0,
                     "--npc: placed " + std::to_string(vehicles_placed) + " of " +
                         std::to_string(vehicles) + " vehicles and " +
                         std::to_string(pedestrians_placed) + " of " + std::to_string(pedestrians) +
                         " pedestrians (not enough free driving lanes / sidewalks on the map)"));
  }
  for (size_t i = 0; i < out.entities.size(); ++i) {
    out.entities[i].instance_id = static_cast<uint32_t>(simulation.entity_count() + 1 + i);
  }
  return out;
}

void move_npcs(const NpcSet& npcs, engine::WorldSnapshot& world) {
  for (size_t i = 0; i < npcs.entities.size(); ++i) {
    engine::EntitySnapshot e = npcs.entities[i];
    double speed = 0.0;
    e.pose = pose_on(*npcs.map, npcs.tracks[i], world.time, speed);
    e.speed = speed;
    e.vx = speed * std::cos(e.pose.h);
    e.vy = speed * std::sin(e.pose.h);
    world.entities.push_back(std::move(e));
  }
}

}  // namespace corsa::cli
