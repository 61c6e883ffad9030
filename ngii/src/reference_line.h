#pragma once

// Evaluation of a fitted plan view at many s values, with the converter's own clothoid
// integration (the same one the fit used, so measurements agree with the fit exactly).

#include <vector>

#include "corsa/xodr/model.h"

namespace corsa::ngii::detail {

struct RefSample {
  double x = 0.0;
  double y = 0.0;
  double hdg = 0.0;
};

/// Reference line points at every s of `s_sorted` (non-decreasing, within [0, length]).
std::vector<RefSample> sample_reference(const std::vector<xodr::Geometry>& plan_view,
                                        const std::vector<double>& s_sorted);

/// Curvature (1/m, + left) of `plan_view` at s (0 on lines and records of other kinds).
double curvature_at(const std::vector<xodr::Geometry>& plan_view, double s);

/// Value at s of a piecewise cubic (the last piece starting at or before s; the first before).
double piecewise_value(const std::vector<xodr::Poly3>& pieces, double s);

}  // namespace corsa::ngii::detail
