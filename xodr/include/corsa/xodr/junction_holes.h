#pragma once

// Holes in junctions: places inside a junction's area that no road surface covers but that the
// junction's roads (its connecting roads and the roads they join) enclose on all sides. Maps
// whose connecting roads diverge from one point (two turning paths leaving one lane) leave such
// wedges at the junction's mouths, where the real street is paved; a traffic island or the
// centre of a roundabout is a hole too, but a large one, or one with a kerb around it or
// something standing in it, and stays unpaved.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "corsa/core/vec.h"
#include "corsa/xodr/road_mesh.h"

namespace corsa::xodr {

class Map;

/// What a hole is taken for.
enum class HoleKind : uint8_t {
  kPaved,     ///< small or narrow, bordered by the junction's roadway: paved as road
  kLarge,     ///< room for a traffic island (wider and larger than the limits below)
  kKerbed,    ///< bordered by a kerb, sidewalk, median or a road not of this junction
  kOccupied,  ///< an OpenDRIVE object or signal stands in it
};

/// Short lower-case names ("paved", "large", "kerbed", "occupied").
const char* hole_kind_name(HoleKind kind);

struct JunctionHoleOptions {
  double cell = 0.1;  ///< m, side of the grid cells the junction's area is sampled on
  /// m², holes smaller than this are cracks between two roads' borders (left to the sensor
  /// world's seams) and are not reported.
  double min_area = 0.1;
  /// A hole bordered only by the junction's roadway, with nothing standing in it, is paved when
  /// it is smaller than `max_area` (m²) or no disc `max_width` (m) across fits in it. An island
  /// a map draws has a kerb, sidewalk or median lane around it or something standing in it and
  /// is kept whatever its size; an unmarked hole is taken for pavement up to 50 m², below the
  /// smallest park inside a roundabout (a single-lane roundabout's inscribed circle is at least
  /// 27 m across and its circulatory roadway at most 6 m wide, so its central island is 15 m
  /// across, 170 m²). The largest map wedges between diverging connecting roads measured: 30 m²
  /// (K-City, 3.9 m wide), 38.8 m² (Ex_LHT-Complex-X-Junction). Narrower than 1.2 m (4 ft, the
  /// narrowest raised island) a hole is no island at any length.
  double max_area = 50.0;
  double max_width = 1.2;
  /// m the paving lies under the lowest road surface around it.
  double drop = 0.002;
};

/// One hole of one junction.
struct JunctionHole {
  size_t junction = 0;  ///< index into MapData::junctions
  HoleKind kind = HoleKind::kPaved;
  double area = 0.0;   ///< m²
  double width = 0.0;  ///< m, diameter of the widest disc that fits (to the grid's cell)
  Vec3 centre;         ///< the mean of its cells, at the paving's height
  /// The paving (kPaved only): the hole's cells and a one-cell rim under the roads around it,
  /// `drop` under the plane through the surrounding road surface and under the roads of the rim,
  /// counter-clockwise seen from above.
  std::vector<Vec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
};

/// The holes of every junction with connecting roads, junction by junction in document order,
/// each junction's holes in grid order (deterministic). The junction's area is its <boundary>
/// (OpenDRIVE 1.8 §10.9) when given, else the convex hull of its connecting roads' surface.
/// `road` is the map's lane surface (road marks are ignored).
std::vector<JunctionHole> find_junction_holes(const Map& map, const RoadMesh& road,
                                              const JunctionHoleOptions& options = {});

}  // namespace corsa::xodr
