// Road geometry from lane centre lines (see road_builder.h).
//
// Lane layout: every converted road carries its lanes on the right of the reference line
// (ids -1..-n, OpenDRIVE 1.8 §9.1), since NGII links are one-way and the reference line follows
// the leftmost lane. At each station the measured lane centre offsets c_k (t, m) give the lane
// borders b_0..b_n by a small least-squares problem: each lane's centre (b_{k-1}+b_k)/2 must
// match c_k (heavily weighted, tightened until within 2 cm), each width b_{k-1}-b_k should match
// the measured spacing of neighbouring centre lines, and b_0 (the laneOffset, §9.3) stays near 0.

#include "road_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "corsa/ngii/curve_fit.h"
#include "lane_numbers.h"
#include "polyline.h"
#include "reference_line.h"

namespace corsa::ngii::detail {
namespace {

constexpr double kMinWidth = 2.0;  // m: plausible range of a measured lane width
constexpr double kMaxWidth = 6.0;
constexpr double kCentreTolerance = 0.02;  // m: border solution centre error target
constexpr double kMinShiftRadius = 1.5;    // m: tightest radius of the shifted reference line
constexpr double kEase = 12.0;             // m over which a reduced shift is eased in and out

std::vector<Point3> shifted(const std::vector<Point3>& points, const Origin& origin) {
  std::vector<Point3> out(points);
  for (Point3& p : out) {
    p.x -= origin.x;
    p.y -= origin.y;
  }
  return out;
}

/// Width of the leftmost lane at each of its vertices: the distance to the next lane's centre
/// line, smoothed; `fallback` where there is none.
std::vector<double> leftmost_widths(const Polyline& first, const Polyline* second,
                                    double fallback) {
  const size_t n = first.size();
  std::vector<double> raw(n, std::numeric_limits<double>::quiet_NaN());
  if (second != nullptr) {
    for (size_t i = 0; i < n; ++i) {
      const Projection p = second->project(xy(first.points()[i]));
      if (p.along == 0.0) {
        raw[i] = std::clamp(std::abs(p.lateral), kMinWidth, kMaxWidth);
      }
    }
  }
  // Fill gaps from the nearest measured vertex (by index), or the fallback when none was.
  std::vector<double> filled(n, fallback);
  std::vector<int> previous(n, -1);
  int last_valid = -1;
  for (size_t i = 0; i < n; ++i) {
    last_valid = std::isnan(raw[i]) ? last_valid : static_cast<int>(i);
    previous[i] = last_valid;
  }
  int next_valid = -1;
  for (size_t i = n; i-- > 0;) {
    next_valid = std::isnan(raw[i]) ? next_valid : static_cast<int>(i);
    const int before = previous[i];
    int pick = before;
    if (next_valid >= 0 &&
        (before < 0 || next_valid - static_cast<int>(i) < static_cast<int>(i) - before)) {
      pick = next_valid;
    }
    if (pick >= 0) {
      filled[i] = raw[static_cast<size_t>(pick)];
    }
  }
  // Moving average over +-3 vertices.
  std::vector<double> smooth(n);
  for (size_t i = 0; i < n; ++i) {
    const size_t a = i >= 3 ? i - 3 : 0;
    const size_t b = std::min(n - 1, i + 3);
    double sum = 0.0;
    for (size_t j = a; j <= b; ++j) {
      sum += filled[j];
    }
    smooth[i] = sum / static_cast<double>(b - a + 1);
  }
  return smooth;
}

/// The leftmost lane's vertices moved left by half the lane width, along the normal of the
/// chord over +-1 m (robust to very short segments). In tight left turns the shifted line would
/// turn tighter than the lane (radius R - w/2) or fold over, so there the shift shrinks to keep
/// its radius at least kMinShiftRadius; the laneOffset takes up the difference (§9.3).
std::vector<Point2> reference_points(const Polyline& first, const std::vector<double>& widths) {
  const auto& p = first.points();
  const size_t n = p.size();
  std::vector<Vec2> normals(n);
  std::vector<double> shift(n);
  for (size_t i = 0; i < n; ++i) {
    const double u = first.u()[i];
    const Vec2 back = xy(first.at(u)) - xy(first.at(u - 1.0));
    const Vec2 ahead = xy(first.at(u + 1.0)) - xy(first.at(u));
    Vec2 tangent = back + ahead;
    const double len = norm(tangent);
    tangent = len > 1e-9 ? (1.0 / len) * tangent : first.direction(u);
    normals[i] = Vec2{-tangent.y, tangent.x};
    // Signed curvature from the turn between the half chords (positive: a left turn).
    const double turn = norm(back) > 1e-9 && norm(ahead) > 1e-9
                            ? angle_diff(std::atan2(ahead.y, ahead.x), std::atan2(back.y, back.x))
                            : 0.0;
    const double arc = 0.5 * (norm(back) + norm(ahead));
    const double curvature = arc > 1e-9 ? turn / arc : 0.0;
    shift[i] = 0.5 * widths[i];
    if (curvature > 0.0) {
      shift[i] = std::clamp(1.0 / curvature - kMinShiftRadius, 0.0, shift[i]);
    }
  }
  // Ease the reductions in and out: the smallest shift within kEase on either side, then its
  // mean within kEase / 2 (never above what the turn allows, since every value averaged is a
  // minimum over a window containing this vertex).
  const auto window = [&](const std::vector<double>& in, double reach, bool minimum) {
    std::vector<double> result(n);
    for (size_t i = 0; i < n; ++i) {
      double value = in[i], sum = 0.0;
      size_t count = 0;
      for (size_t j = i; j-- > 0 && first.u()[i] - first.u()[j] <= reach;) {
        value = std::min(value, in[j]);
        sum += in[j];
        ++count;
      }
      for (size_t j = i; j < n && first.u()[j] - first.u()[i] <= reach; ++j) {
        value = std::min(value, in[j]);
        sum += in[j];
        ++count;
      }
      result[i] = minimum ? value : sum / static_cast<double>(count);
    }
    return result;
  };
  const std::vector<double> eased = window(window(shift, kEase, true), 0.5 * kEase, false);
  std::vector<Point2> out(n);
  for (size_t i = 0; i < n; ++i) {
    out[i] = Point2{p[i].x + eased[i] * normals[i].x, p[i].y + eased[i] * normals[i].y};
  }
  return out;
}

/// The leftmost lane's measured width at arc length u (interpolated between its vertices).
double width_at(const Polyline& line, const std::vector<double>& widths, double u) {
  const auto& us = line.u();
  if (u <= us.front()) {
    return widths.front();
  }
  if (u >= us.back()) {
    return widths.back();
  }
  const size_t i = line.segment_at(u);
  const double span = us[i + 1] - us[i];
  const double f = span > 0.0 ? (u - us[i]) / span : 0.0;
  return widths[i] + f * (widths[i + 1] - widths[i]);
}

/// Where the normal of the reference line at a station crosses a lane's centre line.
struct Crossing {
  double t = 0.0;  ///< lateral offset (m, + left)
  double u = 0.0;  ///< arc length along the lane line (may run past its ends when extrapolated)
  double z = 0.0;
};

/// Walks a lane polyline along increasing stations. Each station's crossing is searched only
/// near where the previous one was (a window of arc length), so that a lane folding back on
/// itself (a U-turn path) is never matched on its far leg.
class LaneTracker {
 public:
  /// `start_u`: arc length where the lane proper starts (after its lead-in); crossings are
  /// reported relative to it.
  LaneTracker(const Polyline& line, double start_u)
      : line_(line), start_u_(start_u), last_u_(start_u) {}

  /// The crossing of the normal at station s (stations in increasing order).
  Crossing measure(double s, Vec2 r, Vec2 tangent) {
    expected_u_ = last_u_ + (s - last_s_);
    last_s_ = s;
    Crossing c = measure_absolute(r, tangent);
    c.u -= start_u_;
    return c;
  }

 private:
  Crossing measure_absolute(Vec2 r, Vec2 tangent) {
    const auto& p = line_.points();
    const size_t segments = p.size() - 1;
    const auto g = [&](size_t i) { return dot(xy(p[i]) - r, tangent); };
    const Vec2 normal{-tangent.y, tangent.x};
    const double low = last_u_ - kBehind;
    const double high = last_u_ + kAhead;
    std::optional<Crossing> best;
    for (size_t i = line_.segment_at(std::max(0.0, low)); i < segments; ++i) {
      if (line_.u()[i] > high) {
        break;
      }
      const double g0 = g(i);
      const double g1 = g(i + 1);
      if ((g0 <= 0.0) != (g1 <= 0.0) || g0 == 0.0) {
        const double f = g0 == g1 ? 0.0 : g0 / (g0 - g1);
        const Vec2 q = xy(p[i]) + f * (xy(p[i + 1]) - xy(p[i]));
        const Crossing c{dot(q - r, normal), line_.u()[i] + f * (line_.u()[i + 1] - line_.u()[i]),
                         p[i].z + f * (p[i + 1].z - p[i].z)};
        if (!best || cost(c) < cost(*best)) {
          best = c;
        }
      }
    }
    // The end segments extended as straight lines are candidates too (stations just before
    // the start or past the end, where the lane itself is not crossed).
    for (const bool at_start : {true, false}) {
      if ((at_start && low > 0.0) || (!at_start && high < line_.length())) {
        continue;
      }
      const size_t i = at_start ? 0 : segments - 1;
      const Vec2 a = xy(p[at_start ? 0 : segments]);
      const Vec2 d = line_.segment_direction(i);
      const double denominator = dot(d, tangent);
      if (std::abs(denominator) < 0.3) {
        continue;
      }
      const double lambda = -dot(a - r, tangent) / denominator;
      if ((at_start && lambda > 0.5) || (!at_start && lambda < -0.5)) {
        continue;  // that crossing is on the lane itself, found above if anywhere
      }
      const Crossing c{dot(a + lambda * d - r, normal), (at_start ? 0.0 : line_.length()) + lambda,
                       p[at_start ? 0 : segments].z};
      if (!best || cost(c) < cost(*best)) {
        best = c;
      }
    }
    if (best && std::abs(best->t) < kMaxOffset) {
      last_u_ = std::clamp(best->u, 0.0, line_.length());
      last_t_ = best->t;
      return *best;
    }
    // No usable crossing: the offset of the nearest point in the window.
    Crossing nearest;
    double best_distance = 1e300;
    for (double u = std::max(0.0, low); u <= std::min(high, line_.length()); u += 0.25) {
      const Point3 q = line_.at(u);
      const double d = norm(xy(q) - r);
      if (d < best_distance) {
        best_distance = d;
        nearest = Crossing{dot(xy(q) - r, normal), u, q.z};
      }
    }
    last_u_ = nearest.u;
    last_t_ = nearest.t;
    return nearest;
  }

  static constexpr double kBehind = 5.0;      // m of lane searched behind the last crossing
  static constexpr double kAhead = 25.0;      // m searched ahead of it
  static constexpr double kMaxOffset = 30.0;  // m: farther crossings are not this lane's

  /// A lane advances about as fast as the stations and keeps its offset: the crossing closest
  /// to the expected arc length and to the previous offset is the one on this stretch of the
  /// lane (not its far leg at a U-turn, nor a later part of a sharp turn).
  double cost(const Crossing& c) const {
    return std::abs(c.u - expected_u_) + std::abs(c.t - last_t_);
  }

  const Polyline& line_;
  double start_u_ = 0.0;
  double last_s_ = 0.0;
  double expected_u_ = 0.0;
  double last_u_ = 0.0;
  double last_t_ = 0.0;  ///< the first station starts from the crossing nearest the line
};

/// Solves the dense system a x = b in place (partial pivoting); n is small (lanes + 1).
void solve_dense(double* a, std::vector<double>& b, size_t n) {
  for (size_t col = 0; col < n; ++col) {
    size_t pivot = col;
    for (size_t row = col + 1; row < n; ++row) {
      if (std::abs(a[row * n + col]) > std::abs(a[pivot * n + col])) {
        pivot = row;
      }
    }
    for (size_t k = 0; k < n; ++k) {
      std::swap(a[col * n + k], a[pivot * n + k]);
    }
    std::swap(b[col], b[pivot]);
    for (size_t row = col + 1; row < n; ++row) {
      const double f = a[row * n + col] / a[col * n + col];
      for (size_t k = col; k < n; ++k) {
        a[row * n + k] -= f * a[col * n + k];
      }
      b[row] -= f * b[col];
    }
  }
  for (size_t row = n; row-- > 0;) {
    for (size_t k = row + 1; k < n; ++k) {
      b[row] -= a[row * n + k] * b[k];
    }
    b[row] /= a[row * n + row];
  }
}

/// Lane borders b_0..b_n (t, m) at one station from the lane centres `c` and the measured
/// width of the leftmost lane (see file comment).
std::vector<double> solve_borders(const std::vector<double>& c, double first_width) {
  const size_t lanes = c.size();
  const size_t n = lanes + 1;
  // One workspace: width targets m, weights alpha, matrix a (GCC 12 mis-reports
  // -Wfree-nonheap-object on several small vectors here).
  std::vector<double> work(2 * lanes + n * n, 0.0);
  double* m = work.data();
  double* alpha = m + lanes;
  double* a = alpha + lanes;
  // Width targets from the spacing of neighbouring centre lines.
  for (size_t k = 0; k < lanes; ++k) {
    alpha[k] = 100.0;
    double target = first_width;
    if (k > 0 && k + 1 < lanes) {
      target = 0.5 * (c[k - 1] - c[k + 1]);
    } else if (k > 0) {
      target = c[k - 1] - c[k];
    }
    m[k] = std::clamp(target, kMinWidth, kMaxWidth);
  }
  std::vector<double> b(n);
  for (int round = 0; round < 5; ++round) {
    std::fill(a, a + n * n, 0.0);
    std::fill(b.begin(), b.end(), 0.0);
    a[0] += 0.01;  // keeps b_0 (the laneOffset) near zero, but it takes the reference line error
    for (size_t k = 1; k <= lanes; ++k) {
      const double w = alpha[k - 1];
      a[(k - 1) * n + (k - 1)] += w / 4 + 1.0;
      a[(k - 1) * n + k] += w / 4 - 1.0;
      a[k * n + (k - 1)] += w / 4 - 1.0;
      a[k * n + k] += w / 4 + 1.0;
      b[k - 1] += w * c[k - 1] / 2 + m[k - 1];
      b[k] += w * c[k - 1] / 2 - m[k - 1];
    }
    solve_dense(a, b, n);
    bool done = true;
    for (size_t k = 1; k <= lanes; ++k) {
      if (std::abs(0.5 * (b[k - 1] + b[k]) - c[k - 1]) > kCentreTolerance) {
        alpha[k - 1] *= 10.0;
        done = false;
      }
    }
    if (done) {
      break;
    }
  }
  return b;
}

xodr::LaneType lane_type_of(const Network& network, int link) {
  return network.source(link).link_type == "4" ? xodr::LaneType::kBus : xodr::LaneType::kDriving;
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

std::vector<double> make_stations(double length, double spacing) {
  const int count = std::max(1, static_cast<int>(std::ceil(length / spacing)));
  std::vector<double> s(static_cast<size_t>(count) + 1);
  for (int i = 0; i <= count; ++i) {
    s[static_cast<size_t>(i)] = length * i / count;
  }
  return s;
}

}  // namespace

BuiltRoad build_road(const RoadPlan& plan, const Network& network, const Origin& origin,
                     const ConvertOptions& options) {
  BuiltRoad built;
  const size_t lanes = plan.lanes.size();
  std::vector<Polyline> lines;
  lines.reserve(lanes);
  std::vector<Polyline> raw;
  raw.reserve(lanes);
  // Where offsets are measured: each lane with a few metres of its neighbours before and after,
  // so that stations beyond a lane's own ends (staggered lane ends) see real geometry.
  std::vector<Polyline> measured;
  std::vector<double> measured_start(lanes, 0.0);
  measured.reserve(lanes);
  for (size_t k = 0; k < lanes; ++k) {
    const PlanLane& lane = plan.lanes[k];
    const std::vector<Point3> points = shifted(lane.points, origin);
    raw.emplace_back(points);
    lines.emplace_back(smooth_polyline(points));
    std::vector<Point3> extended = shifted(lane.lead_in, origin);
    const size_t own_first = extended.size();
    extended.insert(extended.end(), points.begin(), points.end());
    const std::vector<Point3> lead_out = shifted(lane.lead_out, origin);
    extended.insert(extended.end(), lead_out.begin(), lead_out.end());
    remove_duplicates(extended);
    measured.emplace_back(smooth_polyline(extended));
    if (own_first > 0) {
      // Near the end of the lead-in (a looping lane may pass its own start again later).
      const double lead = Polyline(shifted(lane.lead_in, origin)).length();
      measured_start[k] = measured.back().project_within(xy(points.front()), 0.0, lead + 1.0).u;
    }
  }
  built.measured_width = lanes > 1;
  const std::vector<double> widths =
      leftmost_widths(lines[0], lanes > 1 ? &lines[1] : nullptr, options.fallback_lane_width);
  const std::vector<Point2> reference = reference_points(lines[0], widths);
  CurveFitOptions fit_options;
  fit_options.tolerance = options.tolerance;
  CurveFit fit = fit_plan_view(reference, fit_options);
  built.reference_error = fit.max_error;
  built.kinks = fit.kinks;
  xodr::Road& road = built.road;
  road.length = fit.length;
  road.plan_view = std::move(fit.geometries);
  road.types.push_back(xodr::RoadType{0.0, "town", "", std::nullopt});

  // Lane centre offsets at stations: evenly spaced, plus where each lane's vertices are (so
  // that the widths follow the lanes into sharp corners of coarsely digitised links).
  std::vector<double> stations = make_stations(road.length, options.station_spacing);
  std::vector<RefSample> ref;
  std::vector<std::vector<Crossing>> crossings;
  const auto measure = [&] {
    ref = sample_reference(road.plan_view, stations);
    crossings.assign(lanes, std::vector<Crossing>(stations.size()));
    for (size_t k = 0; k < lanes; ++k) {
      LaneTracker tracker(measured[k], measured_start[k]);
      for (size_t i = 0; i < stations.size(); ++i) {
        const Vec2 tangent{std::cos(ref[i].hdg), std::sin(ref[i].hdg)};
        crossings[k][i] = tracker.measure(stations[i], Vec2{ref[i].x, ref[i].y}, tangent);
      }
    }
  };
  measure();
  std::vector<double> extra;
  for (size_t k = 0; k < lanes; ++k) {
    std::vector<double> u(stations.size());
    for (size_t i = 0; i < stations.size(); ++i) {
      u[i] = crossings[k][i].u;
    }
    for (const double vertex_u : lines[k].u()) {
      const double s = s_at_u(stations, u, vertex_u);
      if (s > 0.05 && s < road.length - 0.05) {
        extra.push_back(s);
      }
    }
  }
  if (!extra.empty()) {
    stations.insert(stations.end(), extra.begin(), extra.end());
    std::sort(stations.begin(), stations.end());
    // Stations closer than 0.2 m add nothing but cost.
    std::vector<double> kept;
    for (const double s : stations) {
      if (kept.empty() || s - kept.back() >= 0.2 || s == road.length) {
        kept.push_back(s);
      }
    }
    if (kept.back() != road.length) {
      kept.back() = road.length;
    }
    stations = std::move(kept);
    measure();
  }
  // Borders per station, then laneOffset and widths fitted one after the other, each against
  // what the previous fitted borders left (so errors do not add up across lanes).
  std::vector<std::vector<double>> borders(stations.size());
  std::vector<double> centres(lanes);
  for (size_t i = 0; i < stations.size(); ++i) {
    for (size_t k = 0; k < lanes; ++k) {
      centres[k] = crossings[k][i].t;
    }
    borders[i] = solve_borders(centres, width_at(lines[0], widths, crossings[0][i].u));
  }
  std::vector<ProfileSample> samples(stations.size());
  double offset_size = 0.0;
  for (size_t i = 0; i < stations.size(); ++i) {
    samples[i] = {stations[i], borders[i][0]};
    offset_size = std::max(offset_size, std::abs(borders[i][0]));
  }
  std::vector<double> inner(stations.size(), 0.0);
  if (offset_size > 0.005) {
    road.lane_offsets = fit_profile(samples, options.width_tolerance).pieces;
    for (size_t i = 0; i < stations.size(); ++i) {
      const auto& pieces = road.lane_offsets;
      auto it = std::upper_bound(pieces.begin(), pieces.end(), stations[i],
                                 [](double s, const xodr::Poly3& p) { return s < p.s; });
      inner[i] = (it == pieces.begin() ? pieces.front() : *(it - 1)).value(stations[i]);
    }
  }
  xodr::LaneSection section;
  section.s = 0.0;
  xodr::Lane centre;
  centre.id = 0;
  centre.type = xodr::LaneType::kNone;
  centre.type_name = "none";
  section.lanes.push_back(centre);
  built.spans.resize(lanes);
  std::vector<double> u_at(stations.size());
  for (size_t k = 0; k < lanes; ++k) {
    for (size_t i = 0; i < stations.size(); ++i) {
      samples[i] = {stations[i], inner[i] - borders[i][k + 1]};
    }
    const ProfileFit width = fit_profile(samples, options.width_tolerance);
    xodr::Lane lane;
    lane.id = -static_cast<int>(k) - 1;
    const PlanLane& source = plan.lanes[k];
    lane.type = lane_type_of(network, source.links.front());
    lane.type_name = lane.type == xodr::LaneType::kBus ? "bus" : "driving";
    lane.widths = width.pieces;
    for (size_t i = 0; i < stations.size(); ++i) {
      auto it = std::upper_bound(lane.widths.begin(), lane.widths.end(), stations[i],
                                 [](double s, const xodr::Poly3& p) { return s < p.s; });
      const double w =
          (it == lane.widths.begin() ? lane.widths.front() : *(it - 1)).value(stations[i]);
      const double centre_t = inner[i] - 0.5 * w;
      built.lane_error = std::max(built.lane_error, std::abs(centre_t - crossings[k][i].t));
      // Distance from the lane centre to the surveyed polyline, where the station is beside the
      // lane's own part (not its lead-in or lead-out).
      const Vec2 centre_point{ref[i].x - centre_t * std::sin(ref[i].hdg),
                              ref[i].y + centre_t * std::cos(ref[i].hdg)};
      const Projection nearest = raw[k].project(centre_point);
      const bool own_part = crossings[k][i].u >= 0.0 && crossings[k][i].u <= lines[k].length();
      if (own_part && nearest.along == 0.0) {
        built.source_error = std::max(built.source_error, nearest.distance);
      }
      inner[i] -= w;
      u_at[i] = crossings[k][i].u;
    }
    // Source links along the lane, and their speed limits (MaxSpeed km/h -> m/s; 0 = missing).
    // Link starts are arc lengths on the surveyed line: moved onto the smoothed one first.
    const double scale = raw[k].length() > 0.0 ? lines[k].length() / raw[k].length() : 1.0;
    for (size_t j = 0; j < source.links.size(); ++j) {
      BuiltRoad::Span span;
      span.link = source.links[j];
      const double guess = source.link_starts[j] * scale;
      const double start_u = j == 0 ? 0.0
                                    : lines[k]
                                          .project_within(xy(raw[k].at(source.link_starts[j])),
                                                          guess - 5.0, guess + 5.0)
                                          .u;
      span.s_start = j == 0 ? 0.0 : s_at_u(stations, u_at, start_u);
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
    section.lanes.push_back(std::move(lane));
  }
  road.lane_sections.push_back(std::move(section));
  // Elevation from the leftmost lane's heights.
  for (size_t i = 0; i < stations.size(); ++i) {
    samples[i] = {stations[i], crossings[0][i].z};
  }
  road.elevation = fit_profile(samples, options.elevation_tolerance).pieces;
  return built;
}

}  // namespace corsa::ngii::detail
