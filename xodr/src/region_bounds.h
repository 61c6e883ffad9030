#pragma once

// Cheap, conservative bounds of where a lane section lies in the world, from its records alone
// (no evaluation along the road): the spatial index uses them to decide which sections a query
// can need before it builds their chunks (spatial_index.h). Private to corsa_xodr.
//
// The bound holds every chunk rectangle the index builds for the section: the reference line
// (each planView record bounded by its length, or by its polynomial's coefficients), widened by
// the farthest any lane border can be (laneOffset, widths and borders bounded by their
// coefficients over the section) and by the most a chunk rectangle reaches past its samples.

#include <cstddef>

namespace corsa::xodr {
class Map;
}

namespace corsa::xodr::detail {

struct Bounds {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;  ///< m

  bool contains(double x, double y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
  /// Whether the square of half side r about (x, y) meets the box.
  bool meets(double x, double y, double r) const {
    return x + r >= x0 && x - r <= x1 && y + r >= y0 && y - r <= y1;
  }
};

/// The bound of lane section `section` of road `road`, or false when its records allow none
/// (poly3 reference lines, parametric cubics whose speed may vanish, non-finite numbers): such a
/// section is taken to be anywhere.
bool section_bounds(const Map& map, size_t road, size_t section, Bounds& out);

}  // namespace corsa::xodr::detail
