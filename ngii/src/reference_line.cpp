#include "reference_line.h"

#include <algorithm>
#include <variant>

#include "clothoid.h"

namespace corsa::ngii::detail {

std::vector<RefSample> sample_reference(const std::vector<xodr::Geometry>& plan_view,
                                        const std::vector<double>& s_sorted) {
  std::vector<RefSample> out;
  out.reserve(s_sorted.size());
  std::vector<double> local;
  std::vector<ClothoidPoint> points;
  size_t next = 0;
  for (size_t g = 0; g < plan_view.size(); ++g) {
    const xodr::Geometry& geometry = plan_view[g];
    const bool last = g + 1 == plan_view.size();
    local.clear();
    while (next < s_sorted.size() && (last || s_sorted[next] < geometry.s + geometry.length)) {
      local.push_back(std::max(0.0, s_sorted[next] - geometry.s));
      ++next;
    }
    if (local.empty()) {
      continue;
    }
    Clothoid curve{geometry.x, geometry.y, geometry.hdg, 0.0, 0.0};
    if (const auto* arc = std::get_if<xodr::ArcGeometry>(&geometry.shape)) {
      curve.k0 = arc->curvature;
    } else if (const auto* spiral = std::get_if<xodr::SpiralGeometry>(&geometry.shape)) {
      curve.k0 = spiral->curv_start;
      curve.k1 = (spiral->curv_end - spiral->curv_start) / geometry.length;
    }
    evaluate_clothoid(curve, local, points, false);
    for (const ClothoidPoint& p : points) {
      out.push_back({p.x, p.y, p.theta});
    }
  }
  return out;
}

double curvature_at(const std::vector<xodr::Geometry>& plan_view, double s) {
  if (plan_view.empty()) {
    return 0.0;
  }
  auto it = std::upper_bound(plan_view.begin(), plan_view.end(), s,
                             [](double value, const xodr::Geometry& g) { return value < g.s; });
  const xodr::Geometry& g = it == plan_view.begin() ? plan_view.front() : *(it - 1);
  if (const auto* arc = std::get_if<xodr::ArcGeometry>(&g.shape)) {
    return arc->curvature;
  }
  if (const auto* spiral = std::get_if<xodr::SpiralGeometry>(&g.shape)) {
    const double f = g.length > 0.0 ? std::clamp((s - g.s) / g.length, 0.0, 1.0) : 0.0;
    return spiral->curv_start + f * (spiral->curv_end - spiral->curv_start);
  }
  return 0.0;
}

double piecewise_value(const std::vector<xodr::Poly3>& pieces, double s) {
  if (pieces.empty()) {
    return 0.0;
  }
  auto it = std::upper_bound(pieces.begin(), pieces.end(), s,
                             [](double value, const xodr::Poly3& p) { return value < p.s; });
  return (it == pieces.begin() ? pieces.front() : *(it - 1)).value(s);
}

}  // namespace corsa::ngii::detail
