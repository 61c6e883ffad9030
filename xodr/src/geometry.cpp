// Dispatch from a planView record to its kind, and the transform from the kind's local frame
// (start at the origin, heading 0) into map coordinates (OpenDRIVE 1.8 §7.2).

#include "corsa/xodr/geometry.h"

#include <cmath>
#include <type_traits>

#include "geometry_local.h"

namespace corsa::xodr {

namespace detail {
namespace {

RefPoint evaluate_shape(const Geometry& geometry, double ds) {
  return std::visit(
      [&](const auto& shape) -> RefPoint {
        using T = std::decay_t<decltype(shape)>;
        if constexpr (std::is_same_v<T, LineGeometry>) {
          return evaluate_line(ds);
        } else if constexpr (std::is_same_v<T, ArcGeometry>) {
          return evaluate_arc(shape, ds);
        } else if constexpr (std::is_same_v<T, SpiralGeometry>) {
          return evaluate_spiral(shape, geometry.length, ds);
        } else if constexpr (std::is_same_v<T, Poly3Geometry>) {
          return evaluate_poly3(shape, ds);
        } else {
          return evaluate_param_poly3(shape, geometry.length, ds);
        }
      },
      geometry.shape);
}

LocalFrame evaluate_shape_frame(const Geometry& geometry, double ds) {
  if (std::holds_alternative<LineGeometry>(geometry.shape)) {
    return LocalFrame{evaluate_line(ds), 1.0, 0.0};
  }
  if (const auto* arc = std::get_if<ArcGeometry>(&geometry.shape)) {
    const double k = arc->curvature;
    if (k == 0.0) {
      return LocalFrame{evaluate_line(ds), 1.0, 0.0};
    }
    const double half = 0.5 * k * ds;
    const double sin_half = std::sin(half);
    const double cos_half = std::cos(half);
    const double sin_full = 2.0 * sin_half * cos_half;
    const double cos_full = 1.0 - 2.0 * sin_half * sin_half;
    return LocalFrame{RefPoint{sin_full / k, 2.0 * sin_half * sin_half / k, k * ds, k}, cos_full,
                      sin_full};
  }
  if (const auto* spiral = std::get_if<SpiralGeometry>(&geometry.shape)) {
    return evaluate_spiral_frame(*spiral, geometry.length, ds);
  }
  const RefPoint local = evaluate_shape(geometry, ds);
  return LocalFrame{local, std::cos(local.hdg), std::sin(local.hdg)};
}

/// The straight continuation of a record read outside [0, length]: `edge` is its frame at the
/// nearer end, `beyond` the signed distance past it.
LocalFrame straight_on(const LocalFrame& edge, double beyond) {
  const RefPoint& p = edge.point;
  return LocalFrame{RefPoint{p.x + beyond * edge.cos_h, p.y + beyond * edge.sin_h, p.hdg, 0.0},
                    edge.cos_h, edge.sin_h};
}

}  // namespace

// A record describes the reference line over its declared length only (OpenDRIVE 1.8 §7.2). It
// is read outside [0, length] where records overlap or leave a gap, or where a road is longer
// than its records (all warned about by Map::build): there it goes on straight along its end
// tangent. Following the formula instead would turn a short tight spiral overlapping a long line
// into thousands of radians of loops, and cost time (spiral quadrature, index chunks of 0.1 rad)
// in proportion to them, beyond the turn limit checked on the declared length.
[[gnu::hot]] RefPoint evaluate_local(const Geometry& geometry, double ds) {
  if (ds >= 0.0 && ds <= geometry.length) {
    return evaluate_shape(geometry, ds);
  }
  return evaluate_local_frame(geometry, ds).point;
}

// evaluate_local's curvature by the same branches, the paramPoly3 without its heading.
double local_curvature(const Geometry& geometry, double ds) {
  if (!(ds >= 0.0 && ds <= geometry.length)) {
    return evaluate_local_frame(geometry, ds).point.curvature;
  }
  if (const auto* poly = std::get_if<ParamPoly3Geometry>(&geometry.shape)) {
    return param_poly3_curvature(*poly, geometry.length, ds);
  }
  return evaluate_shape(geometry, ds).curvature;
}

LocalFrame evaluate_local_frame(const Geometry& geometry, double ds) {
  if (ds < 0.0) {
    return straight_on(evaluate_shape_frame(geometry, 0.0), ds);
  }
  if (ds > geometry.length) {
    return straight_on(evaluate_shape_frame(geometry, geometry.length), ds - geometry.length);
  }
  return evaluate_shape_frame(geometry, ds);
}

}  // namespace detail

RefPoint evaluate_geometry(const Geometry& geometry, double ds) {
  const RefPoint local = detail::evaluate_local(geometry, ds);
  return detail::to_world(geometry, std::cos(geometry.hdg), std::sin(geometry.hdg), local);
}

const char* geometry_kind_name(const GeometryShape& shape) {
  switch (shape.index()) {
    case 0:
      return "line";
    case 1:
      return "arc";
    case 2:
      return "spiral";
    case 3:
      return "poly3";
    default:
      return "paramPoly3";
  }
}

RefPoint evaluate_line(double ds) { return RefPoint{ds, 0.0, 0.0, 0.0}; }

[[gnu::hot]] RefPoint evaluate_arc(const ArcGeometry& arc, double ds) {
  const double k = arc.curvature;
  if (k == 0.0) {
    return evaluate_line(ds);
  }
  // §7.5: circle of radius 1/k; y = (1 - cos(k ds)) / k written as 2 sin²(k ds / 2) / k to keep
  // precision for small k ds.
  const double half = 0.5 * k * ds;
  const double sin_half = std::sin(half);
  return RefPoint{std::sin(k * ds) / k, 2.0 * sin_half * sin_half / k, k * ds, k};
}

}  // namespace corsa::xodr
