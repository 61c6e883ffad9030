#pragma once

// Triangulated road surface for the sensors and segmentation labels: lane surfaces (every lane
// type, so sidewalks and shoulders are there too) and road marks as thin strips slightly above.

#include <array>
#include <cstdint>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/core/vec.h"
#include "corsa/xodr/model.h"

namespace corsa::xodr {

class Map;

using corsa::Vec3;

enum class SurfaceKind : uint8_t { kLane, kRoadMark };

/// Colour of a road mark (OpenDRIVE 1.8 e_roadMarkColor; "standard" is white).
enum class MarkColor : uint8_t {
  kNone,  ///< lane surfaces
  kWhite,
  kYellow,
  kBlue,
  kGreen,
  kRed,
  kOrange,
  kViolet,
  kBlack,
};

/// What a triangle belongs to.
struct TriangleInfo {
  uint32_t road_index = 0;  ///< index into MapData::roads
  int32_t lane_id = 0;      ///< for a road mark: the lane whose outer border carries it (0: centre)
  LaneType lane_type = LaneType::kNone;
  SurfaceKind kind = SurfaceKind::kLane;
  bool in_junction = false;
  MarkColor color = MarkColor::kNone;  ///< road marks only
};

/// Triangles in map coordinates (metres), counter-clockwise seen from above (normals up).
struct RoadMesh {
  std::vector<Vec3> vertices;
  /// Per vertex, lane coordinates: [0] the road's s (m), [1] across the lanes, counted in lanes
  /// from the centre line: a border between lanes |id| k and k + 1 is at k (the centre line at
  /// 0), so a lane |id| k spans k - 1 (inner border) to k (outer) and a vertex shared by two
  /// lanes has one value. Road-mark vertices are at {0, 0}.
  std::vector<std::array<float, 2>> lane_coords;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<TriangleInfo> info;  ///< one per triangle
};

struct MeshOptions {
  /// Largest distance (m) between a lane border (or a lateral-profile cross-section) and the
  /// mesh edges that approximate it. Straight, constant-width stretches get only their ends.
  double tolerance = 0.1;
  /// Longest triangle edge along the road (m); 0 for no limit.
  double max_segment = 0.0;
  /// Road marks as strips; off gives the lane surfaces alone.
  bool road_marks = true;
  /// How far (m) marks float above the surface when their record gives no height (thickness).
  double mark_lift = 0.01;
};

/// Triangulates every lane of every lane section of `map` (zero-width stretches are left out).
/// Neighbouring lanes share their border vertices, and consecutive lane sections share theirs
/// where the borders meet (within 1 mm); where lane heights differ across a border (a raised
/// sidewalk) a vertical curb face joins the two. s is sampled adaptively, each section on its own
/// set of samples shared by all its lanes. Elevation, superelevation, lateral shape and lane
/// heights are included. Road marks (solid, broken, double, botts dots; the `curb`, `grass` and
/// `none` keywords draw nothing) become strips tagged kRoadMark. Deterministic: the same map and
/// options give the same mesh, vertex for vertex.
///
/// Warnings (once per kind): road mark types or colours this builder does not know, and lane
/// borders that fold over themselves (a border beyond the reference line's centre of curvature),
/// whose folded triangles are left out.
RoadMesh build_road_mesh(const Map& map, const MeshOptions& options,
                         corsa::Diagnostics& diagnostics);
/// Same, discarding the warnings.
RoadMesh build_road_mesh(const Map& map, const MeshOptions& options = {});

/// Short lower-case names ("white", "yellow", ...; "none" for kNone).
const char* mark_color_name(MarkColor color);

}  // namespace corsa::xodr
