#pragma once

// Road mesh files for 3D viewers: Wavefront OBJ (with its .mtl) and PLY, written by Corsa's own
// small writers. Coordinates are the map's (metres, z up), vertices in mesh order. Same mesh,
// same bytes.

#include <filesystem>
#include <string>
#include <string_view>

#include "corsa/xodr/road_mesh.h"

namespace corsa::xodr {

enum class PlyEncoding { kBinary, kAscii };

/// OBJ text: `mtllib <mtl_file>`, the vertices (0.1 mm), then the faces grouped (`g`, `usemtl`)
/// by lane type (`driving`, `sidewalk`, ...; every lane type's OpenDRIVE name) and, for road
/// marks, by colour (`mark_white`, `mark_yellow`, ...). Groups in a fixed order.
std::string mesh_to_obj(const RoadMesh& mesh, std::string_view mtl_file);
/// The materials the OBJ uses (diffuse colours from palette.h).
std::string mesh_materials_mtl(const RoadMesh& mesh);
/// PLY 1.0: double x, y, z per vertex; per face the vertex indices and `lane_type` (LaneType
/// code, names listed in `comment lane_type` lines), `kind` (0 lane, 1 road mark), `color`
/// (MarkColor code), `road` (road index), `lane` (lane id), `junction` (0/1).
std::string mesh_to_ply(const RoadMesh& mesh, PlyEncoding encoding);

/// Writes `path` by its extension: .obj (and the .mtl of the same stem next to it) or .ply,
/// each atomically (corsa::AtomicFile). Throws InputError for another extension or an I/O error.
void write_mesh(const RoadMesh& mesh, const std::filesystem::path& path,
                PlyEncoding encoding = PlyEncoding::kBinary);

}  // namespace corsa::xodr
