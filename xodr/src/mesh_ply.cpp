// PLY 1.0 (binary little-endian or ASCII) of a road mesh, with per-face labels.

#include <bit>
#include <charconv>
#include <cstdint>
#include <string>

#include "corsa/xodr/mesh_io.h"
#include "corsa/xodr/parser.h"

namespace corsa::xodr {
namespace {

void put_le(std::string& out, uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) {
    out += static_cast<char>((value >> (8 * i)) & 0xffu);
  }
}

void append_number(std::string& out, double value) {
  char buffer[64];
  // Shortest text that reads back to the same double.
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, error == std::errc{} ? end : buffer);
}

template <typename Int>
void append_int(std::string& out, Int value) {
  char buffer[24];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, end);
}

std::string header(const RoadMesh& mesh, PlyEncoding encoding) {
  std::string out = "ply\nformat ";
  out += encoding == PlyEncoding::kBinary ? "binary_little_endian" : "ascii";
  out += " 1.0\ncomment Corsa road mesh: map coordinates in metres, z up\n";
  for (int t = 0; t <= static_cast<int>(LaneType::kOther); ++t) {
    const auto type = static_cast<LaneType>(t);
    out += "comment lane_type " + std::to_string(t) + ' ' +
           (type == LaneType::kOther ? std::string("other") : std::string(lane_type_name(type))) +
           '\n';
  }
  out += "comment kind 0 lane, 1 road mark\n";
  for (int c = 0; c <= static_cast<int>(MarkColor::kBlack); ++c) {
    out += "comment color " + std::to_string(c) + ' ' + mark_color_name(static_cast<MarkColor>(c)) +
           '\n';
  }
  out += "element vertex " + std::to_string(mesh.vertices.size()) + '\n';
  out += "property double x\nproperty double y\nproperty double z\n";
  out += "element face " + std::to_string(mesh.triangles.size()) + '\n';
  out += "property list uchar uint vertex_indices\n";
  out += "property uchar lane_type\nproperty uchar kind\nproperty uchar color\n";
  out += "property uint road\nproperty int lane\nproperty uchar junction\nend_header\n";
  return out;
}

}  // namespace

std::string mesh_to_ply(const RoadMesh& mesh, PlyEncoding encoding) {
  std::string out = header(mesh, encoding);
  if (encoding == PlyEncoding::kBinary) {
    out.reserve(out.size() + mesh.vertices.size() * 24 + mesh.triangles.size() * 25);
    for (const Vec3& v : mesh.vertices) {
      for (double c : {v.x, v.y, v.z}) {
        put_le(out, std::bit_cast<uint64_t>(c), 8);
      }
    }
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      const TriangleInfo& info = mesh.info[i];
      put_le(out, 3, 1);
      for (uint32_t index : mesh.triangles[i]) {
        put_le(out, index, 4);
      }
      put_le(out, static_cast<uint64_t>(info.lane_type), 1);
      put_le(out, static_cast<uint64_t>(info.kind), 1);
      put_le(out, static_cast<uint64_t>(info.color), 1);
      put_le(out, info.road_index, 4);
      put_le(out, std::bit_cast<uint32_t>(info.lane_id), 4);
      put_le(out, info.in_junction ? 1 : 0, 1);
    }
    return out;
  }
  for (const Vec3& v : mesh.vertices) {
    append_number(out, v.x);
    out += ' ';
    append_number(out, v.y);
    out += ' ';
    append_number(out, v.z);
    out += '\n';
  }
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const TriangleInfo& info = mesh.info[i];
    out += '3';
    for (uint32_t index : mesh.triangles[i]) {
      out += ' ';
      append_int(out, index);
    }
    for (int value : {static_cast<int>(info.lane_type), static_cast<int>(info.kind),
                      static_cast<int>(info.color)}) {
      out += ' ';
      append_int(out, value);
    }
    out += ' ';
    append_int(out, info.road_index);
    out += ' ';
    append_int(out, info.lane_id);
    out += info.in_junction ? " 1\n" : " 0\n";
  }
  return out;
}

}  // namespace corsa::xodr
