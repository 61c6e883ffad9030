// Greedy G1 fit of lines, arcs and clothoids to a polyline (OpenDRIVE 1.8 §7.4 line, §7.5 spiral,
// §7.6 arc). Each record starts at the end pose of the previous one and is grown over as many
// vertices as the tolerance allows (galloping then binary search on the last vertex); its free
// parameters (curvature, curvature rate, and the start heading for the first record) come from a
// Gauss-Newton fit of the normal distances, with the vertices re-projected on every iteration.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "clothoid.h"
#include "corsa/ngii/curve_fit.h"

namespace corsa::ngii {
namespace {

using detail::Clothoid;
using detail::ClothoidPoint;

enum class Kind { kLine, kArc, kSpiral };

struct FitPoint {
  double x = 0.0;
  double y = 0.0;
  bool added = false;    ///< a point added on a long chord, not an input vertex
  double u = 0.0;        ///< arc length along the input polyline (m)
  double heading = 0.0;  ///< direction of the data here: chord over +-kHeadingSpan (rad)
  /// Half the turn between the chords to the neighbouring points (rad): at a corner of coarsely
  /// digitised data any heading between the two chord directions is as good as the bisector.
  double heading_slack = 0.0;
};

/// Vertices closer than this (m) to the previous kept one carry no shape information (survey
/// noise at sub-metre spacing) and are thinned out before fitting.
constexpr double kMinSpacing = 1.0;
/// Half length (m) of the chord that estimates the data heading at a point (shorter in tight
/// turns, see prepare()).
constexpr double kHeadingSpan = 2.5;
/// Weight (m) of the end-heading residual: a record ending 0.01 rad off the data heading costs
/// as much as a point 2 cm off. It keeps the end state usable for the next record.
constexpr double kHeadingWeight = 2.0;
/// A record must end within this fraction of the tolerance of its last point, and within
/// kEndHeading (rad) of the data heading there.
constexpr double kEndTolerance = 0.25;
constexpr double kEndHeading = 0.02;

/// Position at arc length u of the prepared points (linear between them).
std::pair<double, double> position_at(const std::vector<FitPoint>& points, double u) {
  if (u <= 0.0) {
    return {points.front().x, points.front().y};
  }
  if (u >= points.back().u) {
    return {points.back().x, points.back().y};
  }
  const auto it = std::upper_bound(points.begin(), points.end(), u,
                                   [](double value, const FitPoint& p) { return value < p.u; });
  const FitPoint& b = *it;
  const FitPoint& a = *(it - 1);
  const double f = b.u > a.u ? (u - a.u) / (b.u - a.u) : 0.0;
  return {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)};
}

/// Thins vertices closer than kMinSpacing (keeping the last), adds points on chords longer
/// than `max_spacing`, and estimates the data heading at every point.
std::vector<FitPoint> prepare(std::span<const Point2> input, const CurveFitOptions& options) {
  const double max_spacing = options.max_spacing;
  std::vector<FitPoint> points;
  points.reserve(input.size());
  for (size_t index = 0; index < input.size(); ++index) {
    const Point2& p = input[index];
    if (!points.empty()) {
      const FitPoint last = points.back();  // a copy: the loop below grows `points`
      const double d = std::hypot(p.x - last.x, p.y - last.y);
      const bool final_vertex = index + 1 == input.size();
      if (d < 1e-4 || (d < kMinSpacing && !final_vertex)) {
        continue;
      }
      if (d < kMinSpacing && final_vertex && points.size() > 1) {
        points.pop_back();  // keep the true end point rather than a near neighbour
        const FitPoint& previous = points.back();
        points.push_back(
            {p.x, p.y, false, previous.u + std::hypot(p.x - previous.x, p.y - previous.y)});
        continue;
      }
      const int pieces = static_cast<int>(std::ceil(d / max_spacing));
      for (int k = 1; k < pieces; ++k) {
        const double f = static_cast<double>(k) / pieces;
        points.push_back(
            {last.x + f * (p.x - last.x), last.y + f * (p.y - last.y), true, last.u + f * d});
      }
      points.push_back({p.x, p.y, false, last.u + d});
    } else {
      points.push_back({p.x, p.y, false, 0.0});
    }
  }
  // The chord must be short where the line turns fast, or it no longer points along the line
  // at the curve entries: its span adapts so that it turns by about 0.15 rad at most.
  for (FitPoint& p : points) {
    const auto [ax, ay] = position_at(points, p.u - kHeadingSpan);
    const auto [mx, my] = position_at(points, p.u);
    const auto [bx, by] = position_at(points, p.u + kHeadingSpan);
    const double turn = std::abs(
        std::remainder(std::atan2(by - my, bx - mx) - std::atan2(my - ay, mx - ax), 2.0 * M_PI));
    const double span =
        turn > 0.0 ? std::clamp(0.15 * kHeadingSpan / turn, 0.5, kHeadingSpan) : kHeadingSpan;
    const auto [cx, cy] = position_at(points, p.u - span);
    const auto [dx, dy] = position_at(points, p.u + span);
    p.heading = std::atan2(dy - cy, dx - cx);
  }
  for (size_t i = 1; i + 1 < points.size(); ++i) {
    const FitPoint& a = points[i - 1];
    const FitPoint& m = points[i];
    const FitPoint& b = points[i + 1];
    points[i].heading_slack =
        0.5 * std::abs(std::remainder(
                  std::atan2(b.y - m.y, b.x - m.x) - std::atan2(m.y - a.y, m.x - a.x), 2.0 * M_PI));
  }
  if (options.end_heading && points.size() > 1) {
    points.back().heading = *options.end_heading;
  }
  return points;
}

struct Pose {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
  double kappa = 0.0;
};

struct Trial {
  bool ok = false;
  Kind kind = Kind::kLine;
  Clothoid curve;
  double length = 0.0;
  double max_error = std::numeric_limits<double>::infinity();
  double heading_error = std::numeric_limits<double>::infinity();  ///< at the end (rad)
};

/// Solves the small symmetric system a x = b (n <= 3) by Gaussian elimination with pivoting.
bool solve(double a[3][3], double b[3], int n) {
  for (int col = 0; col < n; ++col) {
    int pivot = col;
    for (int row = col + 1; row < n; ++row) {
      if (std::abs(a[row][col]) > std::abs(a[pivot][col])) {
        pivot = row;
      }
    }
    if (std::abs(a[pivot][col]) < 1e-300) {
      return false;
    }
    std::swap(a[col], a[pivot]);
    std::swap(b[col], b[pivot]);
    for (int row = col + 1; row < n; ++row) {
      const double f = a[row][col] / a[col][col];
      for (int k = col; k < n; ++k) {
        a[row][k] -= f * a[col][k];
      }
      b[row] -= f * b[col];
    }
  }
  for (int row = n - 1; row >= 0; --row) {
    for (int k = row + 1; k < n; ++k) {
      b[row] -= a[row][k] * b[k];
    }
    b[row] /= a[row][row];
  }
  return true;
}

class SegmentFitter {
 public:
  SegmentFitter(const std::vector<FitPoint>& points, const CurveFitOptions& options)
      : points_(points), options_(options) {}

  /// Fits one record of `kind` from `start` over points (i0, j]; the start heading is a free
  /// parameter when `free_heading`. `guess` seeds the curvature parameters.
  Trial fit(size_t i0, size_t j, const Pose& start, bool free_heading, Kind kind,
            const Clothoid& guess) {
    return fit_once(i0, j, start, free_heading, kind, guess, kHeadingWeight);
  }

 private:
  Trial fit_once(size_t i0, size_t j, const Pose& start, bool free_heading, Kind kind,
                 const Clothoid& guess, double heading_weight) {
    Trial trial;
    trial.kind = kind;
    Clothoid& c = trial.curve;
    c = Clothoid{start.x, start.y, start.theta, kind == Kind::kLine ? 0.0 : guess.k0,
                 kind == Kind::kSpiral ? guess.k1 : 0.0};
    const size_t n = j - i0;
    s_.resize(n);
    for (size_t i = 0; i < n; ++i) {
      s_[i] = std::max(0.0, points_[i0 + 1 + i].u - points_[i0].u);
    }
    const int params = (free_heading ? 1 : 0) + (kind == Kind::kSpiral ? 2 : kind == Kind::kArc);
    for (int iteration = 0; iteration < 6; ++iteration) {
      if (!plausible(c)) {
        return trial;  // diverged: far beyond any road curvature (and slow to integrate)
      }
      const double step = gauss_newton_step(i0, c, free_heading, kind, params, heading_weight);
      if (!std::isfinite(step)) {
        return trial;
      }
      if (step < 1e-6) {
        break;
      }
    }
    if (!plausible(c)) {
      return trial;
    }
    // Two more projections with the final parameters, then the true distances.
    reproject(i0, c);
    reproject(i0, c);
    detail::evaluate_clothoid(c, s_, eval_, false);
    double worst = 0.0;
    bool within = true;
    for (size_t i = 0; i < n; ++i) {
      const FitPoint& q = points_[i0 + 1 + i];
      const double error = std::sqrt((q.x - eval_[i].x) * (q.x - eval_[i].x) +
                                     (q.y - eval_[i].y) * (q.y - eval_[i].y));
      // Points added on long chords only keep the line from wandering: 3x the tolerance.
      within = within && error <= options_.tolerance * (q.added ? 3.0 : 1.0);
      worst = q.added ? worst : std::max(worst, error);
    }
    const FitPoint& last = points_[j];
    const double end_error = std::hypot(last.x - eval_[n - 1].x, last.y - eval_[n - 1].y);
    trial.length = s_.back();
    trial.max_error = worst;
    trial.heading_error =
        std::abs(std::remainder(last.heading - c.heading(trial.length), 2.0 * M_PI));
    const double k_end = c.curvature(trial.length);
    // The record must also end on track (position and heading), or the next one starts off;
    // the last record has no next one (and the data heading at the very end is one-sided).
    const bool final_record = j + 1 == points_.size();
    trial.ok = trial.length > 0.0 && within && end_error <= kEndTolerance * options_.tolerance &&
               (final_record
                    ? !options_.end_heading || trial.heading_error <= options_.end_heading_tolerance
                    : trial.heading_error <= kEndHeading + last.heading_slack) &&
               std::abs(c.k0) <= options_.max_curvature &&
               std::abs(k_end) <= options_.max_curvature;
    return trial;
  }

  bool plausible(const Clothoid& c) const {
    const double limit = 2.0 * options_.max_curvature;
    return std::isfinite(c.k0) && std::isfinite(c.k1) && std::isfinite(c.theta0) &&
           std::abs(c.k0) <= limit && std::abs(c.curvature(s_.back())) <= limit;
  }

  /// Re-projects the points on the current curve (one Newton step along the tangent).
  void reproject(size_t i0, const Clothoid& c) {
    detail::evaluate_clothoid(c, s_, eval_, false);
    update_s(i0);
  }

  void update_s(size_t i0) {
    double previous = 0.0;
    for (size_t i = 0; i < s_.size(); ++i) {
      const FitPoint& q = points_[i0 + 1 + i];
      const ClothoidPoint& p = eval_[i];
      const double along = (q.x - p.x) * std::cos(p.theta) + (q.y - p.y) * std::sin(p.theta);
      s_[i] = std::max(previous, s_[i] + along);
      previous = s_[i];
    }
  }

  /// One damped Gauss-Newton step on the normal residuals; returns the step size (inf on
  /// failure). Parameter order: [theta0], [k0], [k1].
  double gauss_newton_step(size_t i0, Clothoid& c, bool free_heading, Kind kind, int params,
                           double heading_weight) {
    detail::evaluate_clothoid(c, s_, eval_, params > 0);
    double jtj[3][3] = {};
    double jtr[3] = {};
    for (size_t i = 0; i < s_.size(); ++i) {
      const FitPoint& q = points_[i0 + 1 + i];
      const ClothoidPoint& p = eval_[i];
      const double nx = -std::sin(p.theta);
      const double ny = std::cos(p.theta);
      const double r = (q.x - p.x) * nx + (q.y - p.y) * ny;
      double jac[3];
      int k = 0;
      if (free_heading) {
        jac[k++] = -(nx * -(p.y - c.y0) + ny * (p.x - c.x0));
      }
      if (kind != Kind::kLine) {
        jac[k++] = -(nx * p.dx_dk0 + ny * p.dy_dk0);
      }
      if (kind == Kind::kSpiral) {
        jac[k++] = -(nx * p.dx_dk1 + ny * p.dy_dk1);
      }
      for (int a = 0; a < params; ++a) {
        jtr[a] += jac[a] * r;
        for (int b = 0; b < params; ++b) {
          jtj[a][b] += jac[a] * jac[b];
        }
      }
    }
    // End-heading residual (see kHeadingWeight).
    if (heading_weight > 0.0) {
      const FitPoint& end = points_[i0 + s_.size()];
      const double length = s_.back();
      const double r = heading_weight * std::remainder(end.heading - c.heading(length), 2.0 * M_PI);
      double jac[3];
      int k = 0;
      if (free_heading) {
        jac[k++] = -heading_weight;
      }
      if (kind != Kind::kLine) {
        jac[k++] = -heading_weight * length;
      }
      if (kind == Kind::kSpiral) {
        jac[k++] = -heading_weight * 0.5 * length * length;
      }
      for (int a = 0; a < params; ++a) {
        jtr[a] += jac[a] * r;
        for (int b = 0; b < params; ++b) {
          jtj[a][b] += jac[a] * jac[b];
        }
      }
    }
    update_s(i0);
    if (params == 0) {
      return 0.0;
    }
    for (int a = 0; a < params; ++a) {
      jtj[a][a] += 1e-9 * jtj[a][a] + 1e-18;  // Marquardt damping against rank deficiency
      jtr[a] = -jtr[a];
    }
    if (!solve(jtj, jtr, params)) {
      return std::numeric_limits<double>::infinity();
    }
    int k = 0;
    double size = 0.0;
    if (free_heading) {
      c.theta0 += jtr[k];
      size = std::max(size, std::abs(jtr[k++]));
    }
    if (kind != Kind::kLine) {
      c.k0 += jtr[k];
      size = std::max(size, std::abs(jtr[k++]) * 10.0);
    }
    if (kind == Kind::kSpiral) {
      c.k1 += jtr[k];
      size = std::max(size, std::abs(jtr[k++]) * 100.0);
    }
    return size;
  }

  const std::vector<FitPoint>& points_;
  const CurveFitOptions& options_;
  std::vector<double> s_;
  std::vector<ClothoidPoint> eval_;
};

/// Fraction of the longest feasible record that is kept (see ChainFitter::longest).
constexpr double kBackOff = 0.7;

/// Minimum number of points after the start that a kind needs to be determined (the end
/// heading adds one equation).
size_t min_points(Kind kind) { return kind == Kind::kLine ? 1 : 1; }

/// A simpler kind replaces a clothoid only if its end heading is about as good (rad).
constexpr double kHeadingSlack = 0.003;

class ChainFitter {
 public:
  ChainFitter(const std::vector<FitPoint>& points, const CurveFitOptions& options)
      : points_(points), options_(options), fitter_(points, options) {}

  CurveFit run() {
    CurveFit result;
    Pose pose{points_[0].x, points_[0].y, options_.start_heading.value_or(initial_heading()), 0.0};
    bool free_heading = !options_.start_heading;
    size_t i0 = 0;
    const size_t last = points_.size() - 1;
    while (i0 < last) {
      Trial trial = longest(i0, pose, free_heading);
      if (!trial.ok) {
        // The next vertex cannot be reached within the tolerance from this pose: the input turns
        // too sharply (two links digitised meeting at an angle). Turn along a short arc first,
        // which keeps the chain G1; only if that cannot be done within the tolerance, or does
        // not help, restart with a free heading (a kink in the chain).
        // Targets: the direction to the next point, then the start heading a free fit from
        // here would take (what the data ahead asks for).
        // A corner too sharp for an arc within max_curvature is turned on a tighter one (a
        // sharp corner, counted with the kinks) rather than with a heading jump.
        for (int attempt = 0; attempt < 6 && !trial.ok; ++attempt) {
          const bool sharp = attempt >= 2;
          const double dx = points_[i0 + 1].x - pose.x;
          const double dy = points_[i0 + 1].y - pose.y;
          double target = std::atan2(dy, dx);
          if (attempt >= 1) {
            const Trial free = longest(i0, pose, true);
            if (free.ok) {
              target = free.curve.theta0;
            }
          }
          if (turn_on_arc(result, pose, target, std::hypot(dx, dy), sharp)) {
            trial = longest(i0, pose, false);
            result.kinks += sharp && trial.ok;
          }
        }
      }
      if (!trial.ok) {
        // Last resort, still G1: aim at the next point on sharp arcs (each leaves a smaller
        // angle to it), then a record from there, or a line to that point.
        ++result.kinks;
        for (int k = 0; k < 4; ++k) {
          const double dx = points_[i0 + 1].x - pose.x;
          const double dy = points_[i0 + 1].y - pose.y;
          if (!turn_on_arc(result, pose, std::atan2(dy, dx), std::hypot(dx, dy), true)) {
            break;
          }
        }
        trial = longest(i0, pose, false);
        if (!trial.ok) {
          trial = fitter_.fit(i0, i0 + 1, pose, false, Kind::kLine, Clothoid{});
          trial_end_ = i0 + 1;
        }
      }
      append(result, trial);
      const ClothoidPoint end = detail::clothoid_at(trial.curve, trial.length);
      pose = Pose{end.x, end.y, end.theta, trial.curve.curvature(trial.length)};
      result.max_error = std::max(result.max_error, trial.max_error);
      i0 = trial_end_;
      free_heading = false;
    }
    return result;
  }

 private:
  double initial_heading() const {
    // Direction to the first point at least 1 m away (or the last point).
    for (const FitPoint& p : points_) {
      if (p.u >= 1.0) {
        return std::atan2(p.y - points_[0].y, p.x - points_[0].x);
      }
    }
    return std::atan2(points_.back().y - points_[0].y, points_.back().x - points_[0].x);
  }

  /// Appends an arc from `pose` that turns it to heading `target` and whose end lies within
  /// half the tolerance of the line through the start in the new direction (an arc of length
  /// L turning by d ends R (1 - cos d) = L (1 - cos d) / |d| off it), and no longer than half of
  /// `room` (m, the distance to the next point). Moves `pose` to the arc's end. False (nothing
  /// appended) when that arc would be tighter than max_curvature (unless `sharp`) or shorter
  /// than a millimetre.
  bool turn_on_arc(CurveFit& result, Pose& pose, double target, double room, bool sharp) const {
    const double turn = std::remainder(target - pose.theta, 2.0 * M_PI);
    if (std::abs(turn) < 1e-6) {
      return false;
    }
    // At most half the way to the next point, so that the next record still starts before it.
    const double radius =
        std::min(0.5 * options_.tolerance / (1.0 - std::cos(turn)), 0.5 * room / std::abs(turn));
    const double deviation = radius * (1.0 - std::cos(turn));
    if (!(sharp || radius * options_.max_curvature >= 1.0) || !(radius * std::abs(turn) > 1e-3)) {
      return false;
    }
    Trial arc;
    arc.ok = true;
    arc.kind = Kind::kArc;
    arc.length = radius * std::abs(turn);
    arc.curve = Clothoid{pose.x, pose.y, pose.theta, std::copysign(1.0 / radius, turn), 0.0};
    append(result, arc);
    result.max_error = std::max(result.max_error, deviation);
    const ClothoidPoint end = detail::clothoid_at(arc.curve, arc.length);
    pose = Pose{end.x, end.y, end.theta, arc.curve.k0};
    return true;
  }

  /// The longest record from (i0, pose): galloping then binary search on the end vertex with the
  /// most flexible kind, then the simplest kind that still fits that range.
  Trial longest(size_t i0, const Pose& pose, bool free_heading) {
    const size_t last = points_.size() - 1;
    Clothoid guess{pose.x, pose.y, pose.theta, pose.kappa, 0.0};
    auto attempt = [&](size_t j) {
      Trial t = fitter_.fit(i0, j, pose, free_heading, Kind::kSpiral, guess);
      if (t.ok) {
        guess = t.curve;
      }
      return t;
    };
    Trial best = attempt(i0 + 1);
    if (!best.ok) {
      Trial line = fitter_.fit(i0, i0 + 1, pose, free_heading, Kind::kLine, guess);
      trial_end_ = i0 + 1;
      return line;
    }
    size_t good = i0 + 1;
    size_t bad = last + 1;
    for (size_t span = 2; good < last;) {
      const size_t j = std::min(last, i0 + span);
      Trial t = attempt(j);
      if (!t.ok) {
        bad = j;
        break;
      }
      best = t;
      good = j;
      span *= 2;
    }
    while (bad - good > 1) {
      const size_t j = good + (bad - good) / 2;
      Trial t = attempt(j);
      if (t.ok) {
        best = t;
        good = j;
      } else {
        bad = j;
      }
    }
    // A record fitted up to the edge of the tolerance ends with a poor heading, which would
    // cripple the next one; ending it earlier, where the least-squares fit is best, keeps the
    // chain smooth at the cost of a few more records.
    if (good < last) {
      const double target = points_[i0].u + kBackOff * (points_[good].u - points_[i0].u);
      size_t cut = good;
      while (cut > i0 + 1 && points_[cut - 1].u >= target) {
        --cut;
      }
      if (cut != good) {
        Trial shorter = attempt(cut);
        if (shorter.ok) {
          best = shorter;
          good = cut;
        }
      }
    }
    trial_end_ = good;
    // Prefer the simplest kind that covers the same vertices.
    for (Kind kind : {Kind::kLine, Kind::kArc}) {
      if (kind == best.kind || good - i0 < min_points(kind)) {
        continue;
      }
      Trial simple = fitter_.fit(i0, good, pose, free_heading, kind, best.curve);
      if (simple.ok && simple.heading_error <= best.heading_error + kHeadingSlack) {
        return simple;
      }
      if (kind == Kind::kArc) {
        break;
      }
    }
    return best;
  }

  void append(CurveFit& result, const Trial& trial) const {
    if (trial.length <= 1e-9) {
      return;
    }
    xodr::Geometry g;
    g.s = result.length;
    g.x = trial.curve.x0;
    g.y = trial.curve.y0;
    g.hdg = std::remainder(trial.curve.theta0, 2.0 * M_PI);
    g.length = trial.length;
    switch (trial.kind) {
      case Kind::kLine:
        g.shape = xodr::LineGeometry{};
        break;
      case Kind::kArc:
        g.shape = xodr::ArcGeometry{trial.curve.k0};
        break;
      case Kind::kSpiral:
        g.shape = xodr::SpiralGeometry{trial.curve.k0, trial.curve.curvature(trial.length)};
        break;
    }
    result.length += trial.length;
    result.geometries.push_back(g);
  }

  const std::vector<FitPoint>& points_;
  const CurveFitOptions& options_;
  SegmentFitter fitter_;
  size_t trial_end_ = 0;
};

}  // namespace

CurveFit fit_plan_view(std::span<const Point2> input, const CurveFitOptions& options) {
  const std::vector<FitPoint> points = prepare(input, options);
  if (points.size() < 2) {
    return {};  // nothing to fit: all vertices coincide
  }
  return ChainFitter(points, options).run();
}

}  // namespace corsa::ngii
