// Road ends bent to meet the lanes' end lines square (see road_reference.h): the line through
// the lane ends (end_line), and the reference polyline turned near each end so that its normal
// there runs along that line (align_ends).

#include <algorithm>
#include <cmath>
#include <optional>

#include "road_reference.h"

namespace corsa::ngii::detail {
namespace {

constexpr double kEndLineTolerance = 0.25;  // m: lane ends farther from one line: no line
/// Skews past this are left alone (the end square to the road's course). A junction path
/// leaving a lane whose end line its course crosses 51 degrees off square (K-City's path 460
/// after road 322) started square with a wedge of 3 m beside it; 55 degrees bend it.
constexpr double kMaxSkew = 55.0 * M_PI / 180.0;
constexpr double kMinSkew = 0.2 * M_PI / 180.0;
/// m: how far the outermost lane's corner may lie off a line it is left skewed to.
constexpr double kSquareCorner = 0.01;

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
/// pointing forward); 0 when the end is square enough (under kMinSkew, with the outermost lane's
/// corner, `road_width` from the reference line, within kSquareCorner of the line) or past
/// kMaxSkew (left alone). A five-lane road 17 m wide ending 0.15 degrees off its line put its
/// outer corners 4.5 cm off it, and where the road after the joint was skewed the other way the
/// strip between them was twice that.
double skew_of(const std::vector<Point2>& p, const EndLine& line, double road_width) {
  const auto forward = end_direction(p);
  if (!forward) {
    return 0.0;
  }
  Vec2 square{line.across.y, -line.across.x};
  if (dot(square, *forward) < 0.0) {
    square = -1.0 * square;
  }
  const double skew = std::atan2(cross(*forward, square), dot(*forward, square));
  const bool square_enough =
      std::abs(skew) < kMinSkew && road_width * std::tan(std::abs(skew)) < kSquareCorner;
  return square_enough || std::abs(skew) > kMaxSkew ? 0.0 : skew;
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

/// Extends the end of `p` along its course onto the parallel of `line` through `anchor`, where
/// the line is within kMinSkew of square (not bent to) and the end lies at most kSlideReach
/// short of it. A road ending a few centimetres before the line it shares with the next road
/// left that strip unpaved across every lane of the joint. An end past the line stays: the two
/// roads overlap there, and pulling it back onto a line slightly off square to it opens a
/// wedge on one side.
constexpr double kSlideReach = 0.25;  // m: as far as an end may lie off its line (end_line)
void slide_end(std::vector<Point2>& p, const EndLine& line, Vec2 anchor) {
  const auto forward = end_direction(p);
  if (!forward || p.size() < 2) {
    return;
  }
  const Vec2 square{line.across.y, -line.across.x};
  if (std::abs(cross(*forward, square)) > std::sin(kMinSkew)) {
    return;
  }
  const double denominator = cross(line.across, *forward);
  const Vec2 last = to_vec(p.back());
  const double along = cross(line.across, anchor - last) / denominator;
  if (along <= 0.0 || along > kSlideReach) {
    return;
  }
  const Vec2 moved = last + along * *forward;
  p.back() = Point2{moved.x, moved.y};
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
/// reach (curvature turn / reach), where a curve back to the line of travel (an S) turns up to four
/// times as tightly at its end and folds the lanes on its inside. The laneOffset takes up the arc's
/// sideways drift (§9.3). `target.point` when the chord does not meet the line ahead (beyond 0.5 m;
/// 5 cm where it hardly turns: a piece 0.4 m long between two parallel lines made an S of five
/// records there and folded), and for bends shorter than kMinEvenTurn (a road of a few metres: its
/// plan view could not follow the drift within the fit tolerance, and its lanes' ends would move)
/// unless it hardly turns (under kStraightTurn): a piece of a metre between two parallel skewed
/// lines (a road cut where one lane ends short of the others' stop line) then runs straight from
/// line to line, where a curve to the line of travel would swing by twice the skew and fold its
/// lanes. With `even` a short bend turns evenly too (bend_to_line: where its drift is small).
constexpr double kMinEvenTurn = 4.0;    // m
constexpr double kStraightTurn = 0.05;  // rad
Vec2 even_turn_end(Vec2 start, Vec2 heading, const EndTarget& target, bool even = false) {
  const double turn = std::atan2(cross(heading, target.square), dot(heading, target.square));
  if (!even && norm(target.point - start) < kMinEvenTurn && std::abs(turn) >= kStraightTurn) {
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
  const double least = std::abs(turn) < kStraightTurn ? 0.05 : 0.5;  // m
  return along > least ? start + along * chord : target.point;
}

/// Bends the end of `p` over its last `reach` metres: a cubic Hermite curve turning evenly to
/// the end line, arriving square to it. Returns the new end heading.
std::optional<double> bend_end(std::vector<Point2>& p, const EndTarget& target, double reach,
                               bool even) {
  double walked = 0.0;
  size_t i = p.size() - 1;
  while (i > 0 && walked + norm(to_vec(p[i]) - to_vec(p[i - 1])) < reach) {
    walked += norm(to_vec(p[i]) - to_vec(p[i - 1]));
    --i;
  }
  if (i + 1 >= p.size()) {
    // The last segment is longer than the reach (a short link surveyed by its two ends): the
    // bend starts on it, `reach` before the end.
    if (i == 0) {
      return std::nullopt;
    }
    const Vec2 a = to_vec(p[i - 1]);
    const Vec2 b = to_vec(p[i]);
    const double f = 1.0 - reach / norm(b - a);
    const Vec2 q = a + f * (b - a);
    p.insert(p.begin() + static_cast<std::ptrdiff_t>(i), Point2{q.x, q.y});
    walked = reach;  // the bend starts at q, the reach before the end: no second start below
  }
  // Sparse vertices (a link digitised with a few long segments): where the vertex the walk
  // stops at lies less than half the reach from the end, the bend starts on the segment before
  // it, at the reach. Turning over the last metre alone, the end of a lane 2 m wide turned right
  // at radii under 2 m and its lane was narrowed there (the inside of the turn), leaving unpaved
  // ground beside the joint.
  if (i > 0 && walked < 0.5 * reach) {
    const Vec2 a = to_vec(p[i - 1]);
    const Vec2 b = to_vec(p[i]);
    const double rest = reach - walked;
    if (const double segment = norm(b - a); segment > rest) {
      const Vec2 q = b + (rest / segment) * (a - b);
      p.insert(p.begin() + static_cast<std::ptrdiff_t>(i), Point2{q.x, q.y});
    }
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
      hermite(start, heading, even_turn_end(start, heading, target, even), target.square);
  p.insert(p.end(), tail.begin(), tail.end());
  return std::atan2(target.square.y, target.square.x);
}

/// How far (m) before an end a turn by `skew` must begin so that lanes up to `road_width` away
/// do not fold (their normals must not cross: turn rate * width well below 1); and the turn
/// that fits into `room` metres.
constexpr double kFoldMargin = 2.0;
/// The margin of a short bend turning evenly at one end only (bend_to_line): width x turn rate
/// stays under 1 / 1.5 along an even turn, where an S turns up to four times as tightly.
constexpr double kShortFoldMargin = 1.5;
constexpr double kShortDrift = 0.4;  // m
double reach_for(double skew, double road_width) {
  return std::max(8.0, kFoldMargin * road_width * std::tan(std::abs(skew)));
}
double skew_within(double skew, double road_width, double room, double margin) {
  const double most = std::atan(room / (margin * std::max(road_width, 1e-3)));
  return std::copysign(std::min(std::abs(skew), most), skew);
}

/// How far an end that turns `residual` short of its end line runs on past the anchor (through
/// which the line runs) along its end heading, for the road's edge `span` metres from the anchor:
/// the depth of the triangle its end edge leaves short of the line at that edge, where that is
/// between kCornerLeast and kCornerDepth, at most kCornerOverrun (the lane's end then lies as far
/// beyond its link's end; the other corner overlaps the next road by twice as much). Sangam's
/// 2.25 m road 365 turns 28 of its 37 degrees before it would fold: its end edge crossed the
/// next road's start line at its lane's centre and left a triangle up to 0.14 m deep unpaved at
/// its right corner, beyond the next road's edge and behind its start line, where no shoulder of
/// that road can reach; run on by 9 cm, the corner lies within 5 cm of the line and the
/// shoulder added beside the next road's start (mouth_fills.cpp) covers the rest. Deeper
/// triangles stay: an overrun within a lane end's tolerance (build_joined allows a junction
/// path's lane end 0.1 m off its link) does not close them.
constexpr double kCornerLeast = 0.01;    // m
constexpr double kCornerDepth = 0.15;    // m
constexpr double kCornerOverrun = 0.09;  // m
double corner_overrun(double residual, double span) {
  const double depth = span * std::tan(residual);
  return depth < kCornerLeast || depth > kCornerDepth ? 0.0 : std::min(depth, kCornerOverrun);
}

/// Bends the end of `p` onto the end line turned by `skew` from its course (through `anchor`),
/// within `room` metres; returns the new end heading. Where the other end is not bent
/// (`alone`) and the bend is short (a road of two or three metres after a skewed stop line, a
/// link surveyed by its two ends), it turns evenly over the room, like an arc, as far as
/// kShortFoldMargin allows. The S back to the line of travel that a short bend makes otherwise
/// turns up to four times as tightly at its end: Sangam's one-lane roads of 2.2-2.5 m after a
/// stop line skewed by 18-21 degrees folded, their lanes narrowed to 1.5 m on the inside; as an
/// arc within kFoldMargin they turned 2-3 degrees short, leaving gaps of up to 0.45 m along
/// their lanes' start edges. Only while the arc's sideways drift (reach x tan(turn / 2), taken
/// up by the laneOffset) stays within kShortDrift: beyond it the lane's end normal no longer
/// meets its own link's end (Sangam's 2.25 m road 365 turning 35 degrees moved its lane end
/// 0.39 m off its link).
std::optional<double> bend_to_line(std::vector<Point2>& p, double skew, Vec2 anchor,
                                   double road_width, double span, double room, bool alone) {
  bool short_even = false;
  if (alone) {
    const double turn = skew_within(skew, road_width, room, kShortFoldMargin);
    const double reach = std::min(room, reach_for(turn, road_width));
    short_even = reach * std::tan(0.5 * std::abs(turn)) <= kShortDrift;
  }
  const double turn =
      skew_within(skew, road_width, room, short_even ? kShortFoldMargin : kFoldMargin);
  auto target = end_target(p, turn, anchor);
  if (!target) {
    return std::nullopt;
  }
  target->point = target->point + corner_overrun(std::abs(skew - turn), span) * target->square;
  return bend_end(p, *target, std::min(room, reach_for(turn, road_width)), short_even);
}

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

ReferencePolyline align_ends(ReferencePolyline reference, const std::optional<EndLine>& start,
                             const std::optional<EndLine>& end, Vec2 start_anchor, Vec2 end_anchor,
                             double road_width, EndSpans spans) {
  std::vector<Point2>& p = reference.points;
  std::vector<Point2> reversed(p.rbegin(), p.rend());
  const double end_skew = end ? skew_of(p, *end, road_width) : 0.0;
  const double start_skew = start ? skew_of(reversed, *start, road_width) : 0.0;
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
  const bool alone = end_skew == 0.0 || start_skew == 0.0;
  const double room = (alone ? 0.85 : 0.45) * length;
  if (end_skew != 0.0) {
    if (const auto heading =
            bend_to_line(p, end_skew, end_anchor, road_width, spans.end, room, alone)) {
      reference.end_heading = *heading;
    }
  }
  if (end && end_skew == 0.0) {
    slide_end(p, *end, end_anchor);
  }
  if (start && start_skew == 0.0) {
    std::reverse(p.begin(), p.end());
    slide_end(p, *start, start_anchor);
    std::reverse(p.begin(), p.end());
  }
  if (start_skew != 0.0) {
    std::reverse(p.begin(), p.end());
    if (const auto heading =
            bend_to_line(p, start_skew, start_anchor, road_width, spans.start, room, alone)) {
      reference.start_heading = std::remainder(*heading + M_PI, 2.0 * M_PI);
    }
    std::reverse(p.begin(), p.end());
  }
  return reference;
}

}  // namespace corsa::ngii::detail
