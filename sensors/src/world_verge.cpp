// Verges: where a road's or a sidewalk's outer edge meets the ground, a strip of terrain 0.8 m
// wide runs from just under the edge down to the ground (which lies 8 cm or more under the road,
// build_ground). It carries lane coordinates as uvs (u along the road, v from 0 at the edge to
// 0.5 at its outer side, a "lane" twice its width), so the terrain pattern knows how far a point
// is from the edge and thins the grass into a trodden, dusty verge there instead of a hard line
// (patterns.cpp, terrain); at its outer side it is the ground's grass exactly. Lanes of class
// terrain (borders, medians) carry their own lane coordinates and need no strip. No strip where
// the ground is far below the edge (bridges, embankments) or where another road's lane lies.

#include <algorithm>
#include <cmath>
#include <optional>

#include "corsa/sensors/semantic.h"
#include "world_build.h"

namespace corsa::sensors::detail {
namespace {

constexpr double kVergeWidth = 0.8;        ///< m beyond the edge
constexpr double kVergeUnderEdge = 0.03;   ///< m the strip reaches under the road's edge
constexpr double kVergeEdgeDrop = 0.012;   ///< m the strip lies under the road surface at the edge
constexpr double kVergeOverGround = 0.02;  ///< m above the ground mesh at its outer side
constexpr double kVergeMaxDrop = 0.5;      ///< m of ground below the edge beyond which no strip
constexpr double kVergeStep = 1.5;         ///< m between cross sections along the road

/// One cross section of a verge strip: its two vertices, or nothing where there is none.
struct VergeSection {
  bool valid = false;
  Vec3 inner;
  Vec3 outer;
  double s = 0.0;
};

/// The outermost lane on `side` at s, when it is one the road mesh draws as a hard surface (not
/// terrain): its outer border's t.
std::optional<double> verge_hard_edge(const xodr::Map& map, size_t r, double s, int side,
                                      std::vector<xodr::LaneSpan>& spans) {
  map.lane_spans(r, s, spans);
  const xodr::LaneSpan* outer = nullptr;
  for (const auto& span : spans) {
    if ((side > 0 ? span.id > 0 : span.id < 0) &&
        (outer == nullptr || std::abs(span.id) > std::abs(outer->id))) {
      outer = &span;
    }
  }
  if (outer == nullptr || outer->width() < 0.05) {
    return std::nullopt;
  }
  const auto& lanes = map.road(r).lane_sections[map.section_index(r, s)].lanes;
  for (const auto& lane : lanes) {
    if (lane.id == outer->id) {
      const SemanticClass c = semantic_class_of_lane(lane.type);
      if (c == SemanticClass::kTerrain || c == SemanticClass::kUnlabeled) {
        return std::nullopt;
      }
    }
  }
  return outer->t_outer;
}

VergeSection verge_section(const WorldBuild& w, size_t r, double s, int side,
                           std::vector<xodr::LaneSpan>& spans) {
  VergeSection v;
  const auto t_edge = verge_hard_edge(w.map, r, s, side, spans);
  if (!t_edge) {
    return v;
  }
  const xodr::WorldPose edge = w.map.world_pose(r, s, *t_edge);
  const xodr::WorldPose inner = w.map.world_pose(r, s, *t_edge - side * kVergeUnderEdge);
  const xodr::WorldPose outer = w.map.world_pose(r, s, *t_edge + side * kVergeWidth);
  const auto ground = w.ground.height_at(outer.x, outer.y);
  if (!ground || edge.z - *ground > kVergeMaxDrop || *ground > edge.z - kVergeEdgeDrop) {
    return v;
  }
  xodr::LocateOptions on_lane;
  on_lane.max_distance = 0.01;
  if (w.map.locate(outer.x, outer.y, on_lane)) {
    return v;  // another road's lane: no ground to meet
  }
  v.valid = true;
  v.inner = {inner.x, inner.y, edge.z - kVergeEdgeDrop};
  v.outer = {outer.x, outer.y, *ground + kVergeOverGround};
  v.s = s;
  return v;
}

}  // namespace

void build_verges(WorldBuild& w) {
  const xodr::Map& map = w.map;
  if (w.ground.h.empty()) {
    return;
  }
  StaticMesh verge;
  verge.name = "verge";
  verge.classes = {SemanticClass::kTerrain};
  // v = 0.5 at the outer side: the "lane" is twice the strip wide (uv_per_m^2 = 1 / width).
  const auto half_lane = static_cast<float>(0.5);
  std::vector<xodr::LaneSpan> spans;
  for (size_t r = 0; r < map.road_count(); ++r) {
    const double length = map.road(r).length;
    const int n = std::max(1, static_cast<int>(std::ceil(length / kVergeStep)));
    for (int side : {1, -1}) {
      VergeSection last;
      for (int k = 0; k <= n; ++k) {
        const VergeSection v = verge_section(w, r, length * k / n, side, spans);
        if (v.valid && last.valid) {
          const auto a = static_cast<uint32_t>(verge.vertices.size());
          verge.vertices.insert(verge.vertices.end(), {last.inner, last.outer, v.outer, v.inner});
          verge.uvs.push_back({static_cast<float>(last.s), 0.0f});
          verge.uvs.push_back({static_cast<float>(last.s), half_lane});
          verge.uvs.push_back({static_cast<float>(v.s), half_lane});
          verge.uvs.push_back({static_cast<float>(v.s), 0.0f});
          // Counter-clockwise seen from above on either side.
          if (side < 0) {
            verge.triangles.push_back({a, a + 1, a + 2});
            verge.triangles.push_back({a, a + 2, a + 3});
          } else {
            verge.triangles.push_back({a, a + 2, a + 1});
            verge.triangles.push_back({a, a + 3, a + 2});
          }
        }
        last = v;
      }
    }
  }
  w.report.verge_triangles = verge.triangles.size();
  if (!verge.triangles.empty()) {
    w.scene.add_static_mesh(std::move(verge));
  }
}

}  // namespace corsa::sensors::detail
