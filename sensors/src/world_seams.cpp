// Seams between roads that lie side by side: two roads whose outer lane borders meet (the two
// halves of a centre strip between opposing carriageways, each on its own road) are evaluated
// from two reference lines, so their borders agree only to the maps' fitting error and leave
// cracks of a few millimetres through which rays reach the ground. Each such border gets a
// narrow band of its lane's surface a hair below the road, reaching under the neighbour, so the
// crack shows the same surface as both sides. Only where a point just beyond the border lies on
// another road (a connecting road of a junction too: a junction's lanes run beside the roads
// that enter it) whose lane has the same class; elsewhere the border is the road's true edge and
// is left as it is.

#include <algorithm>
#include <cmath>

#include "corsa/sensors/semantic.h"
#include "world_build.h"

namespace corsa::sensors::detail {
namespace {

constexpr double kStep = 0.5;      // m between samples along the border
constexpr double kBeyond = 0.05;   // m the band reaches past the border (the widest crack closed)
constexpr double kInside = 0.02;   // m the band reaches under its own lane
constexpr double kProbe = 0.04;    // m beyond the border where the neighbour is looked for
constexpr double kDrop = 0.001;    // m the band lies below the road surface
constexpr double kEndProbe = 0.3;  // m inside a road's ends where the neighbour is looked for

/// The class of the outermost lane on `side` of road `r` at s (one there: edge_at found it).
SemanticClass outer_class(const xodr::Map& map, size_t r, double s, int side) {
  const auto& section = map.road(r).lane_sections[map.section_index(r, s)];
  const xodr::Lane* outer = nullptr;
  for (const auto& lane : section.lanes) {
    if (lane.id * side > 0 && (outer == nullptr || std::abs(lane.id) > std::abs(outer->id))) {
      outer = &lane;
    }
  }
  return outer == nullptr ? SemanticClass::kRoad : semantic_class_of_lane(outer->type);
}

/// True when the point `kProbe` beyond the border at s lies on another road whose lane there has
/// class `c`.
bool meets_neighbour(const xodr::Map& map, size_t r, double s, int side, double t_outer,
                     SemanticClass c) {
  const xodr::WorldPose p = map.world_pose(r, s, t_outer + side * kProbe);
  xodr::LocateOptions o;
  o.max_distance = kBeyond;
  o.z = p.z;
  const auto at = map.locate(p.x, p.y, o);
  if (!at || at->road == r) {
    return false;
  }
  const xodr::Lane* lane = map.lane(at->lane_ref());
  return lane != nullptr && semantic_class_of_lane(lane->type) == c;
}

struct SeamSample {
  bool on = false;
  SemanticClass c = SemanticClass::kRoad;
  Vec3 inner, outer;
};

SeamSample sample_at(const xodr::Map& map, size_t r, double s, int side,
                     std::vector<xodr::LaneSpan>& spans) {
  SeamSample out;
  const Edge e = edge_at(map, r, s, side, spans);
  if (!e.valid) {
    return out;
  }
  const SemanticClass c = outer_class(map, r, s, side);
  // At a road's ends the neighbour is looked for a little inside: right at the end the point may
  // be nearer to the junction or road that continues the neighbour.
  const double end_margin = std::min(kEndProbe, 0.25 * map.road(r).length);
  const double probe_s = std::clamp(s, end_margin, map.road(r).length - end_margin);
  const Edge probe = edge_at(map, r, probe_s, side, spans);
  if (!probe.valid || !meets_neighbour(map, r, probe_s, side, probe.t_outer, c)) {
    return out;
  }
  const xodr::WorldPose a = map.world_pose(r, s, e.t_outer - side * kInside);
  const xodr::WorldPose b = map.world_pose(r, s, e.t_outer + side * kBeyond);
  out.on = true;
  out.c = c;
  out.inner = {a.x, a.y, a.z - kDrop};
  out.outer = {b.x, b.y, b.z - kDrop};
  return out;
}

}  // namespace

void build_seams(WorldBuild& w) {
  const xodr::Map& map = w.map;
  std::vector<xodr::LaneSpan> spans;
  StaticMesh band;
  band.name = "road seams";
  for (size_t r = 0; r < map.road_count(); ++r) {
    const xodr::Road& road = map.road(r);
    if (road.length <= 0.0) {
      continue;
    }
    const int n = std::max(1, static_cast<int>(std::ceil(road.length / kStep)));
    for (int side : {-1, 1}) {
      SeamSample prev = sample_at(map, r, 0.0, side, spans);
      for (int i = 1; i <= n; ++i) {
        const SeamSample next = sample_at(map, r, road.length * i / n, side, spans);
        if (prev.on && next.on && prev.c == next.c) {
          const auto k = static_cast<uint32_t>(band.vertices.size());
          band.vertices.insert(band.vertices.end(),
                               {prev.inner, prev.outer, next.inner, next.outer});
          // Counter-clockwise from above: the outer side is on the right of +s when side < 0.
          if (side < 0) {
            band.triangles.push_back({k, k + 1, k + 3});
            band.triangles.push_back({k, k + 3, k + 2});
          } else {
            band.triangles.push_back({k, k + 3, k + 1});
            band.triangles.push_back({k, k + 2, k + 3});
          }
          band.classes.push_back(prev.c);
          band.classes.push_back(prev.c);
          w.report.seam_length += road.length / n;
        }
        prev = next;
      }
    }
  }
  if (!band.triangles.empty()) {
    w.scene.add_static_mesh(std::move(band));
  }
}

}  // namespace corsa::sensors::detail
