#pragma once

// Helpers of the road-mesh and map-render tests: the shared maps, small roads built in memory,
// and a little geometry on meshes.

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "corsa/xodr/map.h"
#include "corsa/xodr/road_mesh.h"

namespace corsa::xodr::mesh_test {

inline std::filesystem::path shared_map(const std::string& name) {
  return std::filesystem::path(CORSA_SHARED_DIR) / "data" / "xodr" / name;
}

/// Every .xodr of ../shared/data/xodr and of the ASAM OpenSCENARIO conformance databases.
inline std::vector<std::filesystem::path> all_shared_maps() {
  std::vector<std::filesystem::path> maps;
  for (const auto* dir : {"data/xodr", "conformance/asam-osc-1.3/Databases"}) {
    const auto folder = std::filesystem::path(CORSA_SHARED_DIR) / dir;
    if (!std::filesystem::is_directory(folder)) {
      continue;
    }
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
      if (entry.path().extension() == ".xodr") {
        maps.push_back(entry.path());
      }
    }
  }
  std::sort(maps.begin(), maps.end());
  return maps;
}

inline Map load(const std::filesystem::path& path) {
  corsa::Diagnostics diagnostics;
  return Map::load(path, diagnostics);
}

/// One lane of a road built in memory (constant width unless `widths` is given).
struct LaneSpec {
  LaneSpec(int id_, LaneType type_ = LaneType::kDriving, double width_ = 3.5,
           std::vector<Poly3> widths_ = {}, std::vector<LaneHeight> heights_ = {},
           std::vector<RoadMark> marks_ = {})
      : id(id_),
        type(type_),
        width(width_),
        widths(std::move(widths_)),
        heights(std::move(heights_)),
        marks(std::move(marks_)) {}

  int id = 0;
  LaneType type = LaneType::kDriving;
  double width = 3.5;
  std::vector<Poly3> widths;  ///< overrides `width` when not empty
  std::vector<LaneHeight> heights;
  std::vector<RoadMark> marks;
};

inline Geometry geometry(double s, double x, double y, double hdg, double length,
                         GeometryShape shape = LineGeometry{}) {
  return Geometry{.s = s, .x = x, .y = y, .hdg = hdg, .length = length, .shape = shape};
}

/// A road with one lane section of `lanes` (the centre lane is added when missing).
inline Road make_road(const std::string& id, std::vector<Geometry> plan_view,
                      std::vector<LaneSpec> lanes) {
  Road road;
  road.id = id;
  for (const Geometry& g : plan_view) {
    road.length += g.length;
  }
  road.plan_view = std::move(plan_view);
  if (std::none_of(lanes.begin(), lanes.end(), [](const LaneSpec& l) { return l.id == 0; })) {
    lanes.push_back(LaneSpec{0, LaneType::kNone, 0.0, {}, {}, {}});
  }
  std::sort(lanes.begin(), lanes.end(),
            [](const LaneSpec& a, const LaneSpec& b) { return a.id > b.id; });
  LaneSection section;
  for (const LaneSpec& spec : lanes) {
    Lane lane;
    lane.id = spec.id;
    lane.type = spec.type;
    lane.type_name = "lane";
    if (spec.id != 0) {
      lane.widths =
          spec.widths.empty() ? std::vector<Poly3>{Poly3{0.0, spec.width, 0, 0, 0}} : spec.widths;
    }
    lane.heights = spec.heights;
    lane.road_marks = spec.marks;
    section.lanes.push_back(lane);
  }
  road.lane_sections.push_back(section);
  return road;
}

inline Map build(std::vector<Road> roads, corsa::Diagnostics& diagnostics) {
  MapData data;
  data.roads = std::move(roads);
  data.source_file = "memory.xodr";
  return Map::build(std::move(data), diagnostics);
}

inline Map build(std::vector<Road> roads) {
  corsa::Diagnostics diagnostics;
  return build(std::move(roads), diagnostics);
}

inline RoadMark mark(const std::string& type, const std::string& color = "standard",
                     double width = 0.12) {
  RoadMark m;
  m.type = type;
  m.color = color;
  m.width = width;
  return m;
}

// --- geometry on meshes -----------------------------------------------------------------------

/// Twice the signed area seen from above (positive: counter-clockwise).
inline double area2_xy(const Vec3& a, const Vec3& b, const Vec3& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

inline Vec3 normal(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
  const double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  return Vec3{uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
}

inline double distance(const Vec3& a, const Vec3& b) {
  return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) +
                   (a.z - b.z) * (a.z - b.z));
}

inline double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const double abx = b.x - a.x, aby = b.y - a.y, abz = b.z - a.z;
  const double length2 = abx * abx + aby * aby + abz * abz;
  double u =
      length2 > 0.0 ? ((p.x - a.x) * abx + (p.y - a.y) * aby + (p.z - a.z) * abz) / length2 : 0.0;
  u = std::clamp(u, 0.0, 1.0);
  return distance(p, Vec3{a.x + u * abx, a.y + u * aby, a.z + u * abz});
}

/// Barycentric interpolation of z at (x, y) when the triangle covers it seen from above.
inline bool z_at(const Vec3& a, const Vec3& b, const Vec3& c, double x, double y, double& z) {
  const double d = area2_xy(a, b, c);
  if (std::abs(d) < 1e-12) {
    return false;
  }
  const Vec3 p{x, y, 0.0};
  const double wa = area2_xy(p, b, c) / d;
  const double wb = area2_xy(a, p, c) / d;
  const double wc = 1.0 - wa - wb;
  const double eps = 1e-9;
  if (wa < -eps || wb < -eps || wc < -eps) {
    return false;
  }
  z = wa * a.z + wb * b.z + wc * c.z;
  return true;
}

/// The edges (vertex index pairs, smaller first) of the selected triangles with how many of
/// them use each.
template <typename Select>
std::map<std::pair<uint32_t, uint32_t>, int> edge_counts(const RoadMesh& mesh, Select select) {
  std::map<std::pair<uint32_t, uint32_t>, int> counts;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (!select(mesh.info[i])) {
      continue;
    }
    const auto& t = mesh.triangles[i];
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = t[static_cast<size_t>(k)];
      const uint32_t b = t[static_cast<size_t>((k + 1) % 3)];
      ++counts[{std::min(a, b), std::max(a, b)}];
    }
  }
  return counts;
}

/// The boundary edges (used by one selected triangle only) as segments.
template <typename Select>
std::vector<std::pair<Vec3, Vec3>> boundary_segments(const RoadMesh& mesh, Select select) {
  std::vector<std::pair<Vec3, Vec3>> segments;
  for (const auto& [edge, count] : edge_counts(mesh, select)) {
    if (count == 1) {
      segments.emplace_back(mesh.vertices[edge.first], mesh.vertices[edge.second]);
    }
  }
  return segments;
}

inline double distance_to_segments(const std::vector<std::pair<Vec3, Vec3>>& segments,
                                   const Vec3& p) {
  double best = 1e300;
  for (const auto& [a, b] : segments) {
    best = std::min(best, distance_to_segment(p, a, b));
  }
  return best;
}

}  // namespace corsa::xodr::mesh_test
