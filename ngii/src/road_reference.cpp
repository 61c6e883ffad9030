#include "road_reference.h"

#include <algorithm>
#include <cmath>
#include <variant>

namespace corsa::ngii::detail {
namespace {

constexpr double kMinShiftRadius = 1.5;     // m: tightest radius of the shifted reference line
constexpr double kEase = 12.0;              // m over which a reduced shift is eased in and out
constexpr double kEndLineTolerance = 0.25;  // m: lane ends farther from one line: no line
constexpr double kMaxSkew = 50.0 * M_PI / 180.0;
constexpr double kMinSkew = 0.2 * M_PI / 180.0;
// Right turns (towards the lanes) tighter than the road is wide (plus kFoldClearance) are
// smoothed over +-kRelaxReach, at most kRelaxRounds times; curvature from chords of kRelaxChord.
constexpr double kRelaxReach = 2.0;  // m
constexpr double kRelaxChord = 1.0;  // m
constexpr int kRelaxRounds = 20;
// Length (m) of the chords a road end's tangent is extrapolated from (shifted_left).
constexpr double kEndChord = 1.5;
// rad: how far a one-lane road must turn right overall to be fitted along its right edge.
constexpr double kInsideTurn = 0.5;

Vec2 to_vec(const Point2& p) { return {p.x, p.y}; }

std::vector<double> arc_lengths(const std::vector<Point2>& p) {
  std::vector<double> u(p.size(), 0.0);
  for (size_t i = 1; i < p.size(); ++i) {
    u[i] = u[i - 1] + norm(to_vec(p[i]) - to_vec(p[i - 1]));
  }
  return u;
}

/// Point of `q` at arc length `where` by the stations `u` (clamped), linear between vertices.
Vec2 point_at(const std::vector<Point2>& q, const std::vector<double>& u, double where) {
  where = std::clamp(where, 0.0, u.back());
  const size_t i = static_cast<size_t>(std::upper_bound(u.begin(), u.end(), where) - u.begin());
  if (i >= q.size()) {
    return to_vec(q.back());
  }
  const double f = u[i] > u[i - 1] ? (where - u[i - 1]) / (u[i] - u[i - 1]) : 0.0;
  return to_vec(q[i - 1]) + f * (to_vec(q[i]) - to_vec(q[i - 1]));
}

/// A Gaussian average along `p` (sigma kRelaxChord, stations `u`) of the vertices within
/// kRelaxReach of the arc lengths `tight`; eased in from nothing at kRelaxReach from an end to
/// all of it at twice that (the ends and their headings stay: the normals there run through
/// the lane ends).
void ease_at(std::vector<Point2>& p, const std::vector<double>& u,
             const std::vector<double>& tight) {
  const size_t n = p.size();
  std::vector<Point2> next(p);
  for (size_t i = 1; i + 1 < n; ++i) {
    const bool near_end = u[i] < kRelaxReach || u[i] > u.back() - kRelaxReach;
    const bool near = std::any_of(tight.begin(), tight.end(),
                                  [&](double t) { return std::abs(u[i] - t) <= kRelaxReach; });
    if (near_end || !near) {
      continue;
    }
    Vec2 sum{0.0, 0.0};
    double weight = 0.0;
    for (double d = -3.0 * kRelaxChord; d <= 3.0 * kRelaxChord + 1e-9; d += 0.25) {
      const double w = std::exp(-0.5 * d * d / (kRelaxChord * kRelaxChord));
      sum = sum + w * point_at(p, u, u[i] + d);
      weight += w;
    }
    const double from_end = std::min(u[i], u.back() - u[i]);
    const double f = std::clamp(from_end / kRelaxReach - 1.0, 0.0, 1.0);
    next[i] =
        Point2{p[i].x + f * (sum.x / weight - p[i].x), p[i].y + f * (sum.y / weight - p[i].y)};
  }
  p = std::move(next);
}

double polyline_length(const std::vector<Point2>& p) {
  double total = 0.0;
  for (size_t i = 1; i < p.size(); ++i) {
    total += norm(to_vec(p[i]) - to_vec(p[i - 1]));
  }
  return total;
}

/// The direction of travel at the end of `p` (over its last metre or so), or nothing.
std::optional<Vec2> end_direction(const std::vector<Point2>& p) {
  const size_t n = p.size();
  if (n < 2) {
    return std::nullopt;
  }
  const Vec2 last = to_vec(p[n - 1]);
  size_t back = n - 2;
  while (back > 0 && norm(last - to_vec(p[back])) < 1.0) {
    --back;
  }
  const Vec2 forward = last - to_vec(p[back]);
  if (norm(forward) < 1e-9) {
    return std::nullopt;
  }
  return (1.0 / norm(forward)) * forward;
}

/// Signed angle (rad) from the direction of travel to the square of `line` (its normal
/// pointing forward); 0 when the end is already square or past kMaxSkew (left alone).
double skew_of(const std::vector<Point2>& p, const EndLine& line) {
  const auto forward = end_direction(p);
  if (!forward) {
    return 0.0;
  }
  Vec2 square{line.across.y, -line.across.x};
  if (dot(square, *forward) < 0.0) {
    square = -1.0 * square;
  }
  const double skew = std::atan2(cross(*forward, square), dot(*forward, square));
  return std::abs(skew) < kMinSkew || std::abs(skew) > kMaxSkew ? 0.0 : skew;
}

/// Where the reference line must end to meet an end line turned by `skew` from the direction
/// of travel, through `anchor` (the reference lane's end): the point on the line of travel
/// through the end of `p`, and the heading there (square to the end line).
struct EndTarget {
  Vec2 point;
  Vec2 square;
};

std::optional<EndTarget> end_target(const std::vector<Point2>& p, double skew, Vec2 anchor) {
  const auto forward = end_direction(p);
  if (!forward) {
    return std::nullopt;
  }
  const Vec2 last = to_vec(p.back());
  const Vec2 square{std::cos(skew) * forward->x - std::sin(skew) * forward->y,
                    std::sin(skew) * forward->x + std::cos(skew) * forward->y};
  const Vec2 across{square.y, -square.x};
  const double denominator = cross(across, *forward);
  if (std::abs(denominator) < 1e-9) {
    return std::nullopt;
  }
  return EndTarget{anchor + (cross(last - anchor, *forward) / denominator) * across, square};
}

/// Cubic Hermite points from `a` (heading `ta`) to `b` (heading `tb`), every half metre or so,
/// `a` left out.
std::vector<Point2> hermite(Vec2 a, Vec2 ta, Vec2 b, Vec2 tb) {
  const double chord = norm(b - a);
  const int steps = std::max(4, static_cast<int>(std::ceil(chord / 0.5)));
  std::vector<Point2> out;
  for (int k = 1; k <= steps; ++k) {
    const double f = static_cast<double>(k) / steps;
    const double h00 = 2 * f * f * f - 3 * f * f + 1, h10 = f * f * f - 2 * f * f + f;
    const double h01 = -2 * f * f * f + 3 * f * f, h11 = f * f * f - f * f;
    const Vec2 q = h00 * a + (h10 * chord) * ta + h01 * b + (h11 * chord) * tb;
    out.push_back(Point2{q.x, q.y});
  }
  return out;
}

/// Where on the end line through `target` a turn from `start` (heading `heading`) ends when it
/// turns evenly, like an arc: the chord halves the turn. An arc spreads the turn over the whole
/// reach (curvature turn / reach), where a curve back to the line of travel (an S) turns up to
/// four times as tightly at its end and folds the lanes on its inside. The laneOffset takes up
/// the arc's sideways drift (§9.3). `target.point` when the chord does not meet the line ahead,
/// and for bends shorter than kMinEvenTurn (a road of a few metres: its plan view could not
/// follow the drift within the fit tolerance, and its lanes' ends would move) unless it hardly
/// turns (under kStraightTurn): a piece of a metre between two parallel skewed lines (a road
/// cut where one lane ends short of the others' stop line) then runs straight from line to line,
/// where a curve to the line of travel would swing by twice the skew and fold its lanes.
constexpr double kMinEvenTurn = 4.0;   // m
constexpr double kStraightTurn = 0.05;  // rad
Vec2 even_turn_end(Vec2 start, Vec2 heading, const EndTarget& target) {
  const double turn = std::atan2(cross(heading, target.square), dot(heading, target.square));
  if (norm(target.point - start) < kMinEvenTurn && std::abs(turn) >= kStraightTurn) {
    return target.point;
  }
  const double half = 0.5 * turn;
  const Vec2 chord{std::cos(half) * heading.x - std::sin(half) * heading.y,
                   std::sin(half) * heading.x + std::cos(half) * heading.y};
  const Vec2 across{target.square.y, -target.square.x};
  const double denominator = cross(chord, across);
  if (std::abs(denominator) < 1e-9) {
    return target.point;
  }
  const double along = cross(target.point - start, across) / denominator;
  return along > 0.5 ? start + along * chord : target.point;
}

/// Bends the end of `p` over its last `reach` metres: a cubic Hermite curve turning evenly to
/// the end line, arriving square to it. Returns the new end heading.
std::optional<double> bend_end(std::vector<Point2>& p, const EndTarget& target, double reach) {
  double walked = 0.0;
  size_t i = p.size() - 1;
  while (i > 0 && walked + norm(to_vec(p[i]) - to_vec(p[i - 1])) < reach) {
    walked += norm(to_vec(p[i]) - to_vec(p[i - 1]));
    --i;
  }
  if (i + 1 >= p.size()) {
    return std::nullopt;
  }
  const Vec2 start = to_vec(p[i]);
  size_t j = i;
  while (j > 0 && norm(start - to_vec(p[j - 1])) < 1.0) {
    --j;
  }
  Vec2 heading = j < i ? start - to_vec(p[j]) : to_vec(p[i + 1]) - start;
  heading = norm(heading) > 1e-9 ? (1.0 / norm(heading)) * heading : target.square;
  p.resize(i + 1);
  const std::vector<Point2> tail =
      hermite(start, heading, even_turn_end(start, heading, target), target.square);
  p.insert(p.end(), tail.begin(), tail.end());
  return std::atan2(target.square.y, target.square.x);
}

/// How far (m) before an end a turn by `skew` must begin so that lanes up to `road_width` away
/// do not fold (their normals must not cross: turn rate * width well below 1); and the turn
/// that fits into `room` metres.
constexpr double kFoldMargin = 2.0;
double reach_for(double skew, double road_width) {
  return std::max(8.0, kFoldMargin * road_width * std::tan(std::abs(skew)));
}
double skew_within(double skew, double road_width, double room) {
  const double most = std::atan(room / (kFoldMargin * std::max(road_width, 1e-3)));
  return std::copysign(std::min(std::abs(skew), most), skew);
}

}  // namespace

namespace {

/// The principal line of `points` (their mean and main direction, oriented first to last).
EndLine principal_line(const std::vector<Vec2>& points) {
  Vec2 mean{0.0, 0.0};
  for (const Vec2& e : points) {
    mean = mean + (1.0 / static_cast<double>(points.size())) * e;
  }
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (const Vec2& e : points) {
    const Vec2 d = e - mean;
    sxx += d.x * d.x;
    sxy += d.x * d.y;
    syy += d.y * d.y;
  }
  const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  Vec2 across{std::cos(angle), std::sin(angle)};
  if (dot(across, points.back() - points.front()) < 0.0) {
    across = -1.0 * across;
  }
  return EndLine{mean, across};
}

}  // namespace

std::optional<EndLine> end_line(std::vector<Vec2> ends) {
  // The line through the most lane ends (within kEndLineTolerance), tried through every pair,
  // then refitted through those ends: a lane ending elsewhere keeps its gap, the others none.
  if (ends.size() < 2) {
    return std::nullopt;
  }
  std::vector<Vec2> best;
  double best_spread = 0.0;
  for (size_t i = 0; i < ends.size(); ++i) {
    for (size_t j = i + 1; j < ends.size(); ++j) {
      const Vec2 d = ends[j] - ends[i];
      if (norm(d) < 1.0) {
        continue;  // lane ends on top of each other: no direction to follow
      }
      const Vec2 across = (1.0 / norm(d)) * d;
      std::vector<Vec2> inliers;
      for (const Vec2& e : ends) {
        if (std::abs(cross(across, e - ends[i])) <= kEndLineTolerance) {
          inliers.push_back(e);
        }
      }
      const double spread = norm(inliers.back() - inliers.front());
      if (inliers.size() > best.size() || (inliers.size() == best.size() && spread > best_spread)) {
        best = std::move(inliers);
        best_spread = spread;
      }
    }
  }
  if (best.size() < 2) {
    return std::nullopt;
  }
  return principal_line(best);
}

bool on_end_line(const EndLine& line, Vec2 p) {
  return std::abs(cross(line.across, p - line.point)) <= kEndLineTolerance;
}

/// How much of a circle's end tangent extrapolation applies at the start (or `at_end`) of the
/// vertices `p`: 1 unless the first segment is at least kEndChord long and the corner at its far
/// vertex is smaller than the next one (2 r - 1 for the ratio r of the two corners: 1 on a
/// circle, 0 where a straight segment runs into an evenly turning one).
double circle_share(const std::vector<Point3>& p, bool at_end) {
  const size_t n = p.size();
  if (n < 4) {
    return 1.0;
  }
  const auto at = [&](size_t i) { return xy(p[at_end ? n - 1 - i : i]); };
  if (norm(at(1) - at(0)) < kEndChord) {
    return 1.0;
  }
  const auto heading = [&](size_t i) {
    const Vec2 d = at(i + 1) - at(i);
    return std::atan2(d.y, d.x);
  };
  const double c1 = angle_diff(heading(1), heading(0));
  const double c2 = angle_diff(heading(2), heading(1));
  if (std::abs(c2) < 1e-3) {
    return 1.0;
  }
  return std::clamp(2.0 * c1 / c2 - 1.0, 0.0, 1.0);
}

bool along_right_edge(const Polyline& lane) {
  const auto& p = lane.points();
  double turn = 0.0;
  for (size_t i = 2; i < p.size(); ++i) {
    const double h0 = std::atan2(p[i - 1].y - p[i - 2].y, p[i - 1].x - p[i - 2].x);
    const double h1 = std::atan2(p[i].y - p[i - 1].y, p[i].x - p[i - 1].x);
    turn += angle_diff(h1, h0);
  }
  if (turn > -kInsideTurn) {
    return false;
  }
  for (size_t i = 0; i < p.size(); ++i) {
    const double u = lane.u()[i];
    const Vec2 back = xy(lane.at(u)) - xy(lane.at(u - 1.0));
    const Vec2 ahead = xy(lane.at(u + 1.0)) - xy(lane.at(u));
    if (norm(back) < 1e-9 || norm(ahead) < 1e-9) {
      continue;
    }
    const double bend = angle_diff(std::atan2(ahead.y, ahead.x), std::atan2(back.y, back.x));
    const double curvature = bend / (0.5 * (norm(back) + norm(ahead)));
    if (curvature < 0.0 && 1.0 / -curvature < kMinShiftRadius) {
      return false;
    }
  }
  return true;
}

ReferencePolyline shifted_left(const Polyline& first, const std::vector<double>& half_widths) {
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
    shift[i] = half_widths[i];
    // Shifted towards the inside of a turn, the line turns more tightly: at least kMinShiftRadius.
    if (curvature * shift[i] > 0.0) {
      shift[i] = std::copysign(
          std::clamp(1.0 / std::abs(curvature) - kMinShiftRadius, 0.0, std::abs(shift[i])),
          shift[i]);
    }
  }
  // At the ends the chords reach one way only, and on a curve their direction is off the
  // tangent by half the turn along them (13 degrees on a sparse junction link turning 20 degrees
  // a vertex): the tangent there is extrapolated from two chords (exact on a circle).
  const double length = first.length();
  if (n >= 2 && length >= 3.0 * kEndChord) {
    const auto chord = [&](double a, double b) {
      const Vec2 d = xy(first.at(b)) - xy(first.at(a));
      return std::atan2(d.y, d.x);
    };
    // Where the first (last) chord lies on one segment of sparse data, the extrapolation holds
    // only if the data turns like a circle there: equal corners at the next two vertices. A
    // junction path that runs straight for metres and then turns has half the corner at the
    // first (the turn begins there), and its first segment is the tangent; extrapolating would
    // point up to 0.22 rad off it into the outside of the turn, and the line would have to
    // turn back within a metre, folding the lane on the inside. Between the two, in proportion.
    const double s1 = chord(0.0, kEndChord), s2 = chord(kEndChord, 2.0 * kEndChord);
    const double start = s1 - circle_share(p, false) * 0.5 * angle_diff(s2, s1);
    const double e1 = chord(length - kEndChord, length);
    const double e2 = chord(length - 2.0 * kEndChord, length - kEndChord);
    const double end = e1 + circle_share(p, true) * 0.5 * angle_diff(e1, e2);
    normals.front() = Vec2{-std::sin(start), std::cos(start)};
    normals.back() = Vec2{-std::sin(end), std::cos(end)};
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
  // On magnitudes: a line shifted right (negative shifts) is reduced towards zero alike.
  const double side =
      std::any_of(shift.begin(), shift.end(), [](double v) { return v < 0.0; }) ? -1.0 : 1.0;
  for (double& v : shift) {
    v = std::abs(v);
  }
  const std::vector<double> eased = window(window(shift, kEase, true), 0.5 * kEase, false);
  ReferencePolyline out;
  out.points.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const double d = side * eased[i];
    out.points[i] = Point2{p[i].x + d * normals[i].x, p[i].y + d * normals[i].y};
  }
  // The headings of the normals used at the ends (the normal is the tangent turned left).
  out.start_heading = std::atan2(-normals.front().x, normals.front().y);
  out.end_heading = std::atan2(-normals.back().x, normals.back().y);
  return out;
}

void relax_right_turns(std::vector<Point2>& p, const std::vector<double>& road_width,
                       bool lanes_left) {
  const size_t n = p.size();
  if (n < 3) {
    return;
  }
  std::vector<double> u(n, 0.0);
  for (size_t i = 1; i < n; ++i) {
    u[i] = u[i - 1] + norm(to_vec(p[i]) - to_vec(p[i - 1]));
  }
  const auto at = [&](const std::vector<Point2>& q, double where) { return point_at(q, u, where); };
  for (int round = 0; round < kRelaxRounds; ++round) {
    // Arc lengths of right turns tighter than the road is wide.
    std::vector<double> tight;
    for (size_t i = 1; i + 1 < n; ++i) {
      const Vec2 a = at(p, u[i] - kRelaxChord), m = to_vec(p[i]), b = at(p, u[i] + kRelaxChord);
      if (norm(m - a) < 1e-6 || norm(b - m) < 1e-6) {
        continue;
      }
      const double turn =
          angle_diff(std::atan2(b.y - m.y, b.x - m.x), std::atan2(m.y - a.y, m.x - a.x));
      const double curvature = (lanes_left ? -turn : turn) / (0.5 * (norm(m - a) + norm(b - m)));
      if (curvature < -1.0 / (road_width[i] + kFoldClearance)) {
        tight.push_back(u[i]);
      }
    }
    if (tight.empty()) {
      return;
    }
    ease_at(p, u, tight);
  }
}

void ease_near(std::vector<Point2>& points, const std::vector<double>& at) {
  if (points.size() < 3 || at.empty()) {
    return;
  }
  ease_at(points, arc_lengths(points), at);
}

std::vector<double> tight_right_turns(const CurveFit& fit, double curvature, bool lanes_left) {
  std::vector<double> out;
  for (const xodr::Geometry& g : fit.geometries) {
    double k0 = 0.0, k1 = 0.0;
    if (const auto* arc = std::get_if<xodr::ArcGeometry>(&g.shape)) {
      k0 = k1 = arc->curvature;
    } else if (const auto* spiral = std::get_if<xodr::SpiralGeometry>(&g.shape)) {
      k0 = spiral->curv_start;
      k1 = spiral->curv_end;
    }
    if (lanes_left) {
      k0 = -k0;
      k1 = -k1;
    }
    if (std::min(k0, k1) < -curvature) {
      out.push_back(g.s + (k0 < k1 ? 0.0 : g.length));
    }
  }
  return out;
}

ReferencePolyline align_ends(ReferencePolyline reference, const std::optional<EndLine>& start,
                             const std::optional<EndLine>& end, Vec2 start_anchor, Vec2 end_anchor,
                             double road_width) {
  std::vector<Point2>& p = reference.points;
  std::vector<Point2> reversed(p.rbegin(), p.rend());
  const double end_skew = end ? skew_of(p, *end) : 0.0;
  const double start_skew = start ? skew_of(reversed, *start) : 0.0;
  const double length = polyline_length(p);
  // A short road skewed at both ends (a parallelogram between two stop lines): one curve square
  // to both lines, from the start target to where it meets the end line, rather than two bends
  // that do not fit. The lanes then cross its normals at a slant, which their offsets follow
  // (the laneOffset drifts by about length x tan(skew)).
  if (end_skew != 0.0 && start_skew != 0.0 &&
      reach_for(end_skew, road_width) + reach_for(start_skew, road_width) > 0.9 * length) {
    const auto e = end_target(p, end_skew, end_anchor);
    const auto s = end_target(reversed, start_skew, start_anchor);
    const auto d0 = end_direction(reversed);
    const auto d1 = end_direction(p);
    // Only for roads that hardly turn (the curve replaces the lane's own course).
    if (e && s && d0 && d1 && dot(-1.0 * *d0, *d1) > std::cos(0.35)) {
      const Vec2 start_square = -1.0 * s->square;
      const Vec2 across{e->square.y, -e->square.x};
      const double denominator = cross(start_square, across);
      if (std::abs(denominator) > 0.5) {
        const Vec2 meet = even_turn_end(s->point, start_square, *e);
        std::vector<Point2> curve{Point2{s->point.x, s->point.y}};
        const std::vector<Point2> rest = hermite(s->point, start_square, meet, e->square);
        curve.insert(curve.end(), rest.begin(), rest.end());
        reference.points = std::move(curve);
        reference.start_heading = std::atan2(start_square.y, start_square.x);
        reference.end_heading = std::atan2(e->square.y, e->square.x);
        return reference;
      }
    }
  }
  // Both ends share the road; one alone may use most of it. A turn that does not fit is made
  // only as far as it can be without folding (the outer lanes then keep part of their gap).
  const double room = (end_skew != 0.0 && start_skew != 0.0 ? 0.45 : 0.85) * length;
  if (end_skew != 0.0) {
    const double skew = skew_within(end_skew, road_width, room);
    const auto target = end_target(p, skew, end_anchor);
    if (target) {
      if (const auto heading = bend_end(p, *target, std::min(room, reach_for(skew, road_width)))) {
        reference.end_heading = *heading;
      }
    }
  }
  if (start_skew != 0.0) {
    const double skew = skew_within(start_skew, road_width, room);
    std::reverse(p.begin(), p.end());
    const auto target = end_target(p, skew, start_anchor);
    if (target) {
      if (const auto heading = bend_end(p, *target, std::min(room, reach_for(skew, road_width)))) {
        reference.start_heading = std::remainder(*heading + M_PI, 2.0 * M_PI);
      }
    }
    std::reverse(p.begin(), p.end());
  }
  return reference;
}

}  // namespace corsa::ngii::detail
