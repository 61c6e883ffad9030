#include "lateral_profile.h"

#include <algorithm>
#include <cmath>

#include "corsa/ngii/curve_fit.h"
#include "reference_line.h"

namespace corsa::ngii::detail {
namespace {

constexpr double kPlaneTolerance = 0.02;   // m: lanes off the plane by more need a shape
constexpr double kShapeTolerance = 0.015;  // m: shape interpolation error between stations
constexpr double kShapeMargin = 10.0;      // m: linear extension of a shape past the lanes

struct Plane {
  double height = 0.0;  ///< at t = 0
  double slope = 0.0;   ///< dz/dt
};

/// Least-squares plane through the lanes of one station (lanes past their ends count little).
Plane plane_of(const std::vector<LaneHeightSample>& lanes) {
  double sw = 0.0, st = 0.0, sz = 0.0, stt = 0.0, stz = 0.0;
  for (const LaneHeightSample& lane : lanes) {
    const double w = lane.own ? 1.0 : 0.05;
    sw += w;
    st += w * lane.t;
    sz += w * lane.z;
    stt += w * lane.t * lane.t;
    stz += w * lane.t * lane.z;
  }
  const double mean_t = st / sw, mean_z = sz / sw;
  const double var = stt / sw - mean_t * mean_t;
  // One lane (or lanes on top of each other): level across, at the lane's own height.
  const double slope = var > 0.25 ? (stz / sw - mean_t * mean_z) / var : 0.0;
  return {mean_z - slope * mean_t, slope};
}

/// The shape records of one station: cubic Hermite pieces through (t, height above the
/// elevation) of the lanes, slopes from the neighbouring points, and straight lines beyond.
std::vector<xodr::ShapeRecord> shape_at(double s, std::vector<std::pair<double, double>> points) {
  std::sort(points.begin(), points.end());
  const size_t n = points.size();
  std::vector<double> slope(n, 0.0);
  for (size_t j = 0; j < n; ++j) {
    const size_t a = j > 0 ? j - 1 : j;
    const size_t b = j + 1 < n ? j + 1 : j;
    const double dt = points[b].first - points[a].first;
    slope[j] = dt > 1e-6 ? (points[b].second - points[a].second) / dt : 0.0;
  }
  std::vector<xodr::ShapeRecord> out;
  const auto& [t0, v0] = points.front();
  out.push_back({s, t0 - kShapeMargin, v0 - kShapeMargin * slope[0], slope[0], 0.0, 0.0});
  for (size_t j = 0; j + 1 < n; ++j) {
    const double h = points[j + 1].first - points[j].first;
    if (h < 1e-6) {
      continue;
    }
    const double dv = points[j + 1].second - points[j].second;
    const double c = (3.0 * dv / h - 2.0 * slope[j] - slope[j + 1]) / h;
    const double d = (slope[j] + slope[j + 1] - 2.0 * dv / h) / (h * h);
    out.push_back({s, points[j].first, points[j].second, slope[j], c, d});
  }
  out.push_back({s, points.back().first, points.back().second, slope[n - 1], 0.0, 0.0});
  return out;
}

double shape_value(const std::vector<xodr::ShapeRecord>& records, double t) {
  const xodr::ShapeRecord* best = &records.front();
  for (const xodr::ShapeRecord& r : records) {
    if (r.t <= t) {
      best = &r;
    }
  }
  const double dt = t - best->t;
  return best->a + dt * (best->b + dt * (best->c + dt * best->d));
}

/// Shapes at as few stations as keep every lane centre within kShapeTolerance when
/// interpolated linearly in s between them.
std::vector<xodr::ShapeRecord> fit_shapes(const std::vector<double>& s,
                                          const std::vector<std::vector<LaneHeightSample>>& samples,
                                          const std::vector<xodr::Poly3>& elevation) {
  const size_t n = s.size();
  std::vector<std::vector<xodr::ShapeRecord>> at(n);
  for (size_t i = 0; i < n; ++i) {
    std::vector<std::pair<double, double>> points;
    const double base = piecewise_value(elevation, s[i]);
    for (const LaneHeightSample& lane : samples[i]) {
      points.emplace_back(lane.t, lane.z - base);
    }
    at[i] = shape_at(s[i], std::move(points));
  }
  const auto fits = [&](size_t a, size_t b) {
    for (size_t i = a + 1; i < b; ++i) {
      const double w = (s[i] - s[a]) / (s[b] - s[a]);
      const double base = piecewise_value(elevation, s[i]);
      for (const LaneHeightSample& lane : samples[i]) {
        const double v = (1 - w) * shape_value(at[a], lane.t) + w * shape_value(at[b], lane.t);
        if (std::abs(v - (lane.z - base)) > kShapeTolerance) {
          return false;
        }
      }
    }
    return true;
  };
  std::vector<xodr::ShapeRecord> out = at[0];
  for (size_t a = 0; a + 1 < n;) {
    size_t b = a + 1;
    while (b + 1 < n && fits(a, b + 1)) {
      ++b;
    }
    out.insert(out.end(), at[b].begin(), at[b].end());
    a = b;
  }
  return out;
}

}  // namespace

std::vector<double> fit_lateral_profile(xodr::Road& road, const std::vector<double>& s,
                                        const std::vector<std::vector<LaneHeightSample>>& samples,
                                        const ConvertOptions& options) {
  const size_t n = s.size();
  std::vector<ProfileSample> height(n), roll(n);
  double reach = 1.0;  // m: largest |t| of a lane centre, to scale the roll tolerance
  double off_plane = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const Plane plane = plane_of(samples[i]);
    height[i] = {s[i], plane.height};
    roll[i] = {s[i], std::atan(plane.slope)};
    for (const LaneHeightSample& lane : samples[i]) {
      reach = std::max(reach, std::abs(lane.t));
      if (lane.own) {
        off_plane = std::max(off_plane, std::abs(plane.height + plane.slope * lane.t - lane.z));
      }
    }
  }
  road.elevation = fit_profile(height, options.elevation_tolerance).pieces;
  std::vector<double> fitted(n, 0.0);
  if (off_plane > kPlaneTolerance) {
    road.shapes = fit_shapes(s, samples, road.elevation);
    return fitted;
  }
  const double largest =
      std::max_element(roll.begin(), roll.end(), [](const auto& a, const auto& b) {
        return std::abs(a.v) < std::abs(b.v);
      })->v;
  if (std::abs(largest) * reach < 0.005) {
    return fitted;  // level within 5 mm at the outermost lane: no superelevation records
  }
  // A roll error e moves the outermost lane by about e * reach vertically.
  road.superelevation = fit_profile(roll, options.superelevation_tolerance / reach).pieces;
  for (size_t i = 0; i < n; ++i) {
    fitted[i] = piecewise_value(road.superelevation, s[i]);
  }
  return fitted;
}

}  // namespace corsa::ngii::detail
