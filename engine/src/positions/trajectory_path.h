#pragma once

// A Trajectory's shape (OpenSCENARIO 1.3 §6.7: Polyline, Clothoid, ClothoidSpline, Nurbs) as a
// path parametrised by arc length, for TrajectoryPosition (and FollowTrajectoryAction).
// Polylines and clothoids are evaluated exactly; NURBS curves are sampled densely into a
// polyline first.

#include <optional>
#include <vector>

#include "corsa/xosc/trajectories.h"
#include "positions/position_resolver.h"

namespace corsa::engine::detail {

struct SimState;

struct PathPoint {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
  double h = 0.0;  ///< heading of the path, rad
};

class TrajectoryPath {
 public:
  struct Segment {
    bool clothoid = false;
    double s0 = 0.0;                                    ///< path s where the segment starts
    double length = 0.0;                                ///< m
    double x = 0.0, y = 0.0, z = 0.0, h = 0.0;          ///< start point and heading
    double z_end = 0.0;                                 ///< lines: z at the end (linear in between)
    double curvature_start = 0.0, curvature_end = 0.0;  ///< clothoids, 1/m
  };

  void add(Segment segment);
  double length() const { return length_; }
  bool empty() const { return segments_.empty(); }
  /// The point at arc length s (clamped to [0, length]).
  PathPoint at(double s) const;

  /// Trajectory times (s) of points along the path (vertex, clothoid and control point times),
  /// for FollowTrajectoryAction's Timing; kept only while both s and time increase.
  void add_time(double s, double time);
  /// True with at least two timed points.
  bool timed() const { return timeline_.size() >= 2; }
  /// Arc length at trajectory time `time`, linear between timed points, clamped to the ends.
  double s_at_time(double time) const;
  /// Trajectory time at arc length s, linear between timed points, clamped to the ends.
  double time_at_s(double s) const;
  double first_time() const { return timeline_.front().second; }
  double last_time() const { return timeline_.back().second; }
  double last_timed_s() const { return timeline_.back().first; }

  /// A polyline vertex at arc length s (in order along the path) and the heading its position
  /// states, if it states one (OpenSCENARIO 1.3 §6.9: a trajectory of six dimensions gives the
  /// entity's orientation along it too).
  void add_vertex(double s, std::optional<double> heading);
  /// The heading stated by the last vertex at or before s: nothing if that vertex states none
  /// or the shape has no vertices (clothoids, splines, NURBS).
  std::optional<double> stated_heading_at(double s) const;
  /// The index (in the order added) of the last vertex at or before s; 0 without vertices.
  size_t vertex_index_at(double s) const;

 private:
  std::vector<Segment> segments_;
  std::vector<std::pair<double, double>> timeline_;                 ///< (s, time), both increasing
  std::vector<std::pair<double, std::optional<double>>> vertices_;  ///< (s, stated heading)
  double length_ = 0.0;
};

/// True if `trajectory` gives times to at least two of its points (vertices, clothoid start and
/// stop, spline segments and end, control points): what a Timing needs to set the speed.
bool states_times(const xosc::Trajectory& trajectory);

/// Builds the path of `trajectory`; vertex and control point positions are resolved now.
/// Throws InputError (located) for degenerate shapes (fewer than two points, a NURBS with a
/// knot vector of the wrong size).
TrajectoryPath build_trajectory_path(const xosc::Trajectory& trajectory, const SimState& state,
                                     std::optional<uint32_t> self);

ResolvedPosition resolve_trajectory_position(const xosc::TrajectoryPosition& position,
                                             const SimState& state, std::optional<uint32_t> self);

}  // namespace corsa::engine::detail
