#include "mouth_gaps.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace corsa::test {
namespace {

constexpr double kMouthBeyond = 0.05;  // m past the lane end
constexpr double kMouthInside = 0.05;  // m inside each border
constexpr double kMouthStep = 0.025;   // m between samples across
constexpr double kMouthLimit = 0.1;    // m: longer unpaved runs are counted

/// Longest run (m) of samples on no lane across the lane's end edge moved kMouthBeyond out of it.
double uncovered(const xodr::Map& map, const xodr::LaneRef& ref, double s, bool at_start) {
  const auto span = map.lane_span_in_section(ref.road, ref.section, s, ref.lane);
  if (!span || span->width() < 2 * kMouthInside + kMouthStep) {
    return 0.0;
  }
  xodr::LocateOptions options;
  options.max_distance = 1.0;
  const xodr::WorldPose a = map.world_pose(ref.road, s, span->t_min() + kMouthInside);
  const xodr::WorldPose b = map.world_pose(ref.road, s, span->t_max() - kMouthInside);
  // Out of the lane: along the road at its end, against it at its start.
  const double out = at_start ? a.h + M_PI : a.h;
  const double dx = kMouthBeyond * std::cos(out), dy = kMouthBeyond * std::sin(out);
  const double length = std::hypot(b.x - a.x, b.y - a.y);
  const int steps = std::max(1, static_cast<int>(std::ceil(length / kMouthStep)));
  double run = 0.0, longest = 0.0;
  for (int i = 0; i <= steps; ++i) {
    const double f = static_cast<double>(i) / steps;
    const auto at = map.locate(a.x + f * (b.x - a.x) + dx, a.y + f * (b.y - a.y) + dy, options);
    if (at && at->distance <= 1e-6) {
      run = 0.0;
    } else {
      run += length / steps;
      longest = std::max(longest, run);
    }
  }
  return longest;
}

/// A lane's end edge: its borders' world points (t_min, then t_max) and its width (m).
struct MouthEndEdge {
  xodr::WorldPose a, b;
  double width = 0.0;
};

MouthEndEdge mouth_end_edge(const xodr::Map& map, const xodr::LaneRef& ref, double s) {
  MouthEndEdge e;
  if (const auto span = map.lane_span_in_section(ref.road, ref.section, s, ref.lane)) {
    e.a = map.world_pose(ref.road, s, span->t_min());
    e.b = map.world_pose(ref.road, s, span->t_max());
    e.width = span->width();
  }
  return e;
}

/// Lists (stderr) each lane end joined to this one: its width, junction, where its borders lie
/// along this end's edge (m from its t_min border) and beyond it (m, out of the lane), and the
/// heading difference of the two lanes (degrees): what tells a width step from a corner.
void describe_mouth_join(const xodr::Map& map, const xodr::LaneGraph& graph, xodr::LaneNode node,
                         bool at_start) {
  const auto& info = graph.info(node);
  const MouthEndEdge own = mouth_end_edge(map, info.lane, at_start ? info.s_start : info.s_end);
  const double ux = own.b.x - own.a.x, uy = own.b.y - own.a.y;
  const double length = std::max(1e-9, std::hypot(ux, uy));
  const double out = own.a.h + (at_start ? M_PI : 0.0);
  std::fprintf(stderr, "  own: %s w %.2f junction %s\n", map.road(info.lane.road).id.c_str(),
               own.width, map.road(info.lane.road).junction.c_str());
  for (const auto& end : graph.ends(node, at_start)) {
    const auto& other = graph.info(end.node);
    const MouthEndEdge o =
        mouth_end_edge(map, other.lane, end.at_start ? other.s_start : other.s_end);
    const auto along = [&](const xodr::WorldPose& p) {
      return ((p.x - own.a.x) * ux + (p.y - own.a.y) * uy) / length;
    };
    const auto beyond = [&](const xodr::WorldPose& p) {
      return (p.x - own.a.x) * std::cos(out) + (p.y - own.a.y) * std::sin(out);
    };
    // Lanes meeting end to start run the same way; start to start or end to end, opposite.
    const double turn =
        std::remainder(o.a.h - own.a.h + (end.at_start == at_start ? M_PI : 0.0), 2.0 * M_PI);
    std::fprintf(stderr,
                 "  -> road %s lane %d %s w %.2f junction %s: borders at %.2f / %.2f "
                 "(beyond %.2f / %.2f) of %.2f, heading diff %.1f deg\n",
                 map.road(other.lane.road).id.c_str(), other.lane.lane,
                 end.at_start ? "start" : "end", o.width,
                 map.road(other.lane.road).junction.c_str(), along(o.a), along(o.b), beyond(o.a),
                 beyond(o.b), length, turn * 180.0 / M_PI);
  }
}

}  // namespace

MouthGapFigures mouth_gaps(const xodr::Map& map,
                           const std::function<bool(const xodr::LaneRef&, bool)>& skip) {
  MouthGapFigures f;
  const xodr::LaneGraph& graph = map.lane_graph();
  const bool list = std::getenv("CORSA_MEASURE_LIST") != nullptr;
  for (xodr::LaneNode node = 0; node < graph.size(); ++node) {
    const auto& info = graph.info(node);
    for (const bool at_start : {true, false}) {
      if (graph.ends(node, at_start).empty() || skip(info.lane, at_start)) {
        continue;
      }
      const double gap = uncovered(map, info.lane, at_start ? info.s_start : info.s_end, at_start);
      ++f.ends;
      const std::string what = "road " + map.road(info.lane.road).id + " lane " +
                               std::to_string(info.lane.lane) + (at_start ? " start" : " end");
      if (gap > kMouthLimit) {
        ++f.over;
        if (list) {
          const auto p = map.world_pose(info.lane.road, at_start ? info.s_start : info.s_end, 0.0);
          std::fprintf(stderr, "mouth gap %.2f m at %s (map x %.1f y %.1f)\n", gap, what.c_str(),
                       p.x, p.y);
          if (std::getenv("CORSA_MEASURE_DETAIL")) {
            describe_mouth_join(map, graph, node, at_start);
          }
        }
      }
      if (gap > f.max) {
        f.max = gap;
        f.worst = what;
      }
    }
  }
  return f;
}

}  // namespace corsa::test
