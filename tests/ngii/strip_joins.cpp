#include "strip_joins.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace corsa::test {
namespace {

constexpr double kTouch = 0.3;  // m between inner edges

struct StripEnd {
  xodr::LaneNode node = xodr::kNoLane;
  bool at_start = true;
  double x = 0.0, y = 0.0;
  double outer_x = 0.0, outer_y = 0.0;  ///< the strip's outer edge (towards the centre mark)
  double heading = 0.0;  ///< of the reference line, pointing out of the lane at this end
  std::string name;
};

bool is_strip(const xodr::Lane& lane) {
  return lane.type == xodr::LaneType::kRestricted &&
         std::any_of(lane.user_data.begin(), lane.user_data.end(),
                     [](const auto& d) { return d.code == "ngii:centre-strip"; });
}

std::vector<StripEnd> strip_ends_of(const xodr::Map& map) {
  std::vector<StripEnd> out;
  const xodr::LaneGraph& graph = map.lane_graph();
  for (xodr::LaneNode node = 0; node < graph.size(); ++node) {
    const auto& info = graph.info(node);
    const xodr::Lane* lane = map.lane(info.lane);
    if (lane == nullptr || !is_strip(*lane)) {
      continue;
    }
    for (const bool at_start : {true, false}) {
      const double s = at_start ? info.s_start : info.s_end;
      const auto span = map.lane_span_in_section(info.lane.road, info.lane.section, s, lane->id);
      if (!span) {
        continue;
      }
      const xodr::WorldPose p = map.world_pose(info.lane.road, s, span->t_inner);
      const xodr::WorldPose q = map.world_pose(info.lane.road, s, span->t_outer);
      StripEnd end{node, at_start, p.x, p.y, q.x, q.y, at_start ? p.h + M_PI : p.h, ""};
      end.name = map.road(info.lane.road).id + ":" + std::to_string(lane->id) +
                 (at_start ? " start" : " end");
      out.push_back(std::move(end));
    }
  }
  return out;
}

}  // namespace

StripJoinFigures strip_joins(const xodr::Map& map) {
  const std::vector<StripEnd> ends = strip_ends_of(map);
  const xodr::LaneGraph& graph = map.lane_graph();
  StripJoinFigures f;
  f.strip_ends = ends.size();
  for (size_t i = 0; i < ends.size(); ++i) {
    for (size_t j = i + 1; j < ends.size(); ++j) {
      const StripEnd& a = ends[i];
      const StripEnd& b = ends[j];
      // One strip's end at the other's start (both are lane +1, left of their reference
      // lines: only roads running the same way put them side by side), pointing out of their
      // lanes in opposite directions.
      if (a.node == b.node || a.at_start == b.at_start ||
          std::hypot(a.x - b.x, a.y - b.y) > kTouch || std::cos(a.heading - b.heading) > -0.5) {
        continue;
      }
      ++f.touching;
      const auto joins = graph.ends(a.node, a.at_start);
      const bool joined = std::any_of(joins.begin(), joins.end(), [&](const xodr::LaneEnd& e) {
        return e.node == b.node && e.at_start == b.at_start;
      });
      f.joined += joined;
      const double outer = std::hypot(a.outer_x - b.outer_x, a.outer_y - b.outer_y);
      if (joined && outer > f.outer_gap_max) {
        f.outer_gap_max = outer;
        f.outer_worst = a.name + " -> " + b.name;
      }
      if (!joined && f.unjoined.empty()) {
        f.unjoined = a.name + " -> " + b.name;
      }
    }
  }
  return f;
}

}  // namespace corsa::test
