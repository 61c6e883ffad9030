// The reference polyline of a road (see road_reference.h): its reference lane shifted to its
// left edge, and eased where its turns would fold the lanes; road_end_bend.cpp bends its ends.

#include "road_reference.h"

#include <algorithm>
#include <cmath>
#include <variant>

namespace corsa::ngii::detail {
namespace {

constexpr double kMinShiftRadius = 1.5;  // m: tightest radius of the shifted reference line
constexpr double kEase = 12.0;           // m over which a reduced shift is eased in and out
// Right turns (towards the lanes) tighter than the road is wide (plus kFoldClearance) are
// smoothed over +-kRelaxReach, at most kRelaxRounds times; curvature from chords of kRelaxChord.
constexpr double kRelaxReach = 2.0;  // m
constexpr double kRelaxChord = 1.0;  // m
constexpr int kRelaxRounds = 20;
// m: how much of a road end stays unchanged when the tight turn lies at that end itself.
constexpr double kEndKeep = 0.5;
// Length (m) of the chords a road end's tangent is extrapolated from (shifted_left).
constexpr double kEndChord = 1.5;
// rad: how far a one-lane road must turn right overall to be fitted along its right edge.
constexpr double kInsideTurn = 0.5;

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
/// the lane ends), or from kEndKeep to twice that at an end a tight turn lies near.
void ease_at(std::vector<Point2>& p, const std::vector<double>& u,
             const std::vector<double>& tight) {
  const size_t n = p.size();
  std::vector<Point2> next(p);
  // An end stays as it is over kRelaxReach, unless a tight turn lies there itself (a short
  // record meeting the end's heading): then only over kEndKeep.
  const auto keep = [&](bool at_end) {
    const bool tight_there = std::any_of(tight.begin(), tight.end(), [&](double t) {
      return at_end ? t > u.back() - kRelaxReach : t < kRelaxReach;
    });
    return tight_there ? kEndKeep : kRelaxReach;
  };
  const double keep_start = keep(false);
  const double keep_end = keep(true);
  for (size_t i = 1; i + 1 < n; ++i) {
    const bool near_end = u[i] < keep_start || u[i] > u.back() - keep_end;
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
    const double f =
        std::clamp(std::min(u[i] / keep_start, (u.back() - u[i]) / keep_end) - 1.0, 0.0, 1.0);
    next[i] =
        Point2{p[i].x + f * (sum.x / weight - p[i].x), p[i].y + f * (sum.y / weight - p[i].y)};
  }
  p = std::move(next);
}

}  // namespace

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

bool along_right_edge(const Polyline& lane, bool tight_corners) {
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
  if (tight_corners) {
    return true;
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

}  // namespace corsa::ngii::detail
