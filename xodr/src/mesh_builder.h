#pragma once

// Accumulates the road mesh: vertices, triangles with their info, and the warnings of the build.
// Private to corsa_xodr.

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "corsa/xodr/road_marks.h"
#include "corsa/xodr/road_mesh.h"
#include "mesh_section.h"

namespace corsa::xodr::detail {

/// Vertex of a border on the last row of a lane section, offered to the next section's first
/// row so that the two share it (no crack across the section boundary).
struct SeamVertex {
  Vec3 p;               ///< position, lane height included
  double height = 0.0;  ///< lane height on top of the surface (m)
  uint32_t index = 0;
};

class MeshBuilder {
 public:
  /// `file`: the map's source file, for warnings.
  MeshBuilder(RoadMesh& mesh, corsa::Diagnostics& diagnostics, std::string file)
      : mesh_(mesh), diagnostics_(diagnostics), file_(std::move(file)) {}

  /// `lane`: the vertex's lane coordinates (RoadMesh::lane_coords).
  uint32_t add_vertex(const Vec3& p, std::array<float, 2> lane = {0.0F, 0.0F});
  const Vec3& vertex(uint32_t index) const { return mesh_.vertices[index]; }
  /// Adds a triangle that should face up: added when it is counter-clockwise seen from above
  /// with a non-zero area; a clockwise one means the surface folds over itself there (a border
  /// beyond the centre of curvature), which is left out with a warning (once per road, near
  /// road s). With a null `fold_road` (across a jump, and road marks) clockwise triangles and
  /// slivers thinner than a millimetre are dropped silently.
  void add_upward(uint32_t a, uint32_t b, uint32_t c, const TriangleInfo& info,
                  const Road* fold_road, double s);
  /// Adds a triangle as given (vertical faces, whose orientation the caller chose).
  void add_any(uint32_t a, uint32_t b, uint32_t c, const TriangleInfo& info);

  corsa::Diagnostics& diagnostics() { return diagnostics_; }

  /// Removes the vertices no triangle uses (renumbering the others in order).
  void compact();

 private:
  RoadMesh& mesh_;
  corsa::Diagnostics& diagnostics_;
  std::string file_;
};

/// Triangles of every lane of one section over its samples (`tolerance` sets the extra columns
/// on roads with a lateral shape). `seam` holds the previous section's last-row border vertices
/// on entry (empty for a road's first section) and this section's on return.
void mesh_section_lanes(const SectionView& view, const SectionSamples& samples, double tolerance,
                        MeshBuilder& builder, std::vector<SeamVertex>& seam);

/// The painted lines of one section's road marks (unknown types and colours are warned about).
void section_mark_lines(const SectionView& view, const SectionSamples& samples,
                        const MeshOptions& options, corsa::Diagnostics& diagnostics,
                        std::vector<MarkLine>& out);

/// A mark line as a strip of triangles (kind kRoadMark).
void mesh_mark_line(const MarkLine& line, MeshBuilder& builder);

}  // namespace corsa::xodr::detail
