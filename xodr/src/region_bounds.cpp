#include "region_bounds.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

#include "corsa/xodr/map.h"
#include "road_eval.h"

namespace corsa::xodr::detail {
namespace {

// What the spatial index's chunks can reach (spatial_index.cpp): at most 5 m long (plus a sliver
// of 5 cm absorbed at a section's end), samples a quarter of that apart.
constexpr double kChunkReach = 5.1;  // m of s
constexpr double kSampleStep = 1.3;  // m of s
// Pieces a parametric cubic's parameter range is cut into to bound its curvature.
constexpr int kCurvaturePieces = 32;

/// |a + b x + c x^2 + d x^3| for |x| <= X.
double cubic_bound(double a, double b, double c, double d, double x) {
  return std::abs(a) + x * (std::abs(b) + x * (std::abs(c) + x * std::abs(d)));
}

/// |p(q)| for q in [lo, hi] (absolute s of the record's variable).
double poly_bound(const Poly3& p, double lo, double hi) {
  return cubic_bound(p.a, p.b, p.c, p.d, std::max(std::abs(lo - p.s), std::abs(hi - p.s)));
}

/// The largest |value| a list of records in s order takes for s in [lo, hi], each record
/// serving from its start to the next one's (the first also before its start).
double records_bound(const std::vector<Poly3>& records, double lo, double hi, bool zero_before) {
  double bound = 0.0;
  for (size_t i = 0; i < records.size(); ++i) {
    const double from =
        (i == 0 && !zero_before) ? -std::numeric_limits<double>::infinity() : records[i].s;
    const double to =
        i + 1 < records.size() ? records[i + 1].s : std::numeric_limits<double>::infinity();
    if (to < lo || from > hi) {
      continue;
    }
    bound = std::max(bound, poly_bound(records[i], std::max(lo, from), std::min(hi, to)));
  }
  return bound;
}

/// The farthest (m) any lane border of the section is from the reference line.
double lateral_bound(const Road& road, size_t section_index, double s0, double s1) {
  const LaneSection& section = road.lane_sections[section_index];
  double t = records_bound(road.lane_offsets, s0, s1, true);
  const double offset = t;
  // Widths and borders run on ds from the section's start.
  const double lo = s0 - section.s, hi = s1 - section.s;
  const auto outer = [&](const Lane& lane, double inner) {
    if (!lane.widths.empty()) {
      return inner + records_bound(lane.widths, lo, hi, false);
    }
    if (!lane.borders.empty()) {
      return records_bound(lane.borders, lo, hi, false);
    }
    return inner;
  };
  const size_t center = center_index(section);
  double inner = offset;
  for (size_t i = center; i-- > 0;) {
    inner = outer(section.lanes[i], inner);
    t = std::max(t, inner);
  }
  inner = offset;
  for (size_t i = center; i < section.lanes.size(); ++i) {
    if (section.lanes[i].id == 0) {
      continue;
    }
    inner = outer(section.lanes[i], inner);
    t = std::max(t, inner);
  }
  return t;
}

/// Range of a quadratic q(p) = a + b p + c p^2 over [lo, hi].
void quadratic_range(double a, double b, double c, double lo, double hi, double& min, double& max) {
  const auto at = [&](double p) { return a + p * (b + p * c); };
  min = std::min(at(lo), at(hi));
  max = std::max(at(lo), at(hi));
  if (c != 0.0) {
    const double vertex = -b / (2.0 * c);
    if (vertex > lo && vertex < hi) {
      min = std::min(min, at(vertex));
      max = std::max(max, at(vertex));
    }
  }
}

double smallest_magnitude(double min, double max) {
  return min > 0.0 ? min : max < 0.0 ? -max : 0.0;
}

/// Bounds of a parametric cubic over p in [lo, hi]: its largest speed |r'(p)| and curvature
/// (false when the speed may vanish there, leaving the curvature unbounded).
bool param_poly3_bounds(const ParamPoly3Geometry& g, double lo, double hi, double& speed,
                        double& curvature) {
  speed = 0.0;
  curvature = 0.0;
  for (int k = 0; k < kCurvaturePieces; ++k) {
    const double a = lo + (hi - lo) * k / kCurvaturePieces;
    const double b = lo + (hi - lo) * (k + 1) / kCurvaturePieces;
    double du0, du1, dv0, dv1;
    quadratic_range(g.bu, 2.0 * g.cu, 3.0 * g.du, a, b, du0, du1);
    quadratic_range(g.bv, 2.0 * g.cv, 3.0 * g.dv, a, b, dv0, dv1);
    const double ddu =
        std::max(std::abs(2.0 * g.cu + 6.0 * g.du * a), std::abs(2.0 * g.cu + 6.0 * g.du * b));
    const double ddv =
        std::max(std::abs(2.0 * g.cv + 6.0 * g.dv * a), std::abs(2.0 * g.cv + 6.0 * g.dv * b));
    const double du = std::max(std::abs(du0), std::abs(du1));
    const double dv = std::max(std::abs(dv0), std::abs(dv1));
    const double su = smallest_magnitude(du0, du1), sv = smallest_magnitude(dv0, dv1);
    const double slowest = su * su + sv * sv;
    if (!(slowest > 0.0)) {
      return false;
    }
    speed = std::max(speed, std::hypot(du, dv));
    curvature = std::max(curvature, (du * ddv + dv * ddu) / (slowest * std::sqrt(slowest)));
  }
  return true;
}

/// What one planView record contributes over ds in [lo, hi] (m from its start): the box of its
/// points, its largest curvature and its speed per metre of s.
struct RecordReach {
  Bounds box;
  double curvature = 0.0;
  double stretch = 1.0;
};

bool record_reach(const Geometry& g, double lo, double hi, RecordReach& out) {
  const double reach = std::max(std::abs(lo), std::abs(hi));
  const double c = std::cos(g.hdg), s = std::sin(g.hdg);
  // A disc of radius r about the record's start.
  const auto disc = [&](double r) { out.box = Bounds{g.x - r, g.y - r, g.x + r, g.y + r}; };
  return std::visit(
      [&](const auto& shape) -> bool {
        using T = std::decay_t<decltype(shape)>;
        if constexpr (std::is_same_v<T, LineGeometry>) {
          const double xa = g.x + c * lo, ya = g.y + s * lo;
          const double xb = g.x + c * hi, yb = g.y + s * hi;
          out.box = Bounds{std::min(xa, xb), std::min(ya, yb), std::max(xa, xb), std::max(ya, yb)};
          return true;
        } else if constexpr (std::is_same_v<T, ArcGeometry>) {
          disc(reach);  // arc length: no point farther from the start than the distance along it
          out.curvature = std::abs(shape.curvature);
          return true;
        } else if constexpr (std::is_same_v<T, SpiralGeometry>) {
          disc(reach);
          const double rate = g.length > 0.0 ? (shape.curv_end - shape.curv_start) / g.length : 0.0;
          out.curvature = std::abs(shape.curv_start) + std::abs(rate) * reach;
          return true;
        } else if constexpr (std::is_same_v<T, ParamPoly3Geometry>) {
          const bool normalized = shape.range == ParamRange::kNormalized;
          const double scale = normalized ? (g.length > 0.0 ? 1.0 / g.length : 0.0) : 1.0;
          const double p_lo = std::min(lo, 0.0) * scale, p_hi = std::max(hi, 0.0) * scale;
          const double p = std::max(std::abs(p_lo), std::abs(p_hi));
          disc(std::hypot(cubic_bound(shape.au, shape.bu, shape.cu, shape.du, p),
                          cubic_bound(shape.av, shape.bv, shape.cv, shape.dv, p)));
          double speed = 0.0;
          if (!param_poly3_bounds(shape, p_lo, p_hi, speed, out.curvature)) {
            return false;
          }
          out.stretch = std::max(1.0, speed * scale);
          return true;
        } else {
          return false;  // poly3: u comes from an iteration, no closed bound
        }
      },
      g.shape);
}

bool finite(const Bounds& b) {
  return std::isfinite(b.x0) && std::isfinite(b.y0) && std::isfinite(b.x1) && std::isfinite(b.y1);
}

}  // namespace

bool section_bounds(const Map& map, size_t road_index, size_t section, Bounds& out) {
  const Road& road = map.road(road_index);
  const auto& plan = road.plan_view;
  if (plan.empty() || section >= road.lane_sections.size()) {
    return false;
  }
  // The s the index samples: the section's range, within the road (Map::reference clamps).
  const double s0 = std::clamp(road.lane_sections[section].s, 0.0, road.length);
  const double s1 = std::clamp(map.section_end(road_index, section), s0, road.length);
  const auto start_of = [](const Geometry& g) { return g.s; };
  const size_t first = record_index(plan, s0, start_of);
  const size_t last = record_index(plan, s1, start_of);
  Bounds box{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
             -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  double curvature = 0.0, stretch = 1.0;
  for (size_t g = first; g <= last; ++g) {
    const Geometry& record = plan[g];
    const double from = g == first ? s0 : record.s;
    const double to = g == last ? s1 : plan[g + 1].s;
    RecordReach reach;
    if (!record_reach(record, from - record.s, to - record.s, reach)) {
      return false;
    }
    box = Bounds{std::min(box.x0, reach.box.x0), std::min(box.y0, reach.box.y0),
                 std::max(box.x1, reach.box.x1), std::max(box.y1, reach.box.y1)};
    curvature = std::max(curvature, reach.curvature);
    stretch = std::max(stretch, reach.stretch);
  }
  const double t = lateral_bound(road, section, s0, s1);
  // A chunk's rectangle: its samples lie within t of reference points at most kChunkReach x
  // stretch apart, so each corner is within that plus 2 t of a sample's reference point, and
  // the index adds a margin for bowing between samples.
  const double margin = 0.1 + (t + kSampleStep) * (1.5 * curvature * kSampleStep * stretch + 0.01);
  const double widen = kChunkReach * stretch + 3.0 * t + margin + 0.5;
  const double slack = 1e-6 + 1e-9 * std::max({std::abs(box.x0), std::abs(box.y0), std::abs(box.x1),
                                               std::abs(box.y1)});
  out = Bounds{box.x0 - widen - slack, box.y0 - widen - slack, box.x1 + widen + slack,
               box.y1 + widen + slack};
  return std::isfinite(widen) && finite(out);
}

}  // namespace corsa::xodr::detail
