// Conflict zones and right of way of junction lanes (controllers/junction_conflicts.h).

#include "controllers/junction_conflicts.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "corsa/xodr/map.h"
#include "lanes/lane_follow.h"

namespace corsa::engine::detail {
namespace {

constexpr double kSample = 0.5;  // m between the centre line points compared
constexpr double kLevels = 2.5;  // m: points farther apart in height are on different levels
constexpr double kCell = kConflictDistance;  // m, the grid the points are looked up in

struct Sample {
  double x = 0.0, y = 0.0, z = 0.0, s = 0.0;
  uint32_t lane = 0;  ///< index into the junction's lanes
};

/// The s range of one lane near another (empty while min > max).
struct Range {
  double min = 1e300;
  double max = -1e300;
  void add(double s) {
    min = std::min(min, s);
    max = std::max(max, s);
  }
  bool empty() const { return min > max; }
};

/// The samples of one junction by grid cell (kCell square), a dense grid over their extent:
/// cell c holds index_[first_[c]] .. index_[first_[c + 1]] in sample order.
class SampleGrid {
 public:
  explicit SampleGrid(const std::vector<Sample>& samples) {
    double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300;
    for (const Sample& p : samples) {
      min_x = std::min(min_x, p.x);
      min_y = std::min(min_y, p.y);
      max_x = std::max(max_x, p.x);
      max_y = std::max(max_y, p.y);
    }
    x0_ = std::floor(min_x / kCell);
    y0_ = std::floor(min_y / kCell);
    nx_ = static_cast<int64_t>(std::floor(max_x / kCell) - x0_) + 1;
    ny_ = static_cast<int64_t>(std::floor(max_y / kCell) - y0_) + 1;
    first_.assign(static_cast<size_t>(nx_ * ny_) + 1, 0);
    cells_.resize(samples.size());
    for (size_t i = 0; i < samples.size(); ++i) {
      cells_[i] = cell(column(samples[i].x), row(samples[i].y));
      ++first_[cells_[i] + 1];
    }
    for (size_t c = 1; c < first_.size(); ++c) {
      first_[c] += first_[c - 1];
    }
    index_.resize(samples.size());
    std::vector<uint32_t> fill(first_.begin(), first_.end() - 1);
    for (uint32_t i = 0; i < samples.size(); ++i) {
      index_[fill[cells_[i]]++] = i;
    }
  }
  int64_t column(double x) const { return static_cast<int64_t>(std::floor(x / kCell) - x0_); }
  int64_t row(double y) const { return static_cast<int64_t>(std::floor(y / kCell) - y0_); }
  /// The samples of cell (cx, cy), none outside the grid.
  std::span<const uint32_t> at(int64_t cx, int64_t cy) const {
    if (cx < 0 || cy < 0 || cx >= nx_ || cy >= ny_) {
      return {};
    }
    const size_t c = cell(cx, cy);
    return {index_.data() + first_[c], index_.data() + first_[c + 1]};
  }

 private:
  size_t cell(int64_t cx, int64_t cy) const { return static_cast<size_t>(cy * nx_ + cx); }
  double x0_ = 0.0, y0_ = 0.0;
  int64_t nx_ = 0, ny_ = 0;
  std::vector<uint32_t> first_;
  std::vector<size_t> cells_;
  std::vector<uint32_t> index_;
};

// Points along the centre line of lane `node`, kSample apart, both ends included.
void sample_lane(const xodr::Map& map, xodr::LaneNode node, uint32_t lane,
                 std::vector<Sample>& out) {
  const auto& info = map.lane_graph().info(node);
  const double length = info.s_end - info.s_start;
  const int count = std::max(1, static_cast<int>(std::ceil(length / kSample)));
  for (int k = 0; k <= count; ++k) {
    // Just inside the section at its end: the s lookup there would answer for the next one.
    const double s = std::min(info.s_start + length * k / count, info.s_end - 1e-6);
    const auto t = lane_center_t(map, info.lane.road, std::max(s, info.s_start), info.lane.lane);
    if (!t) {
      continue;
    }
    const xodr::WorldPose pose = map.world_pose(info.lane.road, s, *t);
    out.push_back({pose.x, pose.y, pose.z, s, lane});
  }
}

// The lane ends a lane is entered from (in its travel direction).
std::span<const xodr::LaneEnd> entries(const xodr::LaneGraph& graph, xodr::LaneNode node) {
  return graph.ends(node, graph.info(node).direction != xodr::TravelDirection::kBackward);
}

bool share_entry(const xodr::LaneGraph& graph, xodr::LaneNode a, xodr::LaneNode b) {
  for (const xodr::LaneEnd& x : entries(graph, a)) {
    for (const xodr::LaneEnd& y : entries(graph, b)) {
      if (x.node == y.node) {
        return true;
      }
    }
  }
  return false;
}

// Whether lane `a` continues into lane `b` or `b` into `a` (two lane sections of one connecting
// lane): one vehicle drives both, so they are not in conflict with each other.
bool joined(const xodr::LaneGraph& graph, xodr::LaneNode a, xodr::LaneNode b) {
  for (const bool at_start : {false, true}) {
    for (const xodr::LaneEnd& end : graph.ends(a, at_start)) {
      if (end.node == b) {
        return true;
      }
    }
  }
  return false;
}

/// Per lane node, its zones, before they are packed.
using ZoneLists = std::vector<std::vector<ConflictZone>>;

// The conflicts among the lanes of one junction, added to `zones`; returns how many.
size_t junction_conflicts(const xodr::Map& map, const std::vector<xodr::LaneNode>& lanes,
                          size_t first_conflict, ZoneLists& zones) {
  std::vector<Sample> samples;
  for (uint32_t k = 0; k < lanes.size(); ++k) {
    sample_lane(map, lanes[k], k, samples);
  }
  const SampleGrid grid(samples);
  // near[a * n + b]: the s range of lane a within kConflictDistance of lane b. Each pair of
  // points is looked at once, from the one of the lower lane.
  const size_t n = lanes.size();
  std::vector<Range> near(n * n);
  constexpr double kReach2 = kConflictDistance * kConflictDistance;
  for (const Sample& p : samples) {
    const int64_t cx = grid.column(p.x), cy = grid.row(p.y);
    for (int64_t dx = -1; dx <= 1; ++dx) {
      for (int64_t dy = -1; dy <= 1; ++dy) {
        for (const uint32_t j : grid.at(cx + dx, cy + dy)) {
          const Sample& q = samples[j];
          if (q.lane <= p.lane || std::abs(q.z - p.z) > kLevels) {
            continue;
          }
          const double ex = q.x - p.x, ey = q.y - p.y;
          if (ex * ex + ey * ey < kReach2) {
            near[p.lane * n + q.lane].add(p.s);
            near[q.lane * n + p.lane].add(q.s);
          }
        }
      }
    }
  }
  const auto& graph = map.lane_graph();
  size_t conflicts = 0;
  for (size_t a = 0; a < n; ++a) {
    for (size_t b = a + 1; b < n; ++b) {
      const Range& on_a = near[a * n + b];
      const Range& on_b = near[b * n + a];
      if (on_a.empty() || on_b.empty() || share_entry(graph, lanes[a], lanes[b]) ||
          joined(graph, lanes[a], lanes[b])) {
        continue;
      }
      const auto id = static_cast<uint32_t>(first_conflict + conflicts++);
      // Half a sample beyond the outermost points that are near.
      zones[lanes[a]].push_back({id, 0, on_a.min - 0.5 * kSample, on_a.max + 0.5 * kSample});
      zones[lanes[b]].push_back({id, 1, on_b.min - 0.5 * kSample, on_b.max + 0.5 * kSample});
    }
  }
  return conflicts;
}

// The right of way a sign on road `road` gives the traffic it faces: give way (205) and stop
// (206) lower it, priority road (306) and priority (301) raise it; nothing for other signs.
std::optional<RightOfWay> sign_right(const xodr::Road& road, bool toward_plus_s) {
  std::optional<RightOfWay> right;
  for (const xodr::Signal& signal : road.signals) {
    const bool facing = signal.orientation == "none" || signal.orientation.empty() ||
                        (signal.orientation == "+") == toward_plus_s;
    if (!facing) {
      continue;
    }
    if (signal.type == "205" || signal.type == "206") {
      right = RightOfWay::kGiveWay;
    } else if ((signal.type == "306" || signal.type == "301") && !right) {
      right = RightOfWay::kPriority;
    }
  }
  return right;
}

// The right of way a junction's <priority> elements give its connecting road `road` (an id):
// named only as `high` raises it, only as `low` lowers it; named as both (or neither), nothing.
std::optional<RightOfWay> priority_right(const xodr::Junction& junction, const std::string& road) {
  bool high = false;
  bool low = false;
  for (const xodr::JunctionPriority& priority : junction.priorities) {
    high = high || priority.high == road;
    low = low || priority.low == road;
  }
  if (high == low) {
    return std::nullopt;
  }
  return high ? RightOfWay::kPriority : RightOfWay::kGiveWay;
}

// Right of way of every lane node: from the signs on the incoming roads, else from the
// junction's <priority> elements.
std::vector<RightOfWay> rights_of(const xodr::Map& map,
                                  const std::vector<std::vector<xodr::LaneNode>>& by_road) {
  std::vector<RightOfWay> rights(map.lane_graph().size(), RightOfWay::kNormal);
  for (size_t j = 0; j < map.junction_count(); ++j) {
    const xodr::Junction& junction = map.junction(j);
    for (const xodr::Connection& connection : junction.connections) {
      const auto incoming = map.find_road(connection.incoming_road);
      const auto connecting = map.find_road(connection.connecting_road);
      if (!incoming || !connecting) {
        continue;
      }
      // Traffic toward the junction drives +s on a road whose end joins it.
      const xodr::Road& road = map.road(*incoming);
      const bool plus = road.successor.element_type == xodr::LinkElement::kJunction &&
                        road.successor.element_id == junction.id;
      auto right = sign_right(road, plus);
      if (!right && !junction.priorities.empty()) {
        right = priority_right(junction, connection.connecting_road);
      }
      if (right) {
        for (const xodr::LaneNode node : by_road[*connecting]) {
          rights[node] = *right;
        }
      }
    }
  }
  return rights;
}

}  // namespace

JunctionConflicts JunctionConflicts::build(const xodr::Map& map) {
  const auto& graph = map.lane_graph();
  // The drivable lanes of each junction's roads, and every road's lanes.
  std::vector<std::vector<xodr::LaneNode>> by_junction(map.junction_count());
  std::vector<std::vector<xodr::LaneNode>> by_road(map.road_count());
  for (xodr::LaneNode node = 0; node < graph.size(); ++node) {
    const auto& info = graph.info(node);
    by_road[info.lane.road].push_back(node);
    const xodr::Road& road = map.road(info.lane.road);
    if (!road.in_junction() || !xodr::is_drivable(info.type)) {
      continue;
    }
    if (const auto junction = map.find_junction(road.junction)) {
      by_junction[*junction].push_back(node);
    }
  }
  ZoneLists zones(graph.size());
  JunctionConflicts out;
  for (const auto& lanes : by_junction) {
    if (lanes.size() > 1) {
      out.conflicts_ += junction_conflicts(map, lanes, out.conflicts_, zones);
    }
  }
  out.first_.assign(graph.size() + 1, 0);
  for (size_t node = 0; node < graph.size(); ++node) {
    std::sort(zones[node].begin(), zones[node].end(),
              [](const ConflictZone& a, const ConflictZone& b) {
                return a.s_min < b.s_min || (a.s_min == b.s_min && a.conflict < b.conflict);
              });
    out.zones_.insert(out.zones_.end(), zones[node].begin(), zones[node].end());
    out.first_[node + 1] = static_cast<uint32_t>(out.zones_.size());
  }
  out.rights_ = rights_of(map, by_road);
  return out;
}

size_t JunctionConflicts::most_zones() const {
  size_t most = 0;
  for (size_t node = 0; node + 1 < first_.size(); ++node) {
    most = std::max<size_t>(most, first_[node + 1] - first_[node]);
  }
  return most;
}

}  // namespace corsa::engine::detail
