#pragma once

// Fitting OpenDRIVE plan-view records (lines, arcs, clothoids; OpenDRIVE 1.8 §7.4-7.5) and
// cubic profiles (elevation, lane widths; §8.4, §9.5) to surveyed points, within a tolerance,
// with as few records as the tolerance allows rather than one per vertex.

#include <optional>
#include <span>
#include <vector>

#include "corsa/core/vec.h"
#include "corsa/xodr/model.h"

namespace corsa::ngii {

using Point2 = corsa::Vec2;

struct CurveFitOptions {
  /// Largest distance (m) allowed between an input vertex and the fitted line.
  double tolerance = 0.05;
  /// Input vertices farther apart than this (m) get points in between (held to 3x the
  /// tolerance), so that the fitted line cannot wander between sparse vertices.
  double max_spacing = 4.0;
  /// Curvature (1/m) beyond which a piece is rejected as unphysical (radius 1 m: the reference
  /// line of a 3 m U-turn lane, shifted half a lane inward, turns at about 1.4 m).
  double max_curvature = 1.0;
  /// Heading (rad) the chain must start with; fitted when not given.
  std::optional<double> start_heading;
  /// Heading (rad) the chain must end with (within end_heading_tolerance); when not given, the
  /// last record ends as the data nearest its end asks.
  std::optional<double> end_heading;
  /// rad: how closely the chain keeps `end_heading` (0.002: 3 cm across a 16 m wide road end).
  double end_heading_tolerance = 0.002;
};

struct CurveFit {
  /// Consecutive records from s = 0: each starts where the previous ends, with the same heading
  /// (G1) except at those `kinks` that could not be turned on an arc.
  std::vector<xodr::Geometry> geometries;
  double length = 0.0;     ///< total length (m)
  double max_error = 0.0;  ///< largest distance (m) of an input vertex from the fitted line
  /// Corners where the input turns too sharply for the records within the tolerance: turned on
  /// a short arc tighter than max_curvature (the chain stays G1), or, where even that fails,
  /// with a heading jump. Counted; the error there is in max_error.
  int kinks = 0;
};

/// Fits a G1 chain of lines, arcs and clothoids to the polyline `points` (at least 2 points,
/// consecutive duplicates allowed). The chain starts exactly at the first point; its start
/// heading is fitted; it ends at the projection of the last point. Greedy: each record is grown
/// over as many vertices as the tolerance allows, and the simplest kind (line, arc, clothoid)
/// that reaches as far is kept.
CurveFit fit_plan_view(std::span<const Point2> points, const CurveFitOptions& options = {});

/// A sample of a scalar profile: value v at position s (sorted by s).
struct ProfileSample {
  double s = 0.0;
  double v = 0.0;
};

struct ProfileFit {
  std::vector<xodr::Poly3> pieces;  ///< Poly3::s is the piece start (same frame as the samples)
  double max_error = 0.0;           ///< largest |fitted - sample| (m)
};

/// Fits a chain of cubics to `samples` within `tolerance`: the value is continuous, and so is the
/// slope unless a piece with a free slope at the joint reaches further (a real kink in the data).
/// Each piece is as long as the tolerance allows, stays between neighbouring samples (no ringing),
/// and is as simple as possible (constant, linear, quadratic, cubic). `samples` must be sorted by
/// s and non-empty; the first piece starts at samples[0].s.
ProfileFit fit_profile(std::span<const ProfileSample> samples, double tolerance);

}  // namespace corsa::ngii
