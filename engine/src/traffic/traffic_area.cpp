// TrafficAreaAction (OpenSCENARIO 1.3 §7.5.6, XSD TrafficAreaAction / TrafficArea): keeps
// `numberOfEntities` generated entities inside an area, a polygon of Positions or RoadRanges.
// Without `continuous` the entities are spawned once, when the action starts, and then drive on
// wherever they go; with it, those that leave the area are removed and others spawn in their
// place, so that the area keeps its number.
//
// A RoadRange is read as a stretch along its RoadCursors in document order: each cursor's road
// from the cursor's s (default the road's start) to the next cursor's s on the same road, or to
// the road's end; a last cursor alone on its road covers that road from its start to the
// cursor's s (default the end). `length`, when given, caps the stretch (m, in that order). A
// cursor's Lanes restrict its piece to those lanes; without them every drivable lane counts.

#include <algorithm>
#include <cmath>
#include <limits>

#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"
#include "lanes/lane_follow.h"
#include "positions/position_resolver.h"
#include "state/sim_state.h"
#include "traffic/spawn_speed.h"
#include "traffic/spawner.h"
#include "traffic/traffic_generators.h"

namespace corsa::engine::detail {
namespace {

constexpr double kAreaVehicleClearance = 12.0;  // m from any other entity's reference point
constexpr double kAreaWalkerClearance = 2.0;    // m
constexpr int kAreaTriesPerStep = 8;
constexpr int kTriesPerEntity = 40;     // for the one-off fill
constexpr double kAreaGridCell = 16.0;  // m, cells of the grid the fill looks clearances up in

struct Piece {
  uint32_t road = 0;
  double s0 = 0.0;
  double s1 = 0.0;
  std::vector<int> lanes;  ///< empty: every drivable lane
};

uint32_t road_of(const xodr::Map& map, const xosc::RoadCursor& cursor) {
  const auto road = map.find_road(cursor.road_id);
  if (!road) {
    throw InputError(cursor.source.error("unknown road '" + cursor.road_id + "'"));
  }
  return static_cast<uint32_t>(*road);
}

void add_pieces(const xodr::Map& map, const xosc::RoadRange& range, std::vector<Piece>& out) {
  double budget = range.length.value_or(std::numeric_limits<double>::infinity());
  const auto& cursors = range.cursors;
  for (size_t i = 0; i < cursors.size() && budget > 0.0; ++i) {
    const uint32_t road = road_of(map, cursors[i]);
    const double length = map.road(road).length;
    const bool next_same = i + 1 < cursors.size() && road_of(map, cursors[i + 1]) == road;
    const bool prev_same = i > 0 && road_of(map, cursors[i - 1]) == road;
    double s0 = 0.0, s1 = length;
    if (next_same) {
      s0 = cursors[i].s.value_or(0.0);
      s1 = cursors[i + 1].s.value_or(length);
    } else if (i + 1 == cursors.size()) {
      if (prev_same) {
        continue;  // the previous cursor's piece ends here
      }
      s1 = cursors[i].s.value_or(length);
    } else {
      s0 = cursors[i].s.value_or(0.0);
    }
    s0 = std::clamp(s0, 0.0, length);
    s1 = std::clamp(s1, 0.0, length);
    if (s1 < s0) {
      std::swap(s0, s1);
    }
    s1 = std::min(s1, s0 + budget);
    budget -= s1 - s0;
    if (s1 > s0) {
      out.push_back({road, s0, s1, cursors[i].lanes});
    }
  }
}

// Ray casting (even-odd rule).
bool inside_polygon(const std::vector<std::pair<double, double>>& polygon, double x, double y) {
  bool inside = false;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const auto [xi, yi] = polygon[i];
    const auto [xj, yj] = polygon[j];
    if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) {
      inside = !inside;
    }
  }
  return inside;
}

bool lane_allowed(const Piece& piece, int lane) {
  return piece.lanes.empty() ||
         std::find(piece.lanes.begin(), piece.lanes.end(), lane) != piece.lanes.end();
}

class Area final : public GeneratorBase {
 public:
  Area(const xosc::TrafficAreaAction& action, SimState& state)
      : GeneratorBase(
            action.traffic_name, "area",
            derive_seed(state.options.seed, "area:" + std::to_string(action.source.line))),
        action_(action),
        mix_(std::nullopt, &action.traffic_distribution) {
    if (state.map == nullptr) {
      return;
    }
    for (const xosc::Position& p : action.polygon) {
      const ResolvedPosition at = resolve_position(p, state, std::nullopt);
      polygon_.emplace_back(at.pose.x, at.pose.y);
    }
    for (const xosc::RoadRange& range : action.road_ranges) {
      add_pieces(*state.map, range, pieces_);
    }
    for (const Piece& piece : pieces_) {
      weights_.push_back(piece.s1 - piece.s0);
    }
  }

  void step(SimState& state) override {
    if (state.map == nullptr || (polygon_.empty() && pieces_.empty()) || done_) {
      return;
    }
    prune(state);
    if (!action_.continuous) {
      // Once: the area is filled now, the entities then go where they go.
      const int tries = kTriesPerEntity * static_cast<int>(action_.number_of_entities);
      PointGrid others = placed_entities_grid(state, kAreaGridCell);
      for (int i = 0; i < tries && mine_.size() < action_.number_of_entities; ++i) {
        try_spawn(state, &others);
      }
      done_ = true;
      return;
    }
    for (const uint32_t index : std::vector<uint32_t>(mine_)) {
      if (!inside(*state.map, state.world.entities[index].state())) {
        despawn(state, index);
      }
    }
    for (int i = 0; i < kAreaTriesPerStep && mine_.size() < action_.number_of_entities; ++i) {
      try_spawn(state);
    }
  }

 private:
  bool inside(const xodr::Map& map, const EntityState& e) const {
    if (!polygon_.empty()) {
      return inside_polygon(polygon_, e.pose.x, e.pose.y);
    }
    (void)map;
    if (!e.road) {
      return false;
    }
    return std::any_of(pieces_.begin(), pieces_.end(), [&](const Piece& piece) {
      return piece.road == e.road->road && e.road->s >= piece.s0 && e.road->s <= piece.s1 &&
             lane_allowed(piece, e.road->lane);
    });
  }

  // One attempt; `others` (a grid of the placed entities, kept up to date here) makes the
  // clearance test cheap when many are placed at once.
  void try_spawn(SimState& state, PointGrid* others = nullptr) {
    const size_t kind = mix_.draw(random_);
    const bool walks = mix_.walks(kind);
    const auto at =
        polygon_.empty() ? spot_on_range(*state.map, walks) : spot_in_polygon(*state.map, walks);
    if (!at || !clear_of_others(state, at->pose.x, at->pose.y,
                                walks ? kAreaWalkerClearance : kAreaVehicleClearance, others)) {
      return;
    }
    // The action gives no speed (traffic/spawn_speed.h says where it comes from).
    const double speed = spawn_speed(state, random_, mix_, kind, *at, std::nullopt);
    const uint32_t index = spawn(state, mix_, kind, *at, speed);
    if (others != nullptr) {
      const Pose& pose = state.world.entities[index].state().pose;
      others->add(pose.x, pose.y, index);
    }
  }

  std::optional<ResolvedPosition> spot_in_polygon(const xodr::Map& map, bool walks) {
    double x0 = polygon_[0].first, x1 = x0, y0 = polygon_[0].second, y1 = y0;
    for (const auto& [x, y] : polygon_) {
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    const double x = random_.uniform(x0, x1), y = random_.uniform(y0, y1);
    if (!inside_polygon(polygon_, x, y)) {
      return std::nullopt;
    }
    auto at = lane_spot(map, x, y, walks, walks && random_.uniform01() < 0.5);
    if (!at || !inside_polygon(polygon_, at->pose.x, at->pose.y)) {
      return std::nullopt;
    }
    return at;
  }

  std::optional<ResolvedPosition> spot_on_range(const xodr::Map& map, bool walks) {
    const Piece& piece = pieces_[random_.weighted_index(weights_)];
    const double s = random_.uniform(piece.s0, piece.s1);
    const xodr::Road& road = map.road(piece.road);
    const auto& section = road.lane_sections[map.section_index(piece.road, s)];
    std::vector<int> lanes;
    for (const xodr::Lane& lane : section.lanes) {
      const bool usable =
          walks ? lane.type == xodr::LaneType::kSidewalk : xodr::is_drivable(lane.type);
      if (lane.id != 0 && usable && lane_allowed(piece, lane.id)) {
        lanes.push_back(lane.id);
      }
    }
    if (lanes.empty()) {
      return std::nullopt;
    }
    const int lane =
        lanes[static_cast<size_t>(random_.uniform_int(0, static_cast<int64_t>(lanes.size()) - 1))];
    const auto t = lane_center_t(map, piece.road, s, lane);
    if (!t) {
      return std::nullopt;
    }
    int dir = lane < 0 ? 1 : -1;
    if (walks && random_.uniform01() < 0.5) {
      dir = -dir;
    }
    ResolvedPosition at;
    at.pose = map.world_pose(piece.road, s, *t);
    at.pose.h = travel_heading(map, piece.road, s, dir);
    at.road = RoadPoint{piece.road, s, *t, lane};
    return at;
  }

  const xosc::TrafficAreaAction& action_;
  TrafficMix mix_;
  std::vector<std::pair<double, double>> polygon_;  ///< world x, y of the vertices
  std::vector<Piece> pieces_;
  std::vector<double> weights_;  ///< piece lengths
  bool done_ = false;
};

}  // namespace

std::unique_ptr<TrafficGenerator> make_area(const xosc::TrafficAreaAction& action,
                                            SimState& state) {
  return std::make_unique<Area>(action, state);
}

}  // namespace corsa::engine::detail
