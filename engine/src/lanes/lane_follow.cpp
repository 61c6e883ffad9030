#include "lanes/lane_follow.h"

#include <cmath>
#include <numbers>

#include "geometry/angle.h"

namespace corsa::engine::detail {

int step_lane_id(int lane, int delta) {
  while (delta > 0) {
    lane = lane == -1 ? 1 : lane + 1;
    --delta;
  }
  while (delta < 0) {
    lane = lane == 1 ? -1 : lane - 1;
    ++delta;
  }
  return lane;
}

double travel_heading(const xodr::Map& map, uint32_t road, double s, int dir) {
  const double h = map.reference(road, s).hdg;
  return dir >= 0 ? h : h + std::numbers::pi;
}

std::optional<double> lane_center_t(const xodr::Map& map, uint32_t road, double s, int lane) {
  const auto span = map.lane_span(road, s, lane);
  return span ? std::optional<double>(span->t_center()) : std::nullopt;
}

std::optional<double> followed_lane_center_t(const xodr::Map& map, const LaneFollow& follow,
                                             int lane) {
  const auto span = map.lane_span_in_section(follow.road, follow.section, follow.s, lane);
  return span ? std::optional<double>(span->t_center()) : std::nullopt;
}

bool attach_to_lane(const xodr::Map& map, LaneFollow& follow, uint32_t road, double s, double t,
                    int lane, double heading) {
  const auto center = lane_center_t(map, road, s, lane);
  if (!center) {
    return false;
  }
  const auto section = static_cast<uint32_t>(map.section_index(road, s));
  const auto node = map.lane_graph().find(xodr::LaneRef{road, section, lane});
  if (!node) {
    return false;
  }
  follow.on_road = true;
  follow.road = road;
  follow.section = section;
  follow.lane = lane;
  follow.node = *node;
  follow.s = s;
  const double road_heading = map.reference(road, s).hdg;
  follow.dir = std::cos(heading - road_heading) >= 0.0 ? 1 : -1;
  follow.lateral = (t - *center) * follow.dir;
  follow.heading_offset = wrap_angle(heading - travel_heading(map, road, s, follow.dir));
  return true;
}

namespace {

bool enters_in_travel_direction(const xodr::LaneGraph::NodeInfo& info, bool at_start) {
  switch (info.direction) {
    case xodr::TravelDirection::kForward:
      return at_start;
    case xodr::TravelDirection::kBackward:
      return !at_start;
    case xodr::TravelDirection::kBoth:
      return true;
  }
  return true;
}

// Heading of travel where a candidate lane is left again (its far end).
double exit_heading(const xodr::Map& map, const xodr::LaneEnd& end) {
  const auto& info = map.lane_graph().info(end.node);
  return end.at_start ? travel_heading(map, info.lane.road, info.s_end, 1)
                      : travel_heading(map, info.lane.road, info.s_start, -1);
}

}  // namespace

size_t choose_straightest(const xodr::Map& map, const LaneFollow& lane,
                          std::span<const xodr::LaneEnd> candidates) {
  const auto& graph = map.lane_graph();
  const double heading = travel_heading(map, lane.road, lane.s, lane.dir);
  size_t best = 0;
  int best_rank = -1;
  double best_turn = 0.0;
  for (size_t i = 0; i < candidates.size(); ++i) {
    const auto& info = graph.info(candidates[i].node);
    const int rank = (xodr::is_drivable(info.type) ? 2 : 0) +
                     (enters_in_travel_direction(info, candidates[i].at_start) ? 1 : 0);
    const double turn = std::abs(wrap_angle(exit_heading(map, candidates[i]) - heading));
    if (rank > best_rank || (rank == best_rank && turn < best_turn - 1e-9)) {
      best = i;
      best_rank = rank;
      best_turn = turn;
    }
  }
  return best;
}

AdvanceResult advance_along_lanes(const xodr::Map& map, LaneFollow& follow, double distance,
                                  const LaneChooser* chooser) {
  AdvanceResult result;
  if (distance < 0.0) {
    // Backwards: drive the other way round, then turn back.
    follow.dir = -follow.dir;
    follow.lateral = -follow.lateral;
    result = advance_along_lanes(map, follow, -distance, chooser);
    follow.dir = -follow.dir;
    follow.lateral = -follow.lateral;
    result.travelled = -result.travelled;
    return result;
  }
  const auto& graph = map.lane_graph();
  double remaining = distance;
  // A bounded number of lane ends per step: zero-length lanes must not loop forever.
  for (int hops = 0; hops < 64; ++hops) {
    const auto& info = graph.info(follow.node);
    const double boundary = follow.dir > 0 ? info.s_end : info.s_start;
    const double room = std::abs(boundary - follow.s);
    if (remaining <= room) {
      follow.s += follow.dir * remaining;
      result.travelled += remaining;
      return result;
    }
    follow.s = boundary;
    result.travelled += room;
    remaining -= room;
    const auto ends = graph.ends(follow.node, follow.dir < 0);
    if (ends.empty()) {
      result.hit_end = true;
      return result;
    }
    const uint32_t road_before = follow.road;
    enter_next_lane(map, follow, ends, chooser);
    if (follow.road != road_before) {
      result.changed_road = true;
    }
  }
  result.hit_end = true;
  return result;
}

void enter_next_lane(const xodr::Map& map, LaneFollow& follow, std::span<const xodr::LaneEnd> ends,
                     const LaneChooser* chooser) {
  const size_t pick = chooser != nullptr ? chooser->choose(map, follow, ends)
                                         : choose_straightest(map, follow, ends);
  const xodr::LaneEnd next = ends[pick];
  const auto& next_info = map.lane_graph().info(next.node);
  follow.node = next.node;
  follow.road = next_info.lane.road;
  follow.section = next_info.lane.section;
  follow.lane = next_info.lane.lane;
  follow.dir = next.at_start ? 1 : -1;
  follow.s = next.at_start ? next_info.s_start : next_info.s_end;
}

double followed_t(const xodr::Map& map, const LaneFollow& follow,
                  std::vector<xodr::LaneSpan>& spans) {
  map.lane_spans_in_section(follow.road, follow.section, follow.s, spans);
  double center = 0.0;
  for (const auto& span : spans) {
    if (span.id == follow.lane) {
      center = span.t_center();
      break;
    }
  }
  return center + follow.dir * follow.lateral;
}

LanePose lane_pose(const xodr::Map& map, const LaneFollow& follow,
                   std::vector<xodr::LaneSpan>& spans) {
  LanePose out;
  out.t = followed_t(map, follow, spans);
  // The lane containing t: borders belong to the inner lane, as Map::lane_at decides.
  for (const auto& span : spans) {
    if (span.width() > 0.0 && out.t >= span.t_min() && out.t <= span.t_max() &&
        (!out.lane_at || std::abs(span.id) < std::abs(*out.lane_at))) {
      out.lane_at = span.id;
    }
  }
  out.pose = map.world_pose(follow.road, follow.s, out.t);
  if (follow.dir < 0) {
    out.pose.h += std::numbers::pi;
    out.pose.p = -out.pose.p;
    out.pose.r = -out.pose.r;
  }
  out.pose.h = wrap_angle(out.pose.h + follow.heading_offset);
  return out;
}

}  // namespace corsa::engine::detail
