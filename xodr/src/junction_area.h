#pragma once

// A junction's area for the holes search (junction_holes.cpp): the polygon of its <boundary>
// (OpenDRIVE 1.8 §10.9), or the convex hull of its connecting roads' surface, and the grid rows
// that lie inside it.

#include <cstdint>
#include <vector>

#include "corsa/xodr/map.h"

namespace corsa::xodr::detail {

struct Vec2d {
  double x = 0.0, y = 0.0;
};

/// Convex hull (Andrew's monotone chain), counter-clockwise.
std::vector<Vec2d> convex_hull(std::vector<Vec2d> points);

/// Marks the cells of one grid row (centres at y, x0 + (i + 0.5) cell) that lie inside the
/// closed polygon, by the even-odd rule: between pairs of the row's crossings with its edges.
/// `crossings` is scratch space.
void fill_row(const std::vector<Vec2d>& polygon, double y, double x0, double cell,
              std::vector<double>& crossings, uint8_t* row, int nx);

/// The polygon of a junction's <boundary>, in order; empty when it has none (or fewer than three
/// points evaluate).
std::vector<Vec2d> boundary_outline(const Map& map, const Junction& junction);

}  // namespace corsa::xodr::detail
