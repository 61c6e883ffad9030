#pragma once

// Routes (§6.6) and trajectories (§6.7): Route with Waypoints; Trajectory with a Shape
// (Polyline, Clothoid, ClothoidSpline, Nurbs); TimeReference and following mode.

#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "corsa/xosc/common.h"
#include "corsa/xosc/enums.h"
#include "corsa/xosc/parameters.h"
#include "corsa/xosc/positions.h"

namespace corsa::xosc {

/// Where a catalog-expanded element came from (CatalogReference catalogName/entryName).
struct CatalogOrigin {
  std::string catalog_name;
  std::string entry_name;
  std::vector<ParameterAssignment> assignments;
  Source reference;  ///< the CatalogReference element
};

struct Waypoint {
  Position position;
  RouteStrategy route_strategy = RouteStrategy::kShortest;
  Source source;
};

struct Route {
  std::string name;
  bool closed = false;
  std::vector<ParameterDeclaration> parameters;
  std::vector<Waypoint> waypoints;  ///< at least two
  std::optional<CatalogOrigin> catalog;
  Source source;
};

struct Vertex {
  std::optional<double> time;  ///< s
  Position position;
  Source source;
};
struct Polyline {
  std::vector<Vertex> vertices;  ///< at least two
  Source source;
};

/// Clothoid: curvature changes linearly (curvature_prime, 1/m^2) over length, from position.
/// The 1.0 curvatureDot is read into curvature_prime with a deprecation warning.
struct Clothoid {
  double curvature = 0.0;  ///< 1/m
  std::optional<double> curvature_prime;
  double length = 0.0;  ///< m
  std::optional<double> start_time;
  std::optional<double> stop_time;
  Position position;
  Source source;
};

struct ClothoidSplineSegment {
  double curvature_start = 0.0;
  double curvature_end = 0.0;
  double length = 0.0;
  std::optional<double> h_offset;
  std::optional<double> time_start;
  std::optional<Position> position_start;
  Source source;
};
struct ClothoidSpline {
  std::vector<ClothoidSplineSegment> segments;
  std::optional<double> time_end;
  Source source;
};

struct ControlPoint {
  Position position;
  std::optional<double> time;
  std::optional<double> weight;
  Source source;
};
/// NURBS of the given order: control points and a knot vector (size = points + order).
struct Nurbs {
  uint32_t order = 2;
  std::vector<ControlPoint> control_points;
  std::vector<double> knots;
  Source source;
};

using Shape = std::variant<Polyline, Clothoid, ClothoidSpline, Nurbs>;

struct Trajectory {
  std::string name;
  bool closed = false;
  std::vector<ParameterDeclaration> parameters;
  Shape shape;
  std::optional<CatalogOrigin> catalog;
  Source source;
};

/// Timing: trajectory times map to simulation time as t_sim = t * scale + offset, absolute or
/// relative to the action start.
struct Timing {
  ReferenceContext domain_absolute_relative = ReferenceContext::kAbsolute;
  double offset = 0.0;
  double scale = 1.0;
  Source source;
};
/// TimeReference: None (ignore vertex times) or Timing.
struct TimeReference {
  std::optional<Timing> timing;  ///< empty: <None/>
  Source source;
};

}  // namespace corsa::xosc
