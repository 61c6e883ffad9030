#include "positions/trajectory_path.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "corsa/core/vec.h"
#include "corsa/xodr/geometry.h"
#include "geometry/angle.h"
#include "positions/position_common.h"
#include "state/lenient.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

void TrajectoryPath::add(Segment segment) {
  segment.s0 = length_;
  length_ += segment.length;
  segments_.push_back(segment);
}

PathPoint TrajectoryPath::at(double s) const {
  if (segments_.empty()) {
    return {};
  }
  s = std::clamp(s, 0.0, length_);
  const auto it = std::upper_bound(segments_.begin(), segments_.end(), s,
                                   [](double value, const Segment& seg) { return value < seg.s0; });
  const Segment& seg = *(it == segments_.begin() ? it : it - 1);
  const double ds = std::min(s - seg.s0, seg.length);
  if (!seg.clothoid) {
    const double w = seg.length > 0.0 ? ds / seg.length : 0.0;
    return {seg.x + std::cos(seg.h) * ds, seg.y + std::sin(seg.h) * ds,
            seg.z + w * (seg.z_end - seg.z), seg.h};
  }
  xodr::Geometry geometry;
  geometry.x = seg.x;
  geometry.y = seg.y;
  geometry.hdg = seg.h;
  geometry.length = seg.length;
  geometry.shape = xodr::SpiralGeometry{seg.curvature_start, seg.curvature_end};
  const xodr::RefPoint p = xodr::evaluate_geometry(geometry, ds);
  return {p.x, p.y, seg.z, p.hdg};
}

void TrajectoryPath::add_time(double s, double time) {
  if (!timeline_.empty() && (s < timeline_.back().first || time <= timeline_.back().second)) {
    return;
  }
  timeline_.emplace_back(s, time);
}

void TrajectoryPath::add_vertex(double s, std::optional<double> heading) {
  vertices_.emplace_back(s, heading);
}

size_t TrajectoryPath::vertex_index_at(double s) const {
  const auto after =
      std::upper_bound(vertices_.begin(), vertices_.end(), s + 1e-9,
                       [](double value, const std::pair<double, std::optional<double>>& v) {
                         return value < v.first;
                       });
  return after == vertices_.begin() ? 0 : static_cast<size_t>(after - vertices_.begin()) - 1;
}

std::optional<double> TrajectoryPath::stated_heading_at(double s) const {
  if (vertices_.empty() || s + 1e-9 < vertices_.front().first) {
    return std::nullopt;
  }
  return vertices_[vertex_index_at(s)].second;
}

namespace {

// Linear interpolation in a table of increasing (key, value) pairs read as `from` -> `to`.
template <typename From, typename To>
double interpolate(const std::vector<std::pair<double, double>>& table, double key, From from,
                   To to) {
  if (key <= from(table.front())) {
    return to(table.front());
  }
  for (size_t i = 1; i < table.size(); ++i) {
    if (key <= from(table[i])) {
      const double k0 = from(table[i - 1]), k1 = from(table[i]);
      const double w = k1 > k0 ? (key - k0) / (k1 - k0) : 1.0;
      return to(table[i - 1]) + w * (to(table[i]) - to(table[i - 1]));
    }
  }
  return to(table.back());
}

}  // namespace

double TrajectoryPath::s_at_time(double time) const {
  return interpolate(
      timeline_, time, [](const auto& e) { return e.second; },
      [](const auto& e) { return e.first; });
}

double TrajectoryPath::time_at_s(double s) const {
  return interpolate(
      timeline_, s, [](const auto& e) { return e.first; }, [](const auto& e) { return e.second; });
}

namespace {

void add_polyline(TrajectoryPath& path, const std::vector<Vec3>& points) {
  for (size_t i = 1; i < points.size(); ++i) {
    const Vec3& a = points[i - 1];
    const Vec3& b = points[i];
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    if (length <= 0.0) {
      continue;
    }
    TrajectoryPath::Segment seg;
    seg.length = length;
    seg.x = a.x;
    seg.y = a.y;
    seg.z = a.z;
    seg.z_end = b.z;
    seg.h = std::atan2(b.y - a.y, b.x - a.x);
    path.add(seg);
  }
}

Vec3 point_of(const xosc::Position& position, const SimState& state, std::optional<uint32_t> self) {
  const ResolvedPosition at = resolve_position(position, state, self);
  return {at.pose.x, at.pose.y, at.pose.z};
}

// True if the position gives a heading of its own (a WorldPosition's h, an Orientation's h).
bool position_states_heading(const xosc::Position& position) {
  return std::visit(
      [](const auto& kind) {
        using T = std::decay_t<decltype(kind)>;
        if constexpr (std::is_same_v<T, xosc::WorldPosition>) {
          return kind.h.has_value();
        } else if constexpr (requires { kind.orientation; }) {
          return kind.orientation.has_value() && kind.orientation->h.has_value();
        } else {
          return false;
        }
      },
      position.kind);
}

void build_polyline(TrajectoryPath& path, const xosc::Polyline& shape, const SimState& state,
                    std::optional<uint32_t> self) {
  std::vector<Vec3> points;
  std::vector<std::optional<double>> headings;
  for (const xosc::Vertex& vertex : shape.vertices) {
    const ResolvedPosition at = resolve_position(vertex.position, state, self);
    points.push_back({at.pose.x, at.pose.y, at.pose.z});
    headings.push_back(position_states_heading(vertex.position) ? std::optional(at.pose.h)
                                                                : std::nullopt);
  }
  add_polyline(path, points);
  double s = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    if (i > 0) {
      s += std::hypot(points[i].x - points[i - 1].x, points[i].y - points[i - 1].y);
    }
    path.add_vertex(s, headings[i]);
    if (shape.vertices[i].time) {
      path.add_time(s, *shape.vertices[i].time);
    }
  }
}

void build_clothoid(TrajectoryPath& path, const xosc::Clothoid& shape, const SimState& state,
                    std::optional<uint32_t> self) {
  const ResolvedPosition start = resolve_position(shape.position, state, self);
  TrajectoryPath::Segment seg;
  seg.clothoid = true;
  seg.length = shape.length;
  seg.x = start.pose.x;
  seg.y = start.pose.y;
  seg.z = start.pose.z;
  seg.h = start.pose.h;
  seg.curvature_start = shape.curvature;
  seg.curvature_end = shape.curvature + shape.curvature_prime.value_or(0.0) * shape.length;
  path.add(seg);
  if (shape.start_time && shape.stop_time) {
    path.add_time(0.0, *shape.start_time);
    path.add_time(shape.length, *shape.stop_time);
  }
}

void build_clothoid_spline(TrajectoryPath& path, const xosc::ClothoidSpline& shape,
                           const SimState& state, std::optional<uint32_t> self) {
  PathPoint cursor;
  bool have_cursor = false;
  for (const xosc::ClothoidSplineSegment& segment : shape.segments) {
    if (segment.position_start) {
      const ResolvedPosition start = resolve_position(*segment.position_start, state, self);
      cursor = {start.pose.x, start.pose.y, start.pose.z, start.pose.h};
      have_cursor = true;
    } else if (!have_cursor) {
      // The first segment needs a PositionStart (1.3 ClothoidSplineSegment); without one the
      // spline clearly continues from where the entity following it stands.
      if (!self || !state.world.entities[*self].state().placed) {
        fail(segment.source, "the first ClothoidSplineSegment needs a PositionStart");
      }
      lenient(state, segment.source, "the first ClothoidSplineSegment has no PositionStart",
              "a start at the entity following it");
      const auto& pose = state.world.entities[*self].state().pose;
      cursor = {pose.x, pose.y, pose.z, pose.h};
      have_cursor = true;
    }
    TrajectoryPath::Segment seg;
    seg.clothoid = true;
    seg.length = segment.length;
    seg.x = cursor.x;
    seg.y = cursor.y;
    seg.z = cursor.z;
    seg.h = cursor.h + segment.h_offset.value_or(0.0);
    seg.curvature_start = segment.curvature_start;
    seg.curvature_end = segment.curvature_end;
    if (segment.time_start) {
      path.add_time(path.length(), *segment.time_start);
    }
    path.add(seg);
    cursor = path.at(path.length());
  }
  if (shape.time_end) {
    path.add_time(path.length(), *shape.time_end);
  }
}

// Rational B-spline point at parameter u by de Boor's algorithm in homogeneous coordinates.
Vec3 nurbs_point(const std::vector<Vec3>& points, const std::vector<double>& weights,
                 const std::vector<double>& knots, int degree, double u) {
  const int n = static_cast<int>(points.size());
  int span = degree;
  while (span < n - 1 && u >= knots[span + 1]) {
    ++span;
  }
  double d[16][4];
  for (int j = 0; j <= degree; ++j) {
    const int i = j + span - degree;
    const double w = weights[i];
    d[j][0] = points[i].x * w;
    d[j][1] = points[i].y * w;
    d[j][2] = points[i].z * w;
    d[j][3] = w;
  }
  for (int r = 1; r <= degree; ++r) {
    for (int j = degree; j >= r; --j) {
      const double lo = knots[j + span - degree];
      const double hi = knots[j + 1 + span - r];
      const double alpha = hi > lo ? (u - lo) / (hi - lo) : 0.0;
      for (int k = 0; k < 4; ++k) {
        d[j][k] = (1.0 - alpha) * d[j - 1][k] + alpha * d[j][k];
      }
    }
  }
  const double w = d[degree][3] != 0.0 ? d[degree][3] : 1.0;
  return {d[degree][0] / w, d[degree][1] / w, d[degree][2] / w};
}

// A NURBS sampled uniformly in u from u0 to u1: sample i at u0 + (u1 - u0) i / (s.size() - 1),
// s its arc length (m) along the samples.
struct NurbsSamples {
  const std::vector<Vec3>& points;
  const std::vector<double>& weights;
  int degree = 0;
  double u0 = 0.0;
  double u1 = 0.0;
  std::vector<double> s;

  /// Arc length (m) at parameter u, interpolated between the samples.
  double s_at(double u) const {
    const size_t last = s.size() - 1;
    const double x =
        u1 > u0 ? std::clamp((u - u0) / (u1 - u0), 0.0, 1.0) * static_cast<double>(last) : 0.0;
    const size_t lo = std::min(static_cast<size_t>(x), last - 1);
    return s[lo] + (x - static_cast<double>(lo)) * (s[lo + 1] - s[lo]);
  }
};

std::vector<double> sample_lengths(const std::vector<Vec3>& polyline) {
  std::vector<double> s(polyline.size(), 0.0);
  for (size_t i = 1; i < polyline.size(); ++i) {
    s[i] =
        s[i - 1] + std::hypot(polyline[i].x - polyline[i - 1].x, polyline[i].y - polyline[i - 1].y);
  }
  return s;
}

// Some control points without a time: each time is put where its point has most influence, its
// Greville abscissa (the mean of its `degree` inner knots), and interpolated in arc length.
void add_greville_times(TrajectoryPath& path, const xosc::Nurbs& shape,
                        const NurbsSamples& sampled) {
  for (size_t i = 0; i < shape.control_points.size(); ++i) {
    if (!shape.control_points[i].time) {
      continue;
    }
    double greville = 0.0;
    for (int k = 1; k <= sampled.degree; ++k) {
      greville += shape.knots[i + k];
    }
    path.add_time(sampled.s_at(greville / sampled.degree), *shape.control_points[i].time);
  }
}

// esmini's timing of a NURBS (its NurbsShape::CalculatePolyLine): the curve is sampled at
// 1 + (control polygon length in m) even steps of u from 0 to the last knot; each control
// point's time belongs to the sample where its (non-rational) basis function peaks, and the
// time goes linearly in u from one such peak to the next (beyond the last two, on the same
// line).
void add_esmini_nurbs_times(TrajectoryPath& path, const xosc::Nurbs& shape,
                            const NurbsSamples& sampled) {
  const size_t n = sampled.points.size();
  double polygon = 0.0;
  for (size_t i = 1; i < n; ++i) {
    polygon += std::hypot(sampled.points[i].x - sampled.points[i - 1].x,
                          sampled.points[i].y - sampled.points[i - 1].y);
  }
  const int steps = static_cast<int>(1.0 + polygon);
  const double step = shape.knots.back() / steps;
  std::vector<Vec3> unit(n, Vec3{0.0, 0.0, 0.0});
  const std::vector<double> ones(n, 1.0);
  std::vector<double> peak(n, 0.0);
  std::vector<double> peak_value(n, 0.0);
  for (int i = 0; i <= steps; ++i) {
    const double u = i * step;
    const double clamped = std::clamp(u, sampled.u0, sampled.u1 - 1e-10);
    for (size_t j = 0; j < n; ++j) {
      unit[j].x = 1.0;
      const double basis = nurbs_point(unit, ones, shape.knots, sampled.degree, clamped).x;
      unit[j].x = 0.0;
      if (basis > peak_value[j]) {
        peak_value[j] = basis;
        peak[j] = u;
      }
    }
  }
  size_t current = 0;
  for (int i = 0; i <= steps; ++i) {
    const double u = i * step;
    if (u >= peak[current + 1]) {
      current = std::min(current + 1, n - 2);
    }
    const double span = peak[current + 1] - peak[current];
    const double w = span > 0.0 ? (u - peak[current]) / span : 1.0;
    const double t0 = *shape.control_points[current].time;
    const double t1 = *shape.control_points[current + 1].time;
    path.add_time(sampled.s_at(u), t0 + w * (t1 - t0));
  }
}

void build_nurbs(TrajectoryPath& path, const xosc::Nurbs& shape, const SimState& state,
                 std::optional<uint32_t> self) {
  const size_t n = shape.control_points.size();
  const int order = static_cast<int>(shape.order);
  if (order < 2 || order > 16 || n < static_cast<size_t>(order)) {
    fail(shape.source, "Nurbs of order " + std::to_string(order) +
                           " needs at least that many "
                           "control points (and an order of 2 to 16)");
  }
  if (shape.knots.size() != n + static_cast<size_t>(order)) {
    fail(shape.source, "Nurbs has " + std::to_string(shape.knots.size()) + " knots; " +
                           std::to_string(n + order) + " expected (control points + order)");
  }
  std::vector<Vec3> points;
  std::vector<double> weights;
  for (const xosc::ControlPoint& cp : shape.control_points) {
    points.push_back(point_of(cp.position, state, self));
    weights.push_back(cp.weight.value_or(1.0));
  }
  const int degree = order - 1;
  const double u0 = shape.knots[degree];
  const double u1 = shape.knots[n];
  // 32 samples per control point: chord errors far below a centimetre on vehicle-scale curves.
  const size_t samples = 32 * n;
  std::vector<Vec3> polyline;
  for (size_t i = 0; i <= samples; ++i) {
    const double u = u0 + (u1 - u0) * static_cast<double>(i) / static_cast<double>(samples);
    polyline.push_back(nurbs_point(points, weights, shape.knots, degree, std::min(u, u1)));
  }
  add_polyline(path, polyline);
  const bool all_timed =
      std::all_of(shape.control_points.begin(), shape.control_points.end(),
                  [](const xosc::ControlPoint& cp) { return cp.time.has_value(); });
  const NurbsSamples sampled{points, weights, degree, u0, u1, sample_lengths(polyline)};
  if (all_timed && state.options.semantics == Semantics::kEsmini) {
    add_esmini_nurbs_times(path, shape, sampled);
  } else if (all_timed) {
    // OpenSCENARIO 1.3 ControlPoint: time is "the time dimension of the control point", so the
    // curve is four-dimensional: its time at u is the same rational B-spline of the control
    // points' times as its position is of their positions.
    std::vector<Vec3> times;
    for (const xosc::ControlPoint& cp : shape.control_points) {
      times.push_back({*cp.time, 0.0, 0.0});
    }
    for (size_t i = 0; i < polyline.size(); ++i) {
      const double u = u0 + (u1 - u0) * static_cast<double>(i) / static_cast<double>(samples);
      path.add_time(sampled.s[i],
                    nurbs_point(times, weights, shape.knots, degree, std::min(u, u1)).x);
    }
  } else {
    add_greville_times(path, shape, sampled);
  }
}

}  // namespace

bool states_times(const xosc::Trajectory& trajectory) {
  const size_t times = std::visit(
      [](const auto& shape) -> size_t {
        using T = std::decay_t<decltype(shape)>;
        if constexpr (std::is_same_v<T, xosc::Polyline>) {
          return std::ranges::count_if(shape.vertices,
                                       [](const auto& v) { return v.time.has_value(); });
        } else if constexpr (std::is_same_v<T, xosc::Clothoid>) {
          return shape.start_time && shape.stop_time ? 2 : 0;
        } else if constexpr (std::is_same_v<T, xosc::ClothoidSpline>) {
          return std::ranges::count_if(shape.segments,
                                       [](const auto& seg) { return seg.time_start.has_value(); }) +
                 (shape.time_end ? 1 : 0);
        } else {
          return std::ranges::count_if(shape.control_points,
                                       [](const auto& cp) { return cp.time.has_value(); });
        }
      },
      trajectory.shape);
  return times >= 2;
}

TrajectoryPath build_trajectory_path(const xosc::Trajectory& trajectory, const SimState& state,
                                     std::optional<uint32_t> self) {
  TrajectoryPath path;
  std::visit(
      [&](const auto& shape) {
        using T = std::decay_t<decltype(shape)>;
        if constexpr (std::is_same_v<T, xosc::Polyline>) {
          build_polyline(path, shape, state, self);
        } else if constexpr (std::is_same_v<T, xosc::Clothoid>) {
          build_clothoid(path, shape, state, self);
        } else if constexpr (std::is_same_v<T, xosc::ClothoidSpline>) {
          build_clothoid_spline(path, shape, state, self);
        } else {
          build_nurbs(path, shape, state, self);
        }
      },
      trajectory.shape);
  if (path.empty()) {
    fail(trajectory.source, "trajectory '" + trajectory.name + "' has no length");
  }
  return path;
}

ResolvedPosition resolve_trajectory_position(const xosc::TrajectoryPosition& position,
                                             const SimState& state, std::optional<uint32_t> self) {
  if (!position.trajectory) {
    fail(position.source, "TrajectoryPosition without a trajectory");
  }
  const TrajectoryPath path = build_trajectory_path(*position.trajectory, state, self);
  const PathPoint p = path.at(position.s);
  const double t = position.t.value_or(0.0);
  ResolvedPosition out;
  out.pose.x = p.x - std::sin(p.h) * t;
  out.pose.y = p.y + std::cos(p.h) * t;
  out.pose.z = p.z;
  out.pose.h = p.h;
  if (position.orientation) {
    if (position.orientation->type == xosc::ReferenceContext::kRelative) {
      out.pose.h = wrap_angle(p.h + position.orientation->h.value_or(0.0));
    } else {
      out.pose.h = position.orientation->h.value_or(0.0);
    }
    out.pose.p = position.orientation->p.value_or(0.0);
    out.pose.r = position.orientation->r.value_or(0.0);
  }
  if (state.map != nullptr) {
    out.road = locate_point(*state.map, out.pose.x, out.pose.y, 0.0);
  }
  return out;
}

}  // namespace corsa::engine::detail
