#include "lane_widths.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "polyline.h"

namespace corsa::ngii::detail {
namespace {

constexpr double kMinWidth = 1.5;  // m: plausible range of a measured lane width
constexpr double kMaxWidth = 10.0;
constexpr double kMarkReach = 5.5;  // m: farthest mark counted as bounding a lane (half width)
constexpr int kSmooth = 3;          // vertices averaged on either side

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

/// (u, width) samples at the known vertices; empty when none is known.
std::vector<ProfileSample> samples_of(const Polyline& line, const std::vector<double>& widths) {
  std::vector<ProfileSample> out;
  for (size_t i = 0; i < widths.size(); ++i) {
    if (!std::isnan(widths[i])) {
      out.push_back({line.u()[i], widths[i]});
    }
  }
  return out;
}

class WidthMeter {
 public:
  explicit WidthMeter(const Network& network) : network_(network), marks_(network.size()) {
    const Layers& layers = network.layers();
    for (const SurfaceMark& mark : layers.marks) {
      std::vector<Point3> points = mark.points;
      remove_duplicates(points);
      if (points.size() < 2) {
        continue;
      }
      for (const std::string* id : {&mark.right_link, &mark.left_link}) {
        if (const auto link = network.find(*id)) {
          marks_[static_cast<size_t>(*link)].emplace_back(points);
        }
      }
    }
  }

  /// Width at each vertex from the marks bounding the lane's links (NaN where not both sides
  /// have one).
  std::vector<double> from_marks(const PlanLane& lane, const Polyline& line) const {
    std::vector<const Polyline*> candidates;
    for (const int link : lane.links) {
      for (const Polyline& mark : marks_[static_cast<size_t>(link)]) {
        candidates.push_back(&mark);
      }
    }
    std::vector<double> out(line.size(), kUnknown);
    if (candidates.size() < 2) {
      return out;
    }
    for (size_t i = 0; i < line.size(); ++i) {
      const Vec2 v = xy(line.points()[i]);
      const Vec2 tangent = line.direction(line.u()[i]);
      double left = 1e300, right = 1e300;
      for (const Polyline* mark : candidates) {
        const Projection p = mark->project(v);
        if (p.along != 0.0 || p.distance > kMarkReach) {
          continue;
        }
        const bool on_left = cross(tangent, xy(mark->at(p.u)) - v) > 0.0;
        double& side = on_left ? left : right;
        side = std::min(side, p.distance);
      }
      const double width = left + right;
      if (width >= kMinWidth && width <= kMaxWidth) {
        out[i] = width;
      }
    }
    return smoothed(out);
  }

  /// Width at each vertex from the distance to the lane's links' L/R neighbour links.
  std::vector<double> from_neighbours(const PlanLane& lane, const Polyline& line) const {
    std::vector<Polyline> neighbours;
    for (const int link : lane.links) {
      const LinkState& state = network_.links[static_cast<size_t>(link)];
      for (const int other : {state.left, state.right}) {
        if (other >= 0) {
          neighbours.emplace_back(network_.links[static_cast<size_t>(other)].points);
        }
      }
    }
    std::vector<double> out(line.size(), kUnknown);
    for (size_t i = 0; i < line.size() && !neighbours.empty(); ++i) {
      double sum = 0.0;
      int count = 0;
      for (const Polyline& other : neighbours) {
        const Projection p = other.project(xy(line.points()[i]));
        if (p.along == 0.0 && p.distance >= kMinWidth && p.distance <= kMaxWidth) {
          sum += p.distance;
          ++count;
        }
      }
      if (count > 0) {
        out[i] = sum / count;
      }
    }
    return smoothed(out);
  }

 private:
  const Network& network_;
  std::vector<std::vector<Polyline>> marks_;  ///< per A2 link: the marks naming it
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
      WidthSource source = WidthSource::kMarks;
      std::vector<ProfileSample> samples = samples_of(line, meter.from_marks(lane, line));
      if (samples.empty()) {
        source = WidthSource::kNeighbours;
        samples = samples_of(line, meter.from_neighbours(lane, line));
      }
      out.lanes[r].emplace_back(std::move(samples));
      out.sources[r].push_back(source);
      if (out.lanes[r].back().empty()) {
        unknown.emplace_back(r, k);
      }
    }
  }
  // The rest from the lanes before and after them (twice: chains of junction paths).
  const LaneIndex index(plan);
  for (int pass = 0; pass < 2; ++pass) {
    for (const auto& [r, k] : unknown) {
      if (!out.lanes[r][k].empty()) {
        continue;
      }
      const PlanLane& lane = plan.roads[r].lanes[k];
      double before = 0.0, after = 0.0;
      int n_before = 0, n_after = 0;
      for (const auto& ref : index.ending[static_cast<size_t>(lane.start_node)]) {
        const WidthProfile& p = out.lanes[static_cast<size_t>(ref.road)][static_cast<size_t>(ref.lane)];
        if (!p.empty() && &p != &out.lanes[r][k]) {
          before += p.back();
          ++n_before;
        }
      }
      for (const auto& ref : index.starting[static_cast<size_t>(lane.end_node)]) {
        const WidthProfile& p = out.lanes[static_cast<size_t>(ref.road)][static_cast<size_t>(ref.lane)];
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
    }
  }
  for (const auto& [r, k] : unknown) {
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
