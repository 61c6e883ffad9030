// Road geometry from lane centre lines (see road_builder.h).
//
// Lane layout: every converted road carries its lanes on the right of the reference line
// (ids -1..-n, OpenDRIVE 1.8 §9.1), since NGII links are one-way; the reference line follows the
// left edge of the reference lane (the leftmost lane that starts and ends beside the others; a
// lane splitting off on the left sits left of it, the laneOffset making room for it); a
// one-lane road turning right whose lane would fold on the inside of the turn follows its
// lane's right edge instead, the lane left of it (road_reference.h). The steps:
// 1. lane lines (road_stations.h): each lane's surveyed polyline, smoothed, and extended by a
//    few metres of the lanes before and after it (for stations beyond its own ends);
// 2. reference polyline (road_reference.h), fitted with lines, arcs and clothoids;
// 3. stations along it (road_stations.h: every metre and at the lanes' vertices), where each
//    lane's crossing of the normal gives its lateral offset, height and direction;
// 4. lateral profile: per station a plane through the lanes' heights gives the elevation at the
//    reference line and the superelevation (roll), both fitted as cubics;
// 5. lane borders per station (border_solver.h) from the measured centres and widths, turned
//    into the tilted road's t (divided by cos roll), fitted as laneOffset and width cubics.

#include "road_builder.h"

#include <algorithm>
#include <cmath>

#include "border_solver.h"
#include "corsa/ngii/curve_fit.h"
#include "lane_tracker.h"
#include "lateral_profile.h"
#include "polyline.h"
#include "reference_line.h"
#include "road_reference.h"
#include "road_stations.h"

namespace corsa::ngii::detail {
namespace {

/// How often a reference line is eased and refitted where its records fold the road's edge.
constexpr int kFoldRefits = 8;
/// m: the least width a lane is narrowed to on the inside of a tight turn (border_solver.h).
constexpr double kNarrowestInTurn = 1.5;
/// m of width per metre of s over which a lane narrowed on the inside of a turn is eased in
/// and out: narrowed at one station only, its borders would slant across the road at the
/// turn's end (a lane narrowing by 2.5 m within 0.5 m), and the mesh folds over there anyway.
constexpr double kNarrowingEase = 1.0;
/// Where a lane not held to its link (splitting off or merging inside its neighbour) takes its
/// link's heights across the road: this share of the way from the link to the lane's centre.
/// At the lane's centre (1) the surface under the link of a Sangam lane merging inside its
/// neighbour was 5.0 cm off its survey (p95); at the link (0) the lane's centre was 6.3 cm off
/// its link (K-City's A219BS010114 on a 4-7 % crossfall); at 2/3, 3.2 cm, and no vertex of
/// either area more than 4.9 cm off the surface under it.
constexpr double kMergeHeightShare = 2.0 / 3.0;

/// The leftmost lane that starts and ends beside the others (else the leftmost lane).
size_t reference_lane(const RoadPlan& plan) {
  for (size_t k = 0; k < plan.lanes.size(); ++k) {
    if (effective_end(plan, k, true) == LaneEnd::kBeside &&
        effective_end(plan, k, false) == LaneEnd::kBeside) {
      return k;
    }
  }
  return 0;
}

/// The polyline the plan view is fitted to (road_reference.h).
ReferencePolyline reference_polyline(const RoadPlan& plan, const LaneLines& lines,
                                     const std::vector<WidthProfile>& widths,
                                     const RoadEndLines& ends, size_t ref, bool lanes_left) {
  const Polyline& line = lines.smooth[ref];
  // Widths are profiles along the surveyed line; the smoothed one is a little shorter.
  const double scale = line.length() > 0.0 ? lines.raw[ref].length() / line.length() : 1.0;
  // Half the lane's width, averaged over +-kShiftWindow metres: where the marks make the width
  // change quickly, shifting by it would jog the reference line sideways (an S-turn of a few
  // metres that lanes outside it fold over); the laneOffset takes up the difference.
  constexpr double kShiftWindow = 15.0;
  std::vector<double> half(line.size());
  for (size_t i = 0; i < line.size(); ++i) {
    const double u = line.u()[i] * scale;
    double sum = 0.0;
    int count = 0;
    for (double d = -kShiftWindow; d <= kShiftWindow; d += 1.0) {
      sum += widths[ref].at(u + d);
      ++count;
    }
    half[i] = 0.5 * sum / count;
  }
  // Along the right edge: the lane lies left of the line (the laneOffset carries it there).
  if (lanes_left) {
    for (double& h : half) {
      h = -h;
    }
  }
  double road_width = 0.0;
  // How far the road's edges may lie from the reference lane's centre (the anchor) at each end,
  // for an end that turns short of its line to run on past it (align_ends). Not on junction
  // paths: their lines are chosen by how far their lanes' ends move off their links (0.1 m at
  // most, build_joined), which such an overrun would use up.
  EndSpans spans{-0.5 * widths[ref].front(), -0.5 * widths[ref].back()};
  std::vector<double> width_at(line.size(), 0.0);
  for (size_t k = 0; k < plan.lanes.size(); ++k) {
    road_width += widths[k].at(0.0);
    spans.start += widths[k].front();
    spans.end += widths[k].back();
    for (size_t i = 0; i < line.size(); ++i) {
      width_at[i] += widths[k].at(line.u()[i] * scale);
    }
  }
  if (plan.junction >= 0) {
    spans = EndSpans{};
  }
  ReferencePolyline shifted = shifted_left(line, half);
  relax_right_turns(shifted.points, width_at, lanes_left);
  // On a line shared with the roads beyond, the road ends on that line (where the reference
  // lane crosses it); else on its parallel through the reference lane's own end.
  const auto anchor = [](Vec2 own, const std::optional<EndLine>& on, bool shared) {
    return shared && on ? on->point + dot(own - on->point, on->across) * on->across : own;
  };
  ReferencePolyline aligned = align_ends(
      std::move(shifted), ends.start, ends.end,
      anchor(xy(lines.raw[ref].points().front()), ends.start, ends.start_shared),
      anchor(xy(lines.raw[ref].points().back()), ends.end, ends.end_shared), road_width, spans);
  aligned.widest = *std::max_element(width_at.begin(), width_at.end());
  aligned.lanes_left = lanes_left;
  return aligned;
}

/// Width target of lane k at station i: its measured width, widened to what it spans along the
/// reference normal when the lane crosses that normal at an angle (road ends turned square to a
/// skewed stop line).
double width_target(const Stations& st, const LaneLines& lines,
                    const std::vector<WidthProfile>& widths, size_t k, size_t i) {
  const Crossing& c = st.crossings[k][i];
  const double scale =
      lines.smooth[k].length() > 0.0 ? lines.raw[k].length() / lines.smooth[k].length() : 1.0;
  const double w = widths[k].at(c.u * scale);
  const Vec2 tangent{std::cos(st.ref[i].hdg), std::sin(st.ref[i].hdg)};
  const double along = std::max(0.6, std::abs(dot(tangent, c.direction)));
  return w / along;
}

/// Lane borders (horizontal t) at every station, and whether each lane is centred on its link
/// there.
struct Borders {
  std::vector<std::vector<double>> t;      ///< [station][border]
  std::vector<std::vector<bool>> centred;  ///< [station][lane]
};

Borders station_borders(const RoadPlan& plan, const Stations& st, const LaneLines& lines,
                        const std::vector<WidthProfile>& widths, size_t ref) {
  const size_t lanes = plan.lanes.size();
  Borders borders;
  borders.t.resize(st.s.size());
  borders.centred.resize(st.s.size());
  const size_t n = st.s.size();
  std::vector<std::vector<LaneTarget>> all_targets(n, std::vector<LaneTarget>(lanes));
  // How much narrow_inside_of_turn took off each lane's width at each station.
  std::vector<std::vector<double>> narrowed(n, std::vector<double>(lanes, 0.0));
  for (size_t i = 0; i < n; ++i) {
    std::vector<LaneTarget>& targets = all_targets[i];
    for (size_t k = 0; k < lanes; ++k) {
      targets[k] = {st.crossings[k][i].t, width_target(st, lines, widths, k, i), true};
    }
    // A lane splitting off (merging into) a neighbour, while its link still runs inside that
    // neighbour: between two lanes it fills the room between them; at the road's edge its
    // width grows with the distance between the two links, from 0 where they share their node
    // to its full width where the lanes lie side by side.
    for (size_t k = 0; k < lanes; ++k) {
      const bool first_half = st.crossings[k][i].u < 0.5 * lines.smooth[k].length();
      const LaneEnd shape = effective_end(plan, k, first_half);
      if (shape == LaneEnd::kBeside) {
        continue;
      }
      const size_t j = shape == LaneEnd::kFromLeft ? k - 1 : k + 1;
      const double apart = std::abs(targets[j].centre - targets[k].centre);
      const double full = 0.5 * (targets[j].width + targets[k].width);
      if (apart >= full) {
        continue;
      }
      targets[k].centred = false;
      if (k > 0 && k + 1 < lanes) {
        const LaneTarget& left = targets[k - 1];
        const LaneTarget& right = targets[k + 1];
        targets[k].width =
            std::max(0.0, left.centre - 0.5 * left.width - (right.centre + 0.5 * right.width));
      } else {
        targets[k].width *= apart / full;
      }
    }
    std::vector<double> before(lanes);
    for (size_t k = 0; k < lanes; ++k) {
      before[k] = targets[k].width;
    }
    narrow_inside_of_turn(targets, st.curvature[i], kFoldClearance, kNarrowestInTurn);
    for (size_t k = 0; k < lanes; ++k) {
      narrowed[i][k] = before[k] - targets[k].width;
    }
  }
  // Each station narrows a lane by at least what a station within reach narrows it, less
  // kNarrowingEase per metre between them (a forward and a backward sweep).
  for (size_t k = 0; k < lanes; ++k) {
    std::vector<double> eased(n);
    for (size_t i = 0; i < n; ++i) {
      eased[i] = narrowed[i][k];
      if (i > 0) {
        eased[i] = std::max(eased[i], eased[i - 1] - kNarrowingEase * (st.s[i] - st.s[i - 1]));
      }
    }
    for (size_t i = n; i-- > 1;) {
      eased[i - 1] = std::max(eased[i - 1], eased[i] - kNarrowingEase * (st.s[i] - st.s[i - 1]));
    }
    for (size_t i = 0; i < n; ++i) {
      LaneTarget& target = all_targets[i][k];
      const double extra = eased[i] - narrowed[i][k];
      if (target.centred && extra > 0.0 && target.width > kNarrowestInTurn) {
        target.width = std::max(target.width - extra, kNarrowestInTurn);
      }
    }
  }
  for (size_t i = 0; i < n; ++i) {
    borders.t[i] = solve_borders(all_targets[i], ref);
    for (const LaneTarget& target : all_targets[i]) {
      borders.centred[i].push_back(target.centred);
    }
  }
  return borders;
}

/// 1 at x = 0 easing to 0 at x = 1 with zero slope at both (a smoothstep), 0 beyond.
double end_border_ease(double x) {
  if (x >= 1.0) {
    return 0.0;
  }
  const double y = std::max(0.0, x);
  return 1.0 - y * y * (3.0 - 2.0 * y);
}

/// Moves the borders at the road's first and last station onto `targets` (EndBorders) and
/// eases the move out over the stations within reach of that end: the laneOffset and widths
/// fitted to them then meet the joined lanes' borders at the end with zero slope there.
void meet_end_borders(const Stations& st, const EndBorders& targets, Borders& borders) {
  constexpr double kMinMove = 0.01;  // m: smaller moves are left alone
  const size_t n = st.s.size();
  if (n < 2) {
    return;
  }
  const double length = st.s.back();
  for (const bool at_end : {false, true}) {
    const std::vector<std::optional<Vec2>>& points = at_end ? targets.end : targets.start;
    const size_t i0 = at_end ? n - 1 : 0;
    if (points.size() != borders.t[i0].size()) {
      continue;
    }
    const RefSample& ref = st.ref[i0];
    const Vec2 origin{ref.x, ref.y};
    const Vec2 normal{-std::sin(ref.hdg), std::cos(ref.hdg)};
    std::vector<double> move(points.size(), 0.0);
    double largest = 0.0;
    for (size_t b = 0; b < points.size(); ++b) {
      if (points[b]) {
        move[b] = dot(*points[b] - origin, normal) - borders.t[i0][b];
        largest = std::max(largest, std::abs(move[b]));
      }
    }
    if (largest < kMinMove) {
      continue;
    }
    const double ramp = end_border_ramp(largest, length);
    for (size_t i = 0; i < n; ++i) {
      const double f = end_border_ease((at_end ? length - st.s[i] : st.s[i]) / ramp);
      if (f == 0.0) {
        continue;
      }
      std::vector<double>& t = borders.t[i];
      for (size_t b = 0; b < t.size(); ++b) {
        t[b] += f * move[b];
        if (b > 0) {
          t[b] = std::min(t[b], t[b - 1]);  // no lane narrower than nothing
        }
      }
    }
  }
}

xodr::LaneType lane_type_of(const Network& network, int link) {
  return network.source(link).link_type == "4" ? xodr::LaneType::kBus : xodr::LaneType::kDriving;
}

/// Lifts each width record whose value at its start or end dips below zero (a fit within its
/// tolerance of a lane that widens from, or narrows to, nothing) by a linear term that brings
/// that end to 0 m: a lane has no negative width (OpenDRIVE 1.8 §9.5.2). Records stay
/// continuous, since a shared end is lifted alike on both sides.
void lift_negative_ends(std::vector<xodr::Poly3>& widths, double road_end) {
  for (size_t i = 0; i < widths.size(); ++i) {
    xodr::Poly3& w = widths[i];
    const double end = i + 1 < widths.size() ? widths[i + 1].s : road_end;
    const double length = end - w.s;
    const double lift_start = std::max(0.0, -w.a);
    const double lift_end = std::max(0.0, -w.value(end));
    if (lift_start == 0.0 && lift_end == 0.0) {
      continue;
    }
    w.a += lift_start;
    if (length > 0.0) {
      w.b += (lift_end - lift_start) / length;
    }
  }
}

/// laneOffset and lane widths from the borders (already in the road's tilted t), fitted one
/// after the other, each against what the previous fitted borders left (so errors do not add
/// up across lanes). Records the lane centre errors in `built`.
void fit_lanes(BuiltRoad& built, const RoadPlan& plan, const Network& network, const Stations& st,
               const LaneLines& lines, const Borders& borders, const std::vector<double>& roll,
               const ConvertOptions& options) {
  xodr::Road& road = built.road;
  const size_t n = st.s.size();
  std::vector<ProfileSample> samples(n);
  double offset_size = 0.0;
  for (size_t i = 0; i < n; ++i) {
    samples[i] = {st.s[i], borders.t[i][0]};
    offset_size = std::max(offset_size, std::abs(borders.t[i][0]));
  }
  std::vector<double> inner(n, 0.0);
  if (offset_size > 0.005) {
    road.lane_offsets = fit_profile(samples, options.width_tolerance).pieces;
    for (size_t i = 0; i < n; ++i) {
      inner[i] = piecewise_value(road.lane_offsets, st.s[i]);
    }
  }
  xodr::LaneSection section;
  xodr::Lane centre;
  centre.type = xodr::LaneType::kNone;
  centre.type_name = "none";
  section.lanes.push_back(centre);
  for (size_t k = 0; k < plan.lanes.size(); ++k) {
    for (size_t i = 0; i < n; ++i) {
      samples[i] = {st.s[i], std::max(0.0, inner[i] - borders.t[i][k + 1])};
    }
    xodr::Lane lane;
    lane.id = -static_cast<int>(k) - 1;
    lane.type = lane_type_of(network, plan.lanes[k].links.front());
    lane.type_name = lane.type == xodr::LaneType::kBus ? "bus" : "driving";
    lane.widths = fit_profile(samples, options.width_tolerance).pieces;
    lift_negative_ends(lane.widths, st.s.back());
    for (size_t i = 0; i < n; ++i) {
      const double w = piecewise_value(lane.widths, st.s[i]);
      // Back to horizontal offsets for the error measurements.
      const double centre_t = (inner[i] - 0.5 * w) * std::cos(roll[i]);
      inner[i] -= w;
      const RefSample& ref = st.ref[i];
      const Vec2 point{ref.x - centre_t * std::sin(ref.hdg), ref.y + centre_t * std::cos(ref.hdg)};
      if ((i == 0 || i + 1 == n) && borders.centred[i][k]) {
        const auto& surveyed = lines.raw[k].points();
        const Vec2 end = xy(i == 0 ? surveyed.front() : surveyed.back());
        built.end_error = std::max(built.end_error, norm(point - end));
      }
      if (!borders.centred[i][k] || !own_part(st, lines, k, i, 0.0)) {
        continue;
      }
      // Near where the station crosses the lane (long lanes loop back on themselves).
      const double u = st.crossings[k][i].u;
      const Projection nearest = lines.raw[k].project_within(point, u - 5.0, u + 5.0);
      const Projection smooth = lines.smooth[k].project_within(point, u - 5.0, u + 5.0);
      if (nearest.along == 0.0 && smooth.along == 0.0) {
        built.source_error = std::max(built.source_error, nearest.distance);
        built.lane_error = std::max(built.lane_error, smooth.distance);
      }
    }
    section.lanes.push_back(std::move(lane));
  }
  road.lane_sections.push_back(std::move(section));
}

/// Source links along each lane (road s ranges) and the lanes' speed limits (MaxSpeed km/h ->
/// m/s; 0 = missing). Link starts are arc lengths on the surveyed line: moved onto the smoothed
/// one first.
void add_spans(BuiltRoad& built, const RoadPlan& plan, const Network& network, const Stations& st,
               const LaneLines& lines) {
  xodr::Road& road = built.road;
  built.spans.resize(plan.lanes.size());
  std::vector<double> u_at(st.s.size());
  for (size_t k = 0; k < plan.lanes.size(); ++k) {
    for (size_t i = 0; i < st.s.size(); ++i) {
      u_at[i] = st.crossings[k][i].u;
    }
    xodr::Lane& lane = road.lane_sections.front().lanes[k + 1];
    const PlanLane& source = plan.lanes[k];
    const double scale =
        lines.raw[k].length() > 0.0 ? lines.smooth[k].length() / lines.raw[k].length() : 1.0;
    for (size_t j = 0; j < source.links.size(); ++j) {
      BuiltRoad::Span span;
      span.link = source.links[j];
      const double guess = source.link_starts[j] * scale;
      const double start_u = j == 0
                                 ? 0.0
                                 : lines.smooth[k]
                                       .project_within(xy(lines.raw[k].at(source.link_starts[j])),
                                                       guess - 5.0, guess + 5.0)
                                       .u;
      span.s_start = j == 0 ? 0.0 : s_at_u(st.s, u_at, start_u);
      span.s_end = road.length;
      if (j > 0) {
        built.spans[k].back().s_end = span.s_start;
      }
      built.spans[k].push_back(span);
      const int speed = network.source(span.link).max_speed;
      if (speed > 0 && (lane.speeds.empty() || lane.speeds.back().max_speed != speed / 3.6)) {
        lane.speeds.push_back(xodr::LaneSpeed{span.s_start, speed / 3.6});
      }
    }
  }
}

/// Whether a lane border lies beyond the reference line's centre of curvature at a station
/// (the mesh folds over there).
bool folds_at_stations(const Stations& st, const Borders& borders) {
  for (size_t i = 0; i < st.s.size(); ++i) {
    const double k = st.curvature[i];
    for (double b : borders.t[i]) {
      if (k * b >= 1.0) {
        return true;
      }
    }
  }
  return false;
}

/// The road along the reference lane's left edge (`lanes_left`: its right edge).
BuiltRoad build_road_along(const RoadPlan& plan, const Network& network, const LaneLines& lines,
                           const std::vector<WidthProfile>& widths, const RoadEndLines& ends,
                           const EndBorders& end_borders, const ConvertOptions& options,
                           bool lanes_left) {
  BuiltRoad built;
  const size_t ref = reference_lane(plan);
  CurveFitOptions fit_options;
  fit_options.tolerance = options.tolerance;
  ReferencePolyline reference = reference_polyline(plan, lines, widths, ends, ref, lanes_left);
  fit_options.start_heading = reference.start_heading;
  fit_options.end_heading = reference.end_heading;
  CurveFit fit = fit_plan_view(reference.points, fit_options);
  // Records that turn right more tightly than the road is wide fold its right edge over. They
  // follow survey jogs of a few centimetres within a metre (a short record must meet the data
  // heading at its end: an S of curvature -0.5 and back), which the lanes' offsets follow anyway
  // (they are measured from whatever line is fitted): the polyline is eased there and refitted.
  const double tightest = 1.0 / (reference.widest + kFoldClearance);
  for (int round = 0; round < kFoldRefits; ++round) {
    const std::vector<double> tight = tight_right_turns(fit, tightest, reference.lanes_left);
    if (tight.empty()) {
      break;
    }
    ease_near(reference.points, tight);
    fit = fit_plan_view(reference.points, fit_options);
  }
  built.reference_error = fit.max_error;
  built.kinks = fit.kinks;
  xodr::Road& road = built.road;
  road.length = fit.length;
  road.plan_view = std::move(fit.geometries);
  road.types.push_back(xodr::RoadType{0.0, "town", "", std::nullopt});

  Stations st = measure_stations(road, lines, options.station_spacing);
  Borders borders = station_borders(plan, st, lines, widths, ref);
  meet_end_borders(st, end_borders, borders);
  for (int round = 0; round < 2 && refine_stations(st, borders.t, road, lines); ++round) {
    borders = station_borders(plan, st, lines, widths, ref);
    meet_end_borders(st, end_borders, borders);
  }
  built.folds = folds_at_stations(st, borders);
  // A lane splitting off or merging into a neighbour is not held to its link where that link
  // runs inside the neighbour (up to 0.9 m beside the lane's centre): on a road sloping across,
  // its link's height taken at the link's own offset left the lane's centre 5-6 cm above or
  // below its link. Its height is taken kMergeHeightShare of the way from the link to the
  // lane's centre instead, so that neither the lane's centre nor the surface under the link is
  // off by much of the crossfall between them.
  std::vector<std::vector<LaneHeightSample>> heights(st.s.size());
  for (size_t i = 0; i < st.s.size(); ++i) {
    for (size_t k = 0; k < plan.lanes.size(); ++k) {
      const Crossing& c = st.crossings[k][i];
      const double centre = 0.5 * (borders.t[i][k] + borders.t[i][k + 1]);
      const double t = borders.centred[i][k] ? c.t : c.t + kMergeHeightShare * (centre - c.t);
      heights[i].push_back({t, c.z, own_part(st, lines, k, i, 2.0)});
    }
  }
  const std::vector<double> roll = fit_lateral_profile(road, st.s, heights, options);
  for (size_t i = 0; i < st.s.size(); ++i) {
    for (double& b : borders.t[i]) {
      b /= std::cos(roll[i]);  // horizontal offsets -> t along the tilted surface (§8.4.2)
    }
  }
  fit_lanes(built, plan, network, st, lines, borders, roll, options);
  add_spans(built, plan, network, st, lines);
  return built;
}

}  // namespace

bool fitted_road_folds(const xodr::Road& road) {
  constexpr double kFoldStep = 0.02;  // m between samples along the road
  constexpr double kMarkReach = 0.1;  // m: half a road mark's width, and some
  constexpr double kMaxSlant = 2.0;   // sideways metres per metre forward
  if (road.lane_sections.empty() || road.length <= 0.0) {
    return false;
  }
  const auto& lanes = road.lane_sections.front().lanes;
  const auto borders = [&](double s) {
    std::vector<double> t{piecewise_value(road.lane_offsets, s)};
    for (const xodr::Lane& lane : lanes) {
      if (lane.id < 0) {
        t.push_back(t.back() - piecewise_value(lane.widths, s));
      }
    }
    return t;
  };
  const int steps = std::max(1, static_cast<int>(std::ceil(road.length / kFoldStep)));
  std::vector<double> before = borders(0.0);
  for (int j = 1; j <= steps; ++j) {
    const double s0 = road.length * (j - 1) / steps;
    const double s1 = road.length * j / steps;
    const double k = curvature_at(road.plan_view, s0);
    const std::vector<double> after = borders(s1);
    for (size_t b = 0; b < after.size(); ++b) {
      // Forward progress of the border (and of a mark beside it) per metre of s.
      const double forward = 1.0 - k * (before[b] + std::copysign(kMarkReach, k));
      if (forward <= 0.0 || std::abs(after[b] - before[b]) > kMaxSlant * forward * (s1 - s0)) {
        return true;
      }
    }
    before = after;
  }
  return false;
}

BuiltRoad build_road(const RoadPlan& plan, const Network& network, const Origin& origin,
                     const std::vector<WidthProfile>& widths, const RoadEndLines& ends,
                     const ConvertOptions& options, const EndBorders& borders) {
  const LaneLines lines = lane_lines(plan, origin);
  BuiltRoad built = build_road_along(plan, network, lines, widths, ends, borders, options, false);
  // A one-lane road turning right whose lane folds over on the inside of the turn: along its
  // right edge instead, the lane lies on the outside of every right turn, where borders cannot
  // fold (road_reference.h, along_right_edge). Only then: a line along the inside is shorter
  // and follows a junction path's steep height steps over less s. Folding is either a border
  // beyond the centre of curvature at a station or one the fitted records give (a border
  // slanting across the road, fitted_road_folds).
  if (plan.lanes.size() != 1) {
    return built;
  }
  const Polyline& lane = lines.smooth[reference_lane(plan)];
  if ((built.folds || fitted_road_folds(built.road)) && along_right_edge(lane)) {
    BuiltRoad right = build_road_along(plan, network, lines, widths, ends, borders, options, true);
    if (!right.folds) {
      return right;
    }
  }
  // A lane still beyond the centre of curvature at a station: along its right edge even
  // where that turns more tightly than the 1.5 m radius (a corner right after its start), as
  // the last resort only: such a right edge rarely turns onto the line of the road it joins
  // (that end keeps its own line), and for every road that turns so Sangam's centre gaps grow.
  if (built.folds && !along_right_edge(lane) && along_right_edge(lane, true)) {
    BuiltRoad right = build_road_along(plan, network, lines, widths, ends, borders, options, true);
    if (!right.folds) {
      return right;
    }
  }
  return built;
}

double end_border_ramp(double largest_move, double road_length) {
  constexpr double kMinRamp = 1.5;      // m
  constexpr double kRampPerMove = 3.0;  // m of ramp per metre moved (slant at most 0.5)
  constexpr double kRampShare = 0.45;   // of the road's length, at most, per end
  return std::min(std::max(kMinRamp, kRampPerMove * largest_move), kRampShare * road_length);
}

}  // namespace corsa::ngii::detail
