// Wavefront OBJ + MTL text of a road mesh, and write_mesh.

#include <charconv>
#include <stdexcept>
#include <string>
#include <vector>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"
#include "corsa/xodr/mesh_io.h"
#include "corsa/xodr/palette.h"
#include "corsa/xodr/parser.h"

namespace corsa::xodr {
namespace {

constexpr size_t kLaneTypes = static_cast<size_t>(LaneType::kOther) + 1;
constexpr size_t kMarkColors = static_cast<size_t>(MarkColor::kBlack) + 1;
constexpr size_t kGroups = kLaneTypes + kMarkColors;

/// Group of a triangle: its lane type, or (road marks) kLaneTypes + its colour.
size_t group_of(const TriangleInfo& info) {
  return info.kind == SurfaceKind::kRoadMark ? kLaneTypes + static_cast<size_t>(info.color)
                                             : static_cast<size_t>(info.lane_type);
}

std::string group_name(size_t group) {
  if (group >= kLaneTypes) {
    return std::string("mark_") + mark_color_name(static_cast<MarkColor>(group - kLaneTypes));
  }
  const auto type = static_cast<LaneType>(group);
  return type == LaneType::kOther ? "other" : std::string(lane_type_name(type));
}

Rgb group_color(size_t group) {
  return group >= kLaneTypes ? mark_color_rgb(static_cast<MarkColor>(group - kLaneTypes))
                             : lane_type_color(static_cast<LaneType>(group));
}

/// Room for any finite double in fixed notation: 309 digits before the point (DBL_MAX is about
/// 1.8e308), a sign, the point and up to 16 decimals.
constexpr size_t kFixedChars = 330;

void append_fixed(std::string& out, double value, int decimals) {
  char buffer[kFixedChars];
  const auto [end, error] =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals);
  if (error != std::errc{}) {
    // Cannot happen for finite values (build_road_mesh refuses others): never a field left out.
    throw std::logic_error("OBJ number does not fit its buffer");
  }
  out.append(buffer, end);
}

void append_uint(std::string& out, uint64_t value) {
  char buffer[24];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, end);
}

/// Triangle indices per group, groups in order (a counting sort: stable, deterministic).
std::vector<std::vector<uint32_t>> faces_by_group(const RoadMesh& mesh) {
  std::vector<std::vector<uint32_t>> groups(kGroups);
  for (size_t i = 0; i < mesh.info.size(); ++i) {
    groups[group_of(mesh.info[i])].push_back(static_cast<uint32_t>(i));
  }
  return groups;
}

}  // namespace

std::string mesh_to_obj(const RoadMesh& mesh, std::string_view mtl_file) {
  std::string out;
  out.reserve(mesh.vertices.size() * 40 + mesh.triangles.size() * 24 + 256);
  out += "# Corsa road mesh: map coordinates in metres, z up\n# ";
  append_uint(out, mesh.vertices.size());
  out += " vertices, ";
  append_uint(out, mesh.triangles.size());
  out += " triangles\nmtllib ";
  out += mtl_file;
  out += '\n';
  for (const Vec3& v : mesh.vertices) {
    out += "v ";
    append_fixed(out, v.x, 4);
    out += ' ';
    append_fixed(out, v.y, 4);
    out += ' ';
    append_fixed(out, v.z, 4);
    out += '\n';
  }
  const auto groups = faces_by_group(mesh);
  for (size_t g = 0; g < groups.size(); ++g) {
    if (groups[g].empty()) {
      continue;
    }
    const std::string name = group_name(g);
    out += "g " + name + "\nusemtl " + name + '\n';
    for (uint32_t face : groups[g]) {
      out += 'f';
      for (uint32_t v : mesh.triangles[face]) {
        out += ' ';
        append_uint(out, uint64_t{v} + 1);  // OBJ indices are 1-based
      }
      out += '\n';
    }
  }
  return out;
}

std::string mesh_materials_mtl(const RoadMesh& mesh) {
  std::string out = "# Corsa road mesh materials: lane types and road mark colours\n";
  const auto groups = faces_by_group(mesh);
  for (size_t g = 0; g < groups.size(); ++g) {
    if (groups[g].empty()) {
      continue;
    }
    const Rgb c = group_color(g);
    out += "newmtl " + group_name(g) + "\nKd ";
    append_fixed(out, c.r / 255.0, 4);
    out += ' ';
    append_fixed(out, c.g / 255.0, 4);
    out += ' ';
    append_fixed(out, c.b / 255.0, 4);
    out += "\nd 1\nillum 1\n";
  }
  return out;
}

void write_mesh(const RoadMesh& mesh, const std::filesystem::path& path, PlyEncoding encoding) {
  const std::string extension = corsa::to_lower(path.extension().string());
  if (extension == ".ply") {
    write_file_atomic(path, mesh_to_ply(mesh, encoding), true);
    return;
  }
  if (extension != ".obj") {
    throw InputError(
        make_error(path.string(), 0,
                   "unknown mesh format '" + path.extension().string() + "' (use .obj or .ply)"));
  }
  std::filesystem::path mtl = path;
  mtl.replace_extension(".mtl");
  // The materials first: an OBJ that appears always has its .mtl.
  write_file_atomic(mtl, mesh_materials_mtl(mesh));
  write_file_atomic(path, mesh_to_obj(mesh, mtl.filename().string()));
}

}  // namespace corsa::xodr
