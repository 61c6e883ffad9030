#include "mouth_fills.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/xodr/map.h"
#include "reference_line.h"

namespace corsa::ngii::detail {
namespace {

constexpr double kFillMinStep = 0.05;      // m beyond the joined roads' edges: smaller steps stay
constexpr double kFillMargin = 0.02;       // m added: the fill reaches under the wider lane's edge
constexpr double kFillBeyond = 0.02;       // m beyond the lane end where the ground is looked at
constexpr double kFillProbeStart = 0.01;   // m out of the joined road's edge: the first look
constexpr double kFillProbeStep = 0.025;   // m between looks out to the lane's border
constexpr double kFillMinLaneWidth = 0.5;  // m: narrower lanes start or end beside a neighbour
constexpr double kFillMaxTurn = 10.0 * M_PI / 180.0;  // rad between the two lane ends
// m of taper per metre of step: a smoothstep's steepest slant is 1.5 step / taper, so 0.5 m
// sideways per metre forward, well inside the 2 m per metre where mesh triangles turn over
// (fitted_road_folds in road_builder.h)
constexpr double kFillTaperPerStep = 3.0;
constexpr double kFillMinTaper = 2.0;   // m
constexpr double kFillMaxShare = 0.45;  // of the road's length, per end
// A taper shorter than this (a road of a few centimetres) would divide by next to nothing.
constexpr double kFillLeastTaper = 0.01;  // m
constexpr double kFillFoldStep = 0.02;    // m between the samples of the fold check
constexpr double kFillMarkReach = 0.1;    // m beyond the border the fold check keeps clear
constexpr double kFillMaxSlant = 2.0;     // sideways metres per metre forward

/// One shoulder asked for: at a road's start or end, on its left or right, and how wide (m of
/// lateral offset t at the joint).
struct MouthFillKey {
  size_t road = 0;
  bool at_end = false;
  bool left = false;
  auto operator<=>(const MouthFillKey&) const = default;
};

struct MouthFillAsk {
  double width = 0.0;
  std::string from;  ///< the lane end whose ground it paves, "road R lane L end|start"
};

/// Lateral offset t (along the tilted surface, as lane widths are, OpenDRIVE 1.8 §8.4.2) of the
/// horizontal point (x, y) in the frame of `road` at s.
double lateral_offset_at(const xodr::Map& map, size_t road, double s, double x, double y) {
  const xodr::RefPoint ref = map.reference(road, s);
  const double t = (x - ref.x) * -std::sin(ref.hdg) + (y - ref.y) * std::cos(ref.hdg);
  return t / std::cos(map.superelevation(road, s));
}

/// Whether (x, y) lies on some lane of the map other than those of road `except` (the road the
/// shoulder would be added to lies beside it by construction; where that road widens right after
/// its end line, its lanes reach the point only there) and of road `own` (the road whose lane
/// end is looked beyond: where its end edge slants across the joined road's normal, the probe
/// from the joined road's edge runs through it, though the ground just beyond its end is open).
bool paved(const xodr::Map& map, double x, double y, size_t except, size_t own = SIZE_MAX) {
  xodr::LocateOptions options;
  options.max_distance = 1.0;
  const auto at = map.locate(x, y, options);
  return at && at->distance <= 1e-6 && at->road != except && at->road != own;
}

/// The outermost lateral offsets (right, left) of a road's lanes at s, in the section that
/// holds the lane end `end`.
std::pair<double, double> road_extent(const xodr::Map& map, const xodr::LaneGraph::NodeInfo& end,
                                      double s, std::vector<xodr::LaneSpan>& spans) {
  map.lane_spans_in_section(end.lane.road, end.lane.section, s, spans);
  if (spans.empty()) {
    return {0.0, 0.0};
  }
  return {spans.back().t_min(), spans.front().t_max()};
}

/// The nearest joined road beyond which one border of a lane end reaches: which road end and
/// side, and how far (m of that road's t) beyond its outermost border.
struct MouthFillStep {
  MouthFillKey key;
  double step = 0.0;
  double roll = 0.0;  ///< that road's superelevation there (rad)
  double heading = 0.0;
};

/// The shoulder one side of one lane end asks for, if any: the lane's border point just beyond
/// its end, against every road joined there; the ground from the nearest joined road's edge out
/// to that point is looked at (Map::locate) and the shoulder is as wide as it lies on no lane.
/// Nothing where a joined road covers the point, where the ground next to the joined road's
/// edge is paved already, or where the roads meet at a corner (a shoulder beside the next road
/// does not reach ground behind its end line).
std::optional<std::pair<MouthFillKey, double>> fill_for_side(const xodr::Map& map,
                                                             xodr::LaneNode node, bool at_start,
                                                             bool left) {
  const xodr::LaneGraph& graph = map.lane_graph();
  const auto& info = graph.info(node);
  const double s = at_start ? info.s_start : info.s_end;
  const auto span = map.lane_span_in_section(info.lane.road, info.lane.section, s, info.lane.lane);
  if (!span || span->width() < kFillMinLaneWidth) {
    return std::nullopt;
  }
  const xodr::WorldPose edge =
      map.world_pose(info.lane.road, s, left ? span->t_max() : span->t_min());
  const double out = edge.h + (at_start ? M_PI : 0.0);
  const double px = edge.x + kFillBeyond * std::cos(out);
  const double py = edge.y + kFillBeyond * std::sin(out);
  std::optional<MouthFillStep> best;
  std::vector<xodr::LaneSpan> spans;
  for (const xodr::LaneEnd& end : graph.ends(node, at_start)) {
    const auto& other = graph.info(end.node);
    const double sq = end.at_start ? other.s_start : other.s_end;
    const double heading = map.reference(other.lane.road, sq).hdg;
    const double turn =
        std::remainder(heading - edge.h + (end.at_start == at_start ? M_PI : 0.0), 2.0 * M_PI);
    if (std::abs(turn) > kFillMaxTurn) {
      return std::nullopt;
    }
    const auto [right_edge, left_edge] = road_extent(map, other, sq, spans);
    const double t = lateral_offset_at(map, other.lane.road, sq, px, py);
    if (t >= right_edge && t <= left_edge) {
      return std::nullopt;
    }
    const bool beyond_left = t > left_edge;
    const double step = beyond_left ? t - left_edge : right_edge - t;
    if (!best || step < best->step) {
      best = MouthFillStep{MouthFillKey{other.lane.road, !end.at_start, beyond_left}, step,
                           map.superelevation(other.lane.road, sq), heading};
    }
  }
  if (!best || best->step < kFillMinStep) {
    return std::nullopt;
  }
  // From the joined road's edge out to the lane's border point: the unpaved run next to the
  // edge (another road may cover the rest).
  const double horizontal = best->step * std::cos(best->roll);
  const double side = best->key.left ? 1.0 : -1.0;  // out of the joined road, along its normal
  const double nx = -std::sin(best->heading) * side, ny = std::cos(best->heading) * side;
  const double ex = px - nx * horizontal, ey = py - ny * horizontal;
  double run = 0.0;
  for (double u = kFillProbeStart; u <= horizontal + 1e-9; u += kFillProbeStep) {
    if (paved(map, ex + nx * u, ey + ny * u, best->key.road, info.lane.road)) {
      break;
    }
    run = u;
  }
  if (run < kFillMinStep) {
    return std::nullopt;
  }
  return std::make_pair(best->key, run / std::cos(best->roll));
}

/// Whether the outer border of the shoulder `lane_index` of `road` (one lane section) turns
/// over within [s0, s1]: beyond the reference line's centre of curvature, or slanting across
/// the normals more than kFillMaxSlant per metre (the check of fitted_road_folds) beyond what the
/// lane's border beside it slants: where a road is fitted along its lane's edge through a tight
/// corner, that edge itself slants more, and a shoulder narrowing gently beside it follows it.
bool fill_folds(const xodr::Road& road, size_t lane_index, double s0, double s1) {
  const auto& lanes = road.lane_sections.front().lanes;
  const bool left = lanes[lane_index].id > 0;
  const auto to_lane_edge = [&](double s) {  // outer border + this = the lane's border
    return (left ? -1.0 : 1.0) * piecewise_value(lanes[lane_index].widths, s);
  };
  const auto outer = [&](double s) {
    double t = piecewise_value(road.lane_offsets, s);
    for (const xodr::Lane& lane : lanes) {
      if (left ? lane.id > 0 : lane.id < 0) {
        t += (left ? 1.0 : -1.0) * piecewise_value(lane.widths, s);
      }
    }
    return t;
  };
  const int steps = std::max(1, static_cast<int>(std::ceil((s1 - s0) / kFillFoldStep)));
  double before = outer(s0);
  for (int j = 1; j <= steps; ++j) {
    const double a = s0 + (s1 - s0) * (j - 1) / steps;
    const double b = s0 + (s1 - s0) * j / steps;
    const double k = curvature_at(road.plan_view, a);
    const double after = outer(b);
    const double forward = 1.0 - k * (before + std::copysign(kFillMarkReach, k));
    const double most = kFillMaxSlant * forward * (b - a);
    const double lane_slant = std::abs(after + to_lane_edge(b) - before - to_lane_edge(a));
    if (forward <= 0.0 || std::abs(after - before) > most + lane_slant) {
      return true;
    }
    before = after;
  }
  return false;
}

/// Width records of a shoulder `start` wide at s = 0 and `end` wide at the road's end (either
/// may be 0), each narrowing to zero along a smoothstep over its taper; the tapers' lengths.
struct MouthFillWidths {
  std::vector<xodr::Poly3> widths;
  double taper_start = 0.0;
  double taper_end = 0.0;
};

MouthFillWidths fill_widths(double start, double end, double length) {
  const auto taper = [&](double w) {
    return w > 0.0
               ? std::min(std::max(kFillMinTaper, kFillTaperPerStep * w), kFillMaxShare * length)
               : 0.0;
  };
  MouthFillWidths out;
  out.taper_start = taper(start);
  out.taper_end = taper(end);
  if (start > 0.0) {
    const double l = out.taper_start;
    // w(ds) = start (1 - 3 x^2 + 2 x^3), x = ds / l
    out.widths.push_back(
        xodr::Poly3{0.0, start, 0.0, -3.0 * start / (l * l), 2.0 * start / (l * l * l)});
  }
  out.widths.push_back(xodr::Poly3{out.taper_start, 0.0, 0.0, 0.0, 0.0});
  if (end > 0.0) {
    const double l = out.taper_end;
    // w(ds) = end (3 x^2 - 2 x^3), x = ds / l from the taper's start
    out.widths.push_back(
        xodr::Poly3{length - l, 0.0, 0.0, 3.0 * end / (l * l), -2.0 * end / (l * l * l)});
  }
  return out;
}

/// Adds one road's shoulder on one side; false (and nothing added) where it would fold, where a
/// sidewalk is that side's edge, or where the road is too short for a taper.
bool add_fill(xodr::Road& road, bool left, const MouthFillAsk* start, const MouthFillAsk* end) {
  auto& lanes = road.lane_sections.front().lanes;
  if (!lanes.empty() && (left ? lanes.front() : lanes.back()).type == xodr::LaneType::kSidewalk) {
    return false;  // the sidewalk is the road's edge there
  }
  const MouthFillWidths w =
      fill_widths(start ? start->width : 0.0, end ? end->width : 0.0, road.length);
  if ((start && w.taper_start < kFillLeastTaper) || (end && w.taper_end < kFillLeastTaper)) {
    return false;
  }
  xodr::Lane lane;
  lane.type = xodr::LaneType::kShoulder;
  lane.type_name = "shoulder";
  lane.widths = w.widths;
  for (const MouthFillAsk* ask : {start, end}) {
    if (ask) {
      lane.user_data.push_back(xodr::UserData{"ngii:mouth-fill", ask->from});
    }
  }
  size_t index = 0;
  if (left) {
    lane.id = lanes.empty() ? 1 : std::max(lanes.front().id, 0) + 1;
    lanes.insert(lanes.begin(), std::move(lane));
  } else {
    lane.id = lanes.empty() ? -1 : std::min(lanes.back().id, 0) - 1;
    lanes.push_back(std::move(lane));
    index = lanes.size() - 1;
  }
  if ((start && fill_folds(road, index, 0.0, w.taper_start)) ||
      (end && fill_folds(road, index, road.length - w.taper_end, road.length))) {
    lanes.erase(lanes.begin() + static_cast<std::ptrdiff_t>(index));
    return false;
  }
  return true;
}

}  // namespace

size_t fill_lane_mouths(xodr::MapData& map) {
  std::map<MouthFillKey, MouthFillAsk> asks;
  {
    Diagnostics scratch;  // the written map is checked on its own; nothing to report here
    const xodr::Map built = xodr::Map::build(map, scratch);
    const xodr::LaneGraph& graph = built.lane_graph();
    for (xodr::LaneNode node = 0; node < graph.size(); ++node) {
      const auto& info = graph.info(node);
      if (info.type != xodr::LaneType::kDriving) {
        continue;
      }
      for (const bool at_start : {true, false}) {
        for (const bool left : {false, true}) {
          const auto fill = fill_for_side(built, node, at_start, left);
          if (!fill) {
            continue;
          }
          MouthFillAsk& ask = asks[fill->first];
          const double width = fill->second + kFillMargin;
          if (width > ask.width) {
            ask.width = width;
            ask.from = "road " + built.road(info.lane.road).id + " lane " +
                       std::to_string(info.lane.lane) + (at_start ? " start" : " end");
          }
        }
      }
    }
  }
  size_t added = 0;
  for (size_t r = 0; r < map.roads.size(); ++r) {
    xodr::Road& road = map.roads[r];
    if (road.lane_sections.size() != 1) {
      continue;
    }
    for (const bool left : {false, true}) {
      const auto start = asks.find(MouthFillKey{r, false, left});
      const auto end = asks.find(MouthFillKey{r, true, left});
      if (start == asks.end() && end == asks.end()) {
        continue;
      }
      added += add_fill(road, left, start == asks.end() ? nullptr : &start->second,
                        end == asks.end() ? nullptr : &end->second);
    }
  }
  return added;
}

}  // namespace corsa::ngii::detail
