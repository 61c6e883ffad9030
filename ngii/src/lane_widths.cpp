#include "lane_widths.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "polyline.h"

namespace corsa::ngii::detail {
namespace {

constexpr double kMinWidth = 1.5;  // m: plausible range of a lane width between marks
constexpr double kMaxWidth = 10.0;
// m: spacing of neighbouring lane centres that reads as one lane width (farther neighbours
// are lanes apart, e.g. parallel turning paths with a gap between them)
constexpr double kMinSpacing = 2.3;
constexpr double kMaxSpacing = 5.5;
constexpr double kMarkReach = 6.0;  // m: farthest mark counted as bounding a lane (half width)
constexpr double kStep = 1.0;       // m between width samples along a lane
constexpr int kSmooth = 2;          // samples averaged on either side
// Junction path ends: a path whose width where it starts (ends) differs from the built
// ordinary lanes it leaves (enters) by more than kPathEndMatch takes theirs there (any width
// between marks, kMinPathWidth-kMaxWidth: a 2 m lane end or a 9 m one widening into a turn
// pocket is the edge the path meets, and a path narrower or wider than it there leaves unpaved
// ground beside the joint), easing back to its own over kPathEndRamp (at most kPathEndRampShare of
// its length), or over the whole stretch before the marks first give its width (at most half its
// length: there its own width is only the nearest sample held flat, often the 6-8 m a path
// measures between the intersection's edges deep inside it); at least kMinPathWidth wide.
constexpr double kPathEndMatch = 0.02;  // m
constexpr double kPathEndRamp = 3.0;    // m
constexpr double kPathEndRampShare = 0.4;
constexpr double kMinPathWidth = 1.5;  // m

const double kUnknown = std::numeric_limits<double>::quiet_NaN();

/// Moving average over +-kSmooth known values; unknown vertices stay unknown.
std::vector<double> smoothed(const std::vector<double>& raw) {
  const size_t n = raw.size();
  std::vector<double> out(n, kUnknown);
  for (size_t i = 0; i < n; ++i) {
    if (std::isnan(raw[i])) {
      continue;
    }
    double sum = 0.0;
    int count = 0;
    for (size_t j = i >= kSmooth ? i - kSmooth : 0; j < std::min(n, i + kSmooth + 1); ++j) {
      if (!std::isnan(raw[j])) {
        sum += raw[j];
        ++count;
      }
    }
    out[i] = sum / count;
  }
  return out;
}

/// Arc lengths every kStep metres along `line` (both ends included).
std::vector<double> stations_of(const Polyline& line) {
  const int count = std::max(1, static_cast<int>(std::ceil(line.length() / kStep)));
  std::vector<double> u(static_cast<size_t>(count) + 1);
  for (int i = 0; i <= count; ++i) {
    u[static_cast<size_t>(i)] = line.length() * i / count;
  }
  return u;
}

/// (u, width) samples where the width is known; empty when it is nowhere.
std::vector<ProfileSample> samples_of(const std::vector<double>& u,
                                      const std::vector<double>& widths) {
  std::vector<ProfileSample> out;
  for (size_t i = 0; i < widths.size(); ++i) {
    if (!std::isnan(widths[i])) {
      out.push_back({u[i], widths[i]});
    }
  }
  return out;
}

class WidthMeter {
 public:
  explicit WidthMeter(const Network& network)
      : network_(network),
        link_lines_(network.size()),
        left_marks_(network.size()),
        right_marks_(network.size()) {
    for (const SurfaceMark& mark : network.layers().marks) {
      std::vector<Point3> points = mark.points;
      remove_duplicates(points);
      if (points.size() < 2) {
        continue;
      }
      // R_linkID is the link on the mark's right: the mark bounds that lane on its left. A mark
      // naming one link on both sides crosses that lane rather than bounding it.
      if (mark.right_link == mark.left_link) {
        continue;
      }
      if (const auto link = network.find(mark.right_link)) {
        left_marks_[static_cast<size_t>(*link)].emplace_back(points);
      }
      if (const auto link = network.find(mark.left_link)) {
        right_marks_[static_cast<size_t>(*link)].emplace_back(points);
      }
    }
  }

  /// Width at each station u from the marks bounding the link there: the nearest mark naming
  /// the link on each side, within kMarkReach. With `one_side`, where only one side has a mark,
  /// twice the distance to it (the link runs down the lane's middle). NaN where unknown.
  std::vector<double> from_marks(const PlanLane& lane, const Polyline& line,
                                 const std::vector<double>& stations, bool one_side) const {
    std::vector<double> out(stations.size(), kUnknown);
    for (size_t i = 0; i < stations.size(); ++i) {
      const size_t link = static_cast<size_t>(link_at(lane, stations[i]));
      const Vec2 v = xy(line.at(stations[i]));
      const Vec2 tangent = line.direction(stations[i]);
      const double left = side_distance(left_marks_[link], v, tangent, true);
      const double right = side_distance(right_marks_[link], v, tangent, false);
      double width = left + right;
      if (one_side && width > 1e299) {
        width = 2.0 * std::min(left, right);
      }
      if (width >= kMinWidth && width <= kMaxWidth) {
        out[i] = width;
      }
    }
    return smoothed(out);
  }

  /// Width at each station u from the distance to the L/R neighbour links of the link there;
  /// with `any_lane`, to whichever other link runs beside it (either direction: the lane of the
  /// other carriageway), for links without L/R neighbours.
  std::vector<double> from_neighbours(const PlanLane& lane, const Polyline& line,
                                      const std::vector<double>& stations, bool any_lane) const {
    std::vector<double> out(stations.size(), kUnknown);
    std::vector<Polyline> nearby;
    if (any_lane) {
      const Polyline own(lane.points);
      for (size_t l = 0; l < network_.size(); ++l) {
        const LinkState& other = network_.links[l];
        if (other.removed ||
            std::find(lane.links.begin(), lane.links.end(), int(l)) != lane.links.end()) {
          continue;
        }
        const Projection p = own.project(xy(other.points[other.points.size() / 2]));
        if (p.distance < 50.0 + 0.5 * other.length) {
          nearby.emplace_back(other.points);
        }
      }
    }
    std::vector<const Polyline*> neighbours;
    for (size_t i = 0; i < stations.size(); ++i) {
      const LinkState& state = network_.links[static_cast<size_t>(link_at(lane, stations[i]))];
      neighbours.clear();
      if (any_lane) {
        for (const Polyline& other : nearby) {
          neighbours.push_back(&other);
        }
      } else {
        for (const int other : {state.left, state.right}) {
          if (other >= 0) {
            neighbours.push_back(&link_line(other));
          }
        }
      }
      double sum = 0.0;
      int count = 0;
      double nearest = 1e300;
      for (const Polyline* other : neighbours) {
        const Projection p = other->project(xy(line.at(stations[i])));
        if (p.along == 0.0 && p.distance >= kMinSpacing && p.distance <= kMaxSpacing) {
          sum += p.distance;
          ++count;
          nearest = std::min(nearest, p.distance);
        }
      }
      if (count > 0) {
        out[i] = any_lane ? nearest : sum / count;
      }
    }
    return smoothed(out);
  }

 private:
  /// The A2 link of the plan lane at arc length u.
  static int link_at(const PlanLane& lane, double u) {
    size_t j = 0;
    while (j + 1 < lane.links.size() && lane.link_starts[j + 1] <= u) {
      ++j;
    }
    return lane.links[j];
  }

  /// Distance from v to the nearest of `marks` lying on the given side of the direction of
  /// travel, with its foot inside the mark and within kMarkReach; 1e300 when none.
  static double side_distance(const std::vector<Polyline>& marks, Vec2 v, Vec2 tangent, bool left) {
    double best = 1e300;
    for (const Polyline& mark : marks) {
      const Projection p = mark.project(v);
      if (p.along != 0.0 || p.distance > kMarkReach) {
        continue;
      }
      const bool on_left = cross(tangent, xy(mark.at(p.u)) - v) > 0.0;
      if (on_left == left) {
        best = std::min(best, p.distance);
      }
    }
    return best;
  }

  /// The (cleaned) polyline of A2 link `link`, made once.
  const Polyline& link_line(int link) const {
    auto& slot = link_lines_[static_cast<size_t>(link)];
    if (!slot) {
      slot = std::make_unique<Polyline>(network_.links[static_cast<size_t>(link)].points);
    }
    return *slot;
  }

  const Network& network_;
  mutable std::vector<std::unique_ptr<Polyline>> link_lines_;
  /// Per A2 link: the marks bounding it on the left (their R_linkID names it) and right.
  std::vector<std::vector<Polyline>> left_marks_;
  std::vector<std::vector<Polyline>> right_marks_;
};

}  // namespace

double WidthProfile::at(double u) const {
  if (u <= samples_.front().s) {
    return samples_.front().v;
  }
  if (u >= samples_.back().s) {
    return samples_.back().v;
  }
  const auto it = std::upper_bound(samples_.begin(), samples_.end(), u,
                                   [](double x, const ProfileSample& p) { return x < p.s; });
  const ProfileSample& b = *it;
  const ProfileSample& a = *(it - 1);
  const double f = b.s > a.s ? (u - a.s) / (b.s - a.s) : 0.0;
  return a.v + f * (b.v - a.v);
}

namespace {

/// Mean width the ordinary lanes (not junction paths) in `refs` have where they end
/// (`at_end`) or begin, as built, taken across a path whose lane runs along `direction` there
/// (a lane crossing the joined road's end at an angle spans its width / cos(angle) of it);
/// 0 when there are none.
double joined_width(const NetworkPlan& plan, const std::vector<LaneIndex::Ref>& refs,
                    const JoinedLaneEndOf& joined, bool at_end, Vec2 direction) {
  constexpr double kMinAlong = 0.6;  // as the road builder's width targets (road_builder.cpp)
  double sum = 0.0;
  int n = 0;
  for (const auto& ref : refs) {
    const RoadPlan& road = plan.roads[static_cast<size_t>(ref.road)];
    if (road.removed || (road.junction >= 0 && !road.absorbed)) {
      continue;
    }
    const std::optional<JoinedLaneEnd> end = joined(ref, at_end);
    if (!end) {
      continue;
    }
    const double along =
        std::abs(dot(direction, Vec2{std::cos(end->heading), std::sin(end->heading)}));
    sum += end->width * std::max(along, kMinAlong);
    ++n;
  }
  return n > 0 ? sum / n : 0.0;
}

/// 1 at x = 0 easing to 0 at x = 1 with zero slope at both (a smoothstep), 0 beyond.
double ease_out(double x) {
  if (x >= 1.0) {
    return 0.0;
  }
  const double y = std::max(0.0, x);
  return 1.0 - y * y * (3.0 - 2.0 * y);
}

}  // namespace

void match_path_ends(const NetworkPlan& plan, const LaneIndex& index, const JoinedLaneEndOf& joined,
                     std::vector<std::vector<WidthProfile>>& widths) {
  for (size_t r = 0; r < plan.roads.size(); ++r) {
    const RoadPlan& road = plan.roads[r];
    if (road.removed || road.junction < 0 || road.absorbed) {
      continue;
    }
    for (size_t k = 0; k < road.lanes.size(); ++k) {
      const PlanLane& lane = road.lanes[k];
      WidthProfile& profile = widths[r][k];
      const Polyline line(lane.points);
      const double length = line.length();
      if (profile.empty() || length <= 0.0) {
        continue;
      }
      const double before = joined_width(plan, index.ending[static_cast<size_t>(lane.start_node)],
                                         joined, true, line.direction(0.0));
      const double after = joined_width(plan, index.starting[static_cast<size_t>(lane.end_node)],
                                        joined, false, line.direction(length));
      const auto change = [](double target, double own) {
        return target >= kMinPathWidth && target <= kMaxWidth ? target - own : 0.0;
      };
      const double d0 = change(before, profile.front());
      const double d1 = change(after, profile.back());
      if (std::abs(d0) < kPathEndMatch && std::abs(d1) < kPathEndMatch) {
        continue;
      }
      const double ramp = std::min(kPathEndRamp, kPathEndRampShare * length);
      const double ramp0 = std::min(std::max(ramp, profile.first_u()), 0.5 * length);
      const double ramp1 = std::min(std::max(ramp, length - profile.last_u()), 0.5 * length);
      std::vector<ProfileSample> samples;
      for (const double u : stations_of(line)) {
        const double w =
            profile.at(u) + d0 * ease_out(u / ramp0) + d1 * ease_out((length - u) / ramp1);
        samples.push_back({u, std::max(w, kMinPathWidth)});
      }
      profile = WidthProfile(std::move(samples));
    }
  }
}

PlanWidths measure_widths(const NetworkPlan& plan, const Network& network, double fallback) {
  const WidthMeter meter(network);
  PlanWidths out;
  out.lanes.resize(plan.roads.size());
  out.sources.resize(plan.roads.size());
  std::vector<std::pair<size_t, size_t>> unknown;
  for (size_t r = 0; r < plan.roads.size(); ++r) {
    if (plan.roads[r].removed) {
      continue;
    }
    for (size_t k = 0; k < plan.roads[r].lanes.size(); ++k) {
      const PlanLane& lane = plan.roads[r].lanes[k];
      const Polyline line(lane.points);
      const std::vector<double> stations = stations_of(line);
      WidthSource source = WidthSource::kMarks;
      std::vector<ProfileSample> samples =
          samples_of(stations, meter.from_marks(lane, line, stations, false));
      // A junction path with a mark on one side only has no lane mark there but the
      // intersection's edge or a guide line for another turn: twice the distance to it is not
      // its width (up to 12 m in K-City); the paths before and after it give a better one.
      const bool junction_path = plan.roads[r].junction >= 0 && !plan.roads[r].absorbed;
      if (samples.empty() && !junction_path) {
        samples = samples_of(stations, meter.from_marks(lane, line, stations, true));
      }
      if (samples.empty()) {
        source = WidthSource::kNeighbours;
        samples = samples_of(stations, meter.from_neighbours(lane, line, stations, false));
      }
      out.lanes[r].emplace_back(std::move(samples));
      out.sources[r].push_back(source);
      if (out.lanes[r].back().empty()) {
        unknown.emplace_back(r, k);
      }
    }
  }
  // The rest from the lanes before and after them, pass after pass while that reaches more
  // (chains of junction paths).
  const LaneIndex index(plan);
  for (bool progress = true; progress;) {
    progress = false;
    for (const auto& [r, k] : unknown) {
      if (!out.lanes[r][k].empty()) {
        continue;
      }
      const PlanLane& lane = plan.roads[r].lanes[k];
      double before = 0.0, after = 0.0;
      int n_before = 0, n_after = 0;
      for (const auto& ref : index.ending[static_cast<size_t>(lane.start_node)]) {
        const WidthProfile& p =
            out.lanes[static_cast<size_t>(ref.road)][static_cast<size_t>(ref.lane)];
        if (!p.empty() && &p != &out.lanes[r][k]) {
          before += p.back();
          ++n_before;
        }
      }
      for (const auto& ref : index.starting[static_cast<size_t>(lane.end_node)]) {
        const WidthProfile& p =
            out.lanes[static_cast<size_t>(ref.road)][static_cast<size_t>(ref.lane)];
        if (!p.empty() && &p != &out.lanes[r][k]) {
          after += p.front();
          ++n_after;
        }
      }
      if (n_before + n_after == 0) {
        continue;
      }
      const double length = Polyline(lane.points).length();
      const double w0 = n_before > 0 ? before / n_before : after / n_after;
      const double w1 = n_after > 0 ? after / n_after : w0;
      out.lanes[r][k] = WidthProfile({{0.0, w0}, {length, w1}});
      out.sources[r][k] = WidthSource::kTopology;
      progress = true;
    }
  }
  for (const auto& [r, k] : unknown) {
    if (out.lanes[r][k].empty()) {
      const PlanLane& lane = plan.roads[r].lanes[k];
      const Polyline line(lane.points);
      const std::vector<double> stations = stations_of(line);
      out.lanes[r][k] =
          WidthProfile(samples_of(stations, meter.from_neighbours(lane, line, stations, true)));
      out.sources[r][k] = WidthSource::kNeighbours;
    }
    if (out.lanes[r][k].empty()) {
      out.lanes[r][k] = WidthProfile({{0.0, fallback}});
      out.sources[r][k] = WidthSource::kFallback;
    }
  }
  for (const auto& sources : out.sources) {
    for (const WidthSource source : sources) {
      ++out.counts[static_cast<size_t>(source)];
    }
  }
  return out;
}

}  // namespace corsa::ngii::detail
