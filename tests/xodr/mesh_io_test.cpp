// OBJ and PLY files of the road mesh, read back with small readers written here.

#include "corsa/xodr/mesh_io.h"

#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/xodr/parser.h"
#include "mesh_test_util.h"
#include "temp_dir.h"

using namespace corsa::xodr;
using namespace corsa::xodr::mesh_test;

namespace {

std::string group_of(const TriangleInfo& info) {
  if (info.kind == SurfaceKind::kRoadMark) {
    return std::string("mark_") + mark_color_name(info.color);
  }
  return info.lane_type == LaneType::kOther ? "other" : std::string(lane_type_name(info.lane_type));
}

struct ObjFile {
  std::string mtllib;
  std::vector<Vec3> vertices;
  std::vector<std::pair<std::array<uint32_t, 3>, std::string>> faces;  // with their group
  std::vector<std::string> materials;                                  // usemtl, in order
};

ObjFile read_obj(const std::string& text) {
  ObjFile obj;
  std::istringstream in(text);
  std::string line;
  std::string group;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string key;
    fields >> key;
    if (key == "v") {
      Vec3 v;
      fields >> v.x >> v.y >> v.z;
      obj.vertices.push_back(v);
    } else if (key == "f") {
      std::array<uint32_t, 3> f{};
      fields >> f[0] >> f[1] >> f[2];
      for (uint32_t& i : f) {
        --i;  // 1-based
      }
      obj.faces.emplace_back(f, group);
    } else if (key == "g") {
      fields >> group;
    } else if (key == "usemtl") {
      std::string name;
      fields >> name;
      obj.materials.push_back(name);
      CHECK(name == group);
    } else if (key == "mtllib") {
      fields >> obj.mtllib;
    }
  }
  return obj;
}

/// A PLY of the layout mesh_to_ply writes: header, then vertices and faces with their labels.
struct PlyFace {
  std::array<uint32_t, 3> v{};
  int lane_type = 0, kind = 0, color = 0, junction = 0;
  uint32_t road = 0;
  int32_t lane = 0;
};
struct PlyFile {
  std::string format;
  std::vector<Vec3> vertices;
  std::vector<PlyFace> faces;
};

template <typename T>
T take(const std::string& bytes, size_t& at) {
  T value;
  REQUIRE(at + sizeof(T) <= bytes.size());
  std::memcpy(&value, bytes.data() + at, sizeof(T));  // the test machine is little-endian
  at += sizeof(T);
  return value;
}

PlyFile read_ply(const std::string& bytes) {
  PlyFile ply;
  const size_t end = bytes.find("end_header\n");
  REQUIRE(end != std::string::npos);
  std::istringstream header(bytes.substr(0, end));
  std::string line;
  size_t vertices = 0;
  size_t faces = 0;
  std::vector<std::string> properties;
  while (std::getline(header, line)) {
    std::istringstream fields(line);
    std::string key;
    fields >> key;
    if (key == "format") {
      fields >> ply.format;
    } else if (key == "element") {
      std::string name;
      size_t count = 0;
      fields >> name >> count;
      (name == "vertex" ? vertices : faces) = count;
    } else if (key == "property") {
      properties.push_back(line);
    }
  }
  REQUIRE(properties.size() == 10);
  CHECK(properties[3] == "property list uchar uint vertex_indices");
  size_t at = end + std::strlen("end_header\n");
  if (ply.format == "binary_little_endian") {
    for (size_t i = 0; i < vertices; ++i) {
      const double x = take<double>(bytes, at);
      const double y = take<double>(bytes, at);
      const double z = take<double>(bytes, at);
      ply.vertices.push_back(Vec3{x, y, z});
    }
    for (size_t i = 0; i < faces; ++i) {
      PlyFace f;
      REQUIRE(take<uint8_t>(bytes, at) == 3);
      for (uint32_t& v : f.v) {
        v = take<uint32_t>(bytes, at);
      }
      f.lane_type = take<uint8_t>(bytes, at);
      f.kind = take<uint8_t>(bytes, at);
      f.color = take<uint8_t>(bytes, at);
      f.road = take<uint32_t>(bytes, at);
      f.lane = take<int32_t>(bytes, at);
      f.junction = take<uint8_t>(bytes, at);
      ply.faces.push_back(f);
    }
    CHECK(at == bytes.size());
    return ply;
  }
  std::istringstream body(bytes.substr(at));
  for (size_t i = 0; i < vertices; ++i) {
    Vec3 v;
    body >> v.x >> v.y >> v.z;
    ply.vertices.push_back(v);
  }
  for (size_t i = 0; i < faces; ++i) {
    PlyFace f;
    int count = 0;
    body >> count >> f.v[0] >> f.v[1] >> f.v[2] >> f.lane_type >> f.kind >> f.color >> f.road >>
        f.lane >> f.junction;
    REQUIRE(count == 3);
    ply.faces.push_back(f);
  }
  std::string rest;
  body >> rest;
  CHECK(rest.empty());
  return ply;
}

void check_ply_matches(const PlyFile& ply, const RoadMesh& mesh) {
  REQUIRE(ply.vertices.size() == mesh.vertices.size());
  REQUIRE(ply.faces.size() == mesh.triangles.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    // Both encodings give the doubles back exactly (ASCII uses the shortest exact text).
    REQUIRE(ply.vertices[i].x == mesh.vertices[i].x);
    REQUIRE(ply.vertices[i].y == mesh.vertices[i].y);
    REQUIRE(ply.vertices[i].z == mesh.vertices[i].z);
  }
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const PlyFace& f = ply.faces[i];
    const TriangleInfo& info = mesh.info[i];
    REQUIRE(f.v == mesh.triangles[i]);
    REQUIRE(f.lane_type == static_cast<int>(info.lane_type));
    REQUIRE(f.kind == static_cast<int>(info.kind));
    REQUIRE(f.color == static_cast<int>(info.color));
    REQUIRE(f.road == info.road_index);
    REQUIRE(f.lane == info.lane_id);
    REQUIRE(f.junction == (info.in_junction ? 1 : 0));
  }
}

}  // namespace

TEST_CASE("an OBJ of the mesh reads back with its groups and materials", "[xodr][mesh][io]") {
  const Map map = load(shared_map("fabriksgatan.xodr"));
  const RoadMesh mesh = build_road_mesh(map);
  corsa::test::TempDir dir;
  write_mesh(mesh, dir.path() / "town.obj");
  REQUIRE(std::filesystem::exists(dir.path() / "town.mtl"));
  const ObjFile obj = read_obj(corsa::read_file(dir.path() / "town.obj"));
  CHECK(obj.mtllib == "town.mtl");
  REQUIRE(obj.vertices.size() == mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    REQUIRE(distance(obj.vertices[i], mesh.vertices[i]) < 1e-4);  // written to 0.1 mm
  }
  // The same triangles, each in the group of its lane type (or mark colour).
  REQUIRE(obj.faces.size() == mesh.triangles.size());
  std::map<std::array<uint32_t, 3>, std::string> expected;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    expected[mesh.triangles[i]] = group_of(mesh.info[i]);
  }
  for (const auto& [face, group] : obj.faces) {
    REQUIRE(expected.count(face) == 1);
    CHECK(expected[face] == group);
  }
  // Every material used is defined in the .mtl, sidewalks and marks among them.
  const std::string mtl = corsa::read_file(dir.path() / "town.mtl");
  for (const std::string& material : obj.materials) {
    CHECK_THAT(mtl, Catch::Contains("newmtl " + material + "\nKd "));
  }
  CHECK(std::count(obj.materials.begin(), obj.materials.end(), "sidewalk") == 1);
  CHECK(std::count(obj.materials.begin(), obj.materials.end(), "mark_white") == 1);
}

TEST_CASE("a binary and an ASCII PLY of the mesh read back exactly", "[xodr][mesh][io]") {
  const Map map = load(shared_map("Ex_Entry_Exit.xodr"));
  const RoadMesh mesh = build_road_mesh(map);
  corsa::test::TempDir dir;
  write_mesh(mesh, dir.path() / "binary.ply");
  write_mesh(mesh, dir.path() / "text.PLY", PlyEncoding::kAscii);
  const PlyFile binary = read_ply(corsa::read_file(dir.path() / "binary.ply"));
  CHECK(binary.format == "binary_little_endian");
  check_ply_matches(binary, mesh);
  const PlyFile text = read_ply(corsa::read_file(dir.path() / "text.PLY"));
  CHECK(text.format == "ascii");
  check_ply_matches(text, mesh);
  CHECK(dir.entries() == 2);  // no temporaries left behind
}

TEST_CASE("mesh files are byte-identical for the same mesh", "[xodr][mesh][io]") {
  const Map map = load(shared_map("two_plus_one.xodr"));
  CHECK(mesh_to_obj(build_road_mesh(map), "a.mtl") == mesh_to_obj(build_road_mesh(map), "a.mtl"));
  CHECK(mesh_to_ply(build_road_mesh(map), PlyEncoding::kBinary) ==
        mesh_to_ply(build_road_mesh(map), PlyEncoding::kBinary));
}

TEST_CASE("a mesh file of another format is refused", "[xodr][mesh][io]") {
  const RoadMesh mesh;
  corsa::test::TempDir dir;
  try {
    write_mesh(mesh, dir.path() / "map.stl");
    FAIL("no error");
  } catch (const corsa::InputError& error) {
    CHECK_THAT(error.diagnostic().message, Catch::Contains(".obj or .ply"));
  }
  CHECK(dir.entries() == 0);
}
