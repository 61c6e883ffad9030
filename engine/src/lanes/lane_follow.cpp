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

namespace {

// Heading of travel (rad) in direction dir on a road of heading `road_heading` (rad).
double heading_of_travel(double road_heading, int dir) {
  return dir >= 0 ? road_heading : road_heading + std::numbers::pi;
}

}  // namespace

double travel_heading(const xodr::Map& map, uint32_t road, double s, int dir) {
  return heading_of_travel(map.reference(road, s).hdg, dir);
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
  follow.heading_offset = wrap_angle(heading - heading_of_travel(road_heading, follow.dir));
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

[[gnu::hot]] AdvanceResult advance_along_lanes(const xodr::Map& map, LaneFollow& follow,
                                               double distance, const LaneChooser* chooser) {
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
  std::optional<LaneRedirect> redirect;
  if (chooser != nullptr) {
    redirect = chooser->redirect(map, follow, ends);
  }
  if (redirect) {
    const auto own = followed_lane_center_t(map, follow, follow.lane);
    const auto via = followed_lane_center_t(map, follow, redirect->via_lane);
    if (own && via) {
      const double shift = (*own - *via) * follow.dir;
      follow.lateral += shift;
      follow.frame_shift += shift;
    } else {
      redirect.reset();
    }
  }
  const xodr::LaneEnd next = redirect
                                 ? redirect->end
                                 : ends[chooser != nullptr ? chooser->choose(map, follow, ends)
                                                           : choose_straightest(map, follow, ends)];
  const auto& next_info = map.lane_graph().info(next.node);
  follow.node = next.node;
  follow.road = next_info.lane.road;
  follow.section = next_info.lane.section;
  follow.lane = next_info.lane.lane;
  follow.dir = next.at_start ? 1 : -1;
  follow.s = next.at_start ? next_info.s_start : next_info.s_end;
}

double followed_t(const xodr::Map& map, const LaneFollow& follow) {
  const auto span = map.lane_span_in_section(follow.road, follow.section, follow.s, follow.lane);
  return (span ? span->t_center() : 0.0) + follow.dir * follow.lateral;
}

namespace {

// The world pose of t on the followed road, turned to the direction of travel.
xodr::WorldPose travel_pose(const xodr::Map& map, const LaneFollow& follow, double t) {
  xodr::WorldPose pose = map.world_pose(follow.road, follow.s, t);
  if (follow.dir < 0) {
    pose.h += std::numbers::pi;
    pose.p = -pose.p;
    pose.r = -pose.r;
  }
  pose.h = wrap_angle(pose.h + follow.heading_offset);
  return pose;
}

// The lane containing t among `spans`: borders belong to the inner lane, as Map::lane_at decides.
std::optional<int> lane_containing(const std::vector<xodr::LaneSpan>& spans, double t) {
  std::optional<int> lane_at;
  for (const auto& span : spans) {
    if (span.width() > 0.0 && t >= span.t_min() && t <= span.t_max() &&
        (!lane_at || std::abs(span.id) < std::abs(*lane_at))) {
      lane_at = span.id;
    }
  }
  return lane_at;
}

}  // namespace

LanePose lane_pose(const xodr::Map& map, const LaneFollow& follow,
                   std::vector<xodr::LaneSpan>& spans) {
  map.lane_spans_in_section(follow.road, follow.section, follow.s, spans);
  double center = 0.0;
  for (const auto& span : spans) {
    if (span.id == follow.lane) {
      center = span.t_center();
      break;
    }
  }
  LanePose out;
  out.t = center + follow.dir * follow.lateral;
  out.lane_at = lane_containing(spans, out.t);
  out.pose = travel_pose(map, follow, out.t);
  return out;
}

[[gnu::hot]] LanePose lane_pose_of(const xodr::Map& map, const LaneFollow& follow,
                                   std::vector<xodr::LaneSpan>& scratch) {
  const auto span = map.lane_span_in_section(follow.road, follow.section, follow.s, follow.lane);
  LanePose out;
  out.t = (span ? span->t_center() : 0.0) + follow.dir * follow.lateral;
  // With every outer border from widths the lanes of each side follow one another outward from
  // the lane offset without overlapping (widths below 0 count as 0), so a point strictly inside
  // one lane of positive width is in no other.
  if (span && span->width() > 0.0 && out.t > span->t_min() && out.t < span->t_max() &&
      map.section_widths_only(follow.road, follow.section)) {
    out.lane_at = follow.lane;
  } else {
    map.lane_spans_in_section(follow.road, follow.section, follow.s, scratch);
    out.lane_at = lane_containing(scratch, out.t);
  }
  out.pose = travel_pose(map, follow, out.t);
  return out;
}

}  // namespace corsa::engine::detail
