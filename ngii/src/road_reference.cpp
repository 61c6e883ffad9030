#include "road_reference.h"

#include <algorithm>
#include <cmath>

namespace corsa::ngii::detail {
namespace {

constexpr double kMinShiftRadius = 1.5;  // m: tightest radius of the shifted reference line
constexpr double kEase = 12.0;           // m over which a reduced shift is eased in and out
constexpr double kEndLineTolerance = 0.25;  // m: lane ends farther from one line: no line
constexpr double kMaxSkew = 50.0 * M_PI / 180.0;
constexpr double kMinSkew = 0.2 * M_PI / 180.0;

Vec2 to_vec(const Point2& p) { return {p.x, p.y}; }

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
/// pointing forward); nothing when the end is already square or past kMaxSkew.
std::optional<double> skew_of(const std::vector<Point2>& p, const EndLine& line) {
  const auto forward = end_direction(p);
  if (!forward) {
    return std::nullopt;
  }
  Vec2 square{line.across.y, -line.across.x};
  if (dot(square, *forward) < 0.0) {
    square = -1.0 * square;
  }
  const double skew = std::atan2(cross(*forward, square), dot(*forward, square));
  if (std::abs(skew) < kMinSkew || std::abs(skew) > kMaxSkew) {
    return std::nullopt;
  }
  return skew;
}

/// Bends the end of `p` by `skew` (rad, from the direction of travel): over its last `reach`
/// metres, a cubic Hermite curve to the point where the line through `anchor` (the reference
/// lane's end) at that angle meets the line of travel through the end. Returns the new end
/// heading.
std::optional<double> bend_end(std::vector<Point2>& p, double skew, Vec2 anchor, double reach) {
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
  const Vec2 target = anchor + (cross(last - anchor, *forward) / denominator) * across;
  // The point `reach` metres before the end, and the direction there.
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
  heading = norm(heading) > 1e-9 ? (1.0 / norm(heading)) * heading : *forward;
  const double chord = norm(target - start);
  const int steps = std::max(4, static_cast<int>(std::ceil(chord / 0.5)));
  p.resize(i + 1);
  for (int k = 1; k <= steps; ++k) {
    const double f = static_cast<double>(k) / steps;
    const double h00 = 2 * f * f * f - 3 * f * f + 1, h10 = f * f * f - 2 * f * f + f;
    const double h01 = -2 * f * f * f + 3 * f * f, h11 = f * f * f - f * f;
    const Vec2 q = h00 * start + (h10 * chord) * heading + h01 * target + (h11 * chord) * square;
    p.push_back(Point2{q.x, q.y});
  }
  return std::atan2(square.y, square.x);
}

/// How far (m) before an end a turn by `skew` must begin so that lanes up to `road_width` away
/// do not fold (their normals must not cross: turn rate * width well below 1); and the turn
/// that fits into `room` metres.
constexpr double kFoldMargin = 1.5;
double reach_for(double skew, double road_width) {
  return std::max(8.0, kFoldMargin * road_width * std::tan(std::abs(skew)));
}
double skew_within(double skew, double road_width, double room) {
  const double most = std::atan(room / (kFoldMargin * std::max(road_width, 1e-3)));
  return std::copysign(std::min(std::abs(skew), most), skew);
}

}  // namespace

std::optional<EndLine> end_line(std::vector<Vec2> ends) {
  // The principal line of the points; the end farthest off it is dropped until the rest lie
  // within kEndLineTolerance (a lane ending elsewhere keeps a gap, the others none).
  while (ends.size() >= 2) {
    Vec2 mean{0.0, 0.0};
    for (const Vec2& e : ends) {
      mean = mean + (1.0 / static_cast<double>(ends.size())) * e;
    }
    double sxx = 0.0, sxy = 0.0, syy = 0.0;
    for (const Vec2& e : ends) {
      const Vec2 d = e - mean;
      sxx += d.x * d.x;
      sxy += d.x * d.y;
      syy += d.y * d.y;
    }
    const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
    Vec2 across{std::cos(angle), std::sin(angle)};
    if (dot(across, ends.back() - ends.front()) < 0.0) {
      across = -1.0 * across;
    }
    if (norm(ends.back() - ends.front()) < 1.0) {
      return std::nullopt;  // lane ends on top of each other: no direction to follow
    }
    size_t worst = 0;
    double worst_distance = 0.0;
    for (size_t i = 0; i < ends.size(); ++i) {
      const double distance = std::abs(cross(across, ends[i] - mean));
      if (distance > worst_distance) {
        worst_distance = distance;
        worst = i;
      }
    }
    if (worst_distance <= kEndLineTolerance) {
      return EndLine{mean, across};
    }
    ends.erase(ends.begin() + static_cast<std::ptrdiff_t>(worst));
  }
  return std::nullopt;
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
  ReferencePolyline out;
  out.points.resize(n);
  for (size_t i = 0; i < n; ++i) {
    out.points[i] = Point2{p[i].x + eased[i] * normals[i].x, p[i].y + eased[i] * normals[i].y};
  }
  // The headings of the normals used at the ends (the normal is the tangent turned left).
  out.start_heading = std::atan2(-normals.front().x, normals.front().y);
  out.end_heading = std::atan2(-normals.back().x, normals.back().y);
  return out;
}

ReferencePolyline align_ends(ReferencePolyline reference, const std::optional<EndLine>& start,
                             const std::optional<EndLine>& end, Vec2 start_anchor,
                             Vec2 end_anchor, double road_width) {
  std::vector<Point2>& p = reference.points;
  std::vector<Point2> reversed(p.rbegin(), p.rend());
  const std::optional<double> end_skew = end ? skew_of(p, *end) : std::nullopt;
  const std::optional<double> start_skew = start ? skew_of(reversed, *start) : std::nullopt;
  // Both ends share the road; one alone may use most of it. A turn that does not fit is made
  // only as far as it can be without folding (the outer lanes then keep part of their gap).
  const double length = polyline_length(p);
  const double room = (end_skew && start_skew ? 0.45 : 0.85) * length;
  if (end_skew) {
    const double skew = skew_within(*end_skew, road_width, room);
    const double reach = std::min(room, reach_for(skew, road_width));
    if (const auto heading = bend_end(p, skew, end_anchor, reach)) {
      reference.end_heading = *heading;
    }
  }
  if (start_skew) {
    const double skew = skew_within(*start_skew, road_width, room);
    const double reach = std::min(room, reach_for(skew, road_width));
    std::reverse(p.begin(), p.end());
    if (const auto heading = bend_end(p, skew, start_anchor, reach)) {
      reference.start_heading = std::remainder(*heading + M_PI, 2.0 * M_PI);
    }
    std::reverse(p.begin(), p.end());
  }
  return reference;
}

}  // namespace corsa::ngii::detail
