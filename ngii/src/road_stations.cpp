// Lane lines and stations of one road (see road_stations.h).

#include "road_stations.h"

#include <algorithm>
#include <cmath>

namespace corsa::ngii::detail {
namespace {

/// `points` in the map frame (source coordinates minus `origin`).
std::vector<Point3> in_map_frame(const std::vector<Point3>& points, const Origin& origin) {
  std::vector<Point3> out(points);
  for (Point3& p : out) {
    p.x -= origin.x;
    p.y -= origin.y;
  }
  return out;
}

/// Evenly spaced stations from 0 to `length`, at most `spacing` apart.
std::vector<double> make_stations(double length, double spacing) {
  const int count = std::max(1, static_cast<int>(std::ceil(length / spacing)));
  std::vector<double> s(static_cast<size_t>(count) + 1);
  for (int i = 0; i <= count; ++i) {
    s[static_cast<size_t>(i)] = length * i / count;
  }
  return s;
}

/// Each lane's crossing of the reference normal at every station of `st`.
void measure_crossings(Stations& st, const xodr::Road& road, const LaneLines& lines) {
  st.ref = sample_reference(road.plan_view, st.s);
  st.curvature.resize(st.s.size());
  for (size_t i = 0; i < st.s.size(); ++i) {
    st.curvature[i] = curvature_at(road.plan_view, st.s[i]);
  }
  st.crossings.assign(lines.measured.size(), std::vector<Crossing>(st.s.size()));
  for (size_t k = 0; k < lines.measured.size(); ++k) {
    LaneTracker tracker(lines.measured[k], lines.measured_start[k], lines.direction_from[k],
                        lines.direction_to[k]);
    for (size_t i = 0; i < st.s.size(); ++i) {
      const Vec2 tangent{std::cos(st.ref[i].hdg), std::sin(st.ref[i].hdg)};
      st.crossings[k][i] = tracker.measure(st.s[i], Vec2{st.ref[i].x, st.ref[i].y}, tangent);
    }
  }
}

}  // namespace

LaneLines lane_lines(const RoadPlan& plan, const Origin& origin) {
  LaneLines out;
  for (const PlanLane& lane : plan.lanes) {
    const std::vector<Point3> points = in_map_frame(lane.points, origin);
    out.raw.emplace_back(points);
    out.smooth.emplace_back(smooth_polyline(points));
    // The lane's own vertices win where the neighbours' pieces meet them (links meeting at one
    // node may disagree on its height).
    const auto same_place = [](const Point3& a, const Point3& b) {
      return norm(xy(a) - xy(b)) < 0.1;
    };
    std::vector<Point3> extended = in_map_frame(lane.lead_in, origin);
    while (!extended.empty() && same_place(extended.back(), points.front())) {
      extended.pop_back();
    }
    const size_t own_first = extended.size();
    extended.insert(extended.end(), points.begin(), points.end());
    std::vector<Point3> lead_out = in_map_frame(lane.lead_out, origin);
    while (!lead_out.empty() && same_place(lead_out.front(), points.back())) {
      lead_out.erase(lead_out.begin());
    }
    extended.insert(extended.end(), lead_out.begin(), lead_out.end());
    remove_duplicates(extended);
    out.measured.emplace_back(smooth_polyline(extended));
    double start = 0.0;
    if (own_first > 0) {
      // Near the end of the lead-in (a looping lane may pass its own start again later).
      const double lead = Polyline(in_map_frame(lane.lead_in, origin)).length();
      start = out.measured.back().project_within(xy(points.front()), 0.0, lead + 1.0).u;
    }
    out.measured_start.push_back(start);
    const Polyline& measured = out.measured.back();
    double end = measured.length();
    const bool path = plan.junction >= 0 && !plan.absorbed;
    if (path && !lead_out.empty()) {
      // Near the start of the lead-out (a looping lane may pass its own end earlier).
      const double lead = Polyline(in_map_frame(lane.lead_out, origin)).length();
      end = measured.project_within(xy(points.back()), end - lead - 1.0, end).u;
    }
    out.direction_from.push_back(path ? start : 0.0);
    out.direction_to.push_back(std::max(path ? start : 0.0, end));
  }
  return out;
}

/// Road s at which the lane's arc length reaches `u`, from the station measurements.
double s_at_u(const std::vector<double>& stations, const std::vector<double>& u, double target) {
  if (target <= u.front()) {
    return stations.front();
  }
  for (size_t i = 1; i < u.size(); ++i) {
    if (u[i] >= target) {
      const double f = u[i] > u[i - 1] ? (target - u[i - 1]) / (u[i] - u[i - 1]) : 0.0;
      return stations[i - 1] + f * (stations[i] - stations[i - 1]);
    }
  }
  return stations.back();
}

Stations measure_stations(const xodr::Road& road, const LaneLines& lines, double spacing) {
  Stations st;
  st.s = make_stations(road.length, spacing);
  measure_crossings(st, road, lines);
  std::vector<double> extra;
  for (size_t k = 0; k < lines.smooth.size(); ++k) {
    std::vector<double> u(st.s.size());
    for (size_t i = 0; i < st.s.size(); ++i) {
      u[i] = st.crossings[k][i].u;
    }
    for (const double vertex_u : lines.smooth[k].u()) {
      const double s = s_at_u(st.s, u, vertex_u);
      if (s > 0.05 && s < road.length - 0.05) {
        extra.push_back(s);
      }
    }
  }
  if (extra.empty()) {
    return st;
  }
  st.s.insert(st.s.end(), extra.begin(), extra.end());
  std::sort(st.s.begin(), st.s.end());
  std::vector<double> kept;
  for (const double s : st.s) {
    if (kept.empty() || s - kept.back() >= 0.2 || s == road.length) {
      kept.push_back(s);
    }
  }
  kept.back() = road.length;
  st.s = std::move(kept);
  measure_crossings(st, road, lines);
  return st;
}

bool own_part(const Stations& st, const LaneLines& lines, size_t k, size_t i, double margin) {
  const double u = st.crossings[k][i].u;
  return u >= -margin && u <= lines.smooth[k].length() + margin;
}

bool refine_stations(Stations& st, const std::vector<std::vector<double>>& border_t,
                     const xodr::Road& road, const LaneLines& lines) {
  constexpr double kMaxStep = 0.08;    // m
  constexpr double kMinSpacing = 0.3;  // m
  std::vector<double> extra;
  for (size_t i = 0; i + 1 < st.s.size(); ++i) {
    if (st.s[i + 1] - st.s[i] < kMinSpacing) {
      continue;
    }
    double step = 0.0;
    for (size_t k = 0; k < border_t[i].size(); ++k) {
      step = std::max(step, std::abs(border_t[i + 1][k] - border_t[i][k]));
    }
    if (step > kMaxStep) {
      extra.push_back(0.5 * (st.s[i] + st.s[i + 1]));
    }
  }
  if (extra.empty()) {
    return false;
  }
  st.s.insert(st.s.end(), extra.begin(), extra.end());
  std::sort(st.s.begin(), st.s.end());
  measure_crossings(st, road, lines);
  return true;
}

}  // namespace corsa::ngii::detail
