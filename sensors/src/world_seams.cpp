// Seams between roads that lie side by side or end to end: two roads whose borders meet (the
// two halves of a centre strip between opposing carriageways, each on its own road; a road and
// the junction's connecting roads that continue it) are evaluated from two reference lines, so
// their borders agree only to the map's fitting error and leave cracks of a few millimetres
// through which rays reach the ground. Each such border or end gets a narrow band of its lane's
// surface a hair below the road, reaching under the neighbour, so the crack shows the same
// surface as both sides. Only where a point just beyond lies on another road (a junction's
// connecting road too) whose lane has the same class and whose surface there is at most 3 cm
// below this one's (a step down is closed from the lower side); elsewhere the border is the
// road's true edge and is left as it is.

#include <algorithm>
#include <cmath>
#include <optional>

#include "corsa/sensors/semantic.h"
#include "world_build.h"

namespace corsa::sensors::detail {
namespace {

constexpr double kSeamStep = 0.5;      // m between samples along the border
constexpr double kSeamBeyond = 0.05;   // m the band reaches past the border (widest crack closed)
constexpr double kSeamInside = 0.02;   // m the band reaches under its own lane
constexpr double kSeamProbe = 0.04;    // m beyond the border where the neighbour is looked for
constexpr double kSeamDrop = 0.001;    // m the band lies below the road surface
constexpr double kSeamEndProbe = 0.3;  // m inside a road's ends where the neighbour is looked for
constexpr double kSeamHeight = 0.03;   // m the neighbour's surface may lie below this one

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

/// True when (x, y) lies on another road than r whose lane there has class `c` and whose
/// surface is at most `kSeamHeight` below `z`: a band reaching over a much lower surface would
/// stand above it (that crack is closed from the lower road's side, whose band passes under
/// the higher one).
bool neighbour_at(const xodr::Map& map, size_t r, double x, double y, double z, SemanticClass c) {
  xodr::LocateOptions o;
  o.max_distance = kSeamBeyond;
  o.z = z;
  const auto at = map.locate(x, y, o);
  if (!at || at->road == r) {
    return false;
  }
  const xodr::Lane* lane = map.lane(at->lane_ref());
  return lane != nullptr && semantic_class_of_lane(lane->type) == c &&
         map.world_pose(at->road, at->s, at->t).z > z - kSeamHeight;
}

/// True when the point `kSeamProbe` beyond the border at s lies on a neighbour (neighbour_at).
bool meets_neighbour(const xodr::Map& map, size_t r, double s, int side, double t_outer,
                     SemanticClass c) {
  const xodr::WorldPose p = map.world_pose(r, s, t_outer + side * kSeamProbe);
  return neighbour_at(map, r, p.x, p.y, p.z, c);
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
  const double end_margin = std::min(kSeamEndProbe, 0.25 * map.road(r).length);
  const double probe_s = std::clamp(s, end_margin, map.road(r).length - end_margin);
  const Edge probe = edge_at(map, r, probe_s, side, spans);
  if (!probe.valid || !meets_neighbour(map, r, probe_s, side, probe.t_outer, c)) {
    return out;
  }
  const xodr::WorldPose a = map.world_pose(r, s, e.t_outer - side * kSeamInside);
  const xodr::WorldPose b = map.world_pose(r, s, e.t_outer + side * kSeamBeyond);
  out.on = true;
  out.c = c;
  out.inner = {a.x, a.y, a.z - kSeamDrop};
  out.outer = {b.x, b.y, b.z - kSeamDrop};
  return out;
}

/// The class of the lane at lateral position t at s of road r (nothing off the road).
std::optional<SemanticClass> class_at(const xodr::Map& map, size_t r, double s, double t) {
  const auto id = map.lane_at(r, s, t);
  if (!id) {
    return std::nullopt;
  }
  const xodr::Lane* lane =
      map.lane({static_cast<uint32_t>(r), static_cast<uint32_t>(map.section_index(r, s)), *id});
  return lane == nullptr ? std::nullopt : std::optional(semantic_class_of_lane(lane->type));
}

/// A sample across a road's end (s = 0 or its length) at t: the band reaches `kSeamBeyond` past
/// the end along the road's heading where a point `kSeamProbe` past it lies on another road whose
/// lane has the same class.
SeamSample end_sample(const xodr::Map& map, size_t r, double s, int outward, double t) {
  SeamSample out;
  const auto c = class_at(map, r, s, t);
  if (!c) {
    return out;
  }
  const xodr::WorldPose p = map.world_pose(r, s, t);
  const double dx = outward * std::cos(p.h), dy = outward * std::sin(p.h);
  if (!neighbour_at(map, r, p.x + kSeamProbe * dx, p.y + kSeamProbe * dy, p.z, *c)) {
    return out;
  }
  out.on = true;
  out.c = *c;
  out.inner = {p.x - kSeamInside * dx, p.y - kSeamInside * dy, p.z - kSeamDrop};
  out.outer = {p.x + kSeamBeyond * dx, p.y + kSeamBeyond * dy, p.z - kSeamDrop};
  return out;
}

/// Adds the band piece between two samples (both on, same class); `flip` when the samples'
/// inner-to-outer direction turns clockwise into the direction from `a` to `b`.
void add_piece(StaticMesh& band, const SeamSample& a, const SeamSample& b, bool flip) {
  const auto k = static_cast<uint32_t>(band.vertices.size());
  band.vertices.insert(band.vertices.end(), {a.inner, a.outer, b.inner, b.outer});
  if (flip) {
    band.triangles.push_back({k, k + 3, k + 1});
    band.triangles.push_back({k, k + 2, k + 3});
  } else {
    band.triangles.push_back({k, k + 1, k + 3});
    band.triangles.push_back({k, k + 3, k + 2});
  }
  band.classes.push_back(a.c);
  band.classes.push_back(a.c);
}

/// Bands along both outer borders of road r.
void side_seams(const xodr::Map& map, size_t r, StaticMesh& band, double& length) {
  std::vector<xodr::LaneSpan> spans;
  const double road_length = map.road(r).length;
  const int n = std::max(1, static_cast<int>(std::ceil(road_length / kSeamStep)));
  for (int side : {-1, 1}) {
    SeamSample prev = sample_at(map, r, 0.0, side, spans);
    for (int i = 1; i <= n; ++i) {
      const SeamSample next = sample_at(map, r, road_length * i / n, side, spans);
      if (prev.on && next.on && prev.c == next.c) {
        // Counter-clockwise from above: the outer side is on the right of +s when side < 0.
        add_piece(band, prev, next, side > 0);
        length += road_length / n;
      }
      prev = next;
    }
  }
}

/// Bands across both ends of road r, from its right edge to its left one.
void end_seams(const xodr::Map& map, size_t r, StaticMesh& band, double& length) {
  std::vector<xodr::LaneSpan> spans;
  const double road_length = map.road(r).length;
  for (int outward : {-1, 1}) {
    const double s = outward > 0 ? road_length : 0.0;
    const size_t section = map.section_index(r, s);
    map.lane_spans_in_section(r, section, s, spans);
    if (spans.empty()) {
      continue;
    }
    // Spans run left to right: from the last one's outer border to the first one's.
    const double t0 = spans.back().t_min(), t1 = spans.front().t_max();
    const int n = std::max(1, static_cast<int>(std::ceil((t1 - t0) / kSeamStep)));
    // Just inside the end, so the lane found there is the end's own.
    const double probe_s = std::clamp(s - outward * 1e-3, 0.0, road_length);
    SeamSample prev = end_sample(map, r, probe_s, outward, t0 + 1e-3);
    for (int i = 1; i <= n; ++i) {
      const double t = i == n ? t1 - 1e-3 : t0 + (t1 - t0) * i / n;
      const SeamSample next = end_sample(map, r, probe_s, outward, t);
      if (prev.on && next.on && prev.c == next.c) {
        // Across the end, t grows to the left: outward along +s is counter-clockwise.
        add_piece(band, prev, next, outward < 0);
        length += (t1 - t0) / n;
      }
      prev = next;
    }
  }
}

}  // namespace

void build_seams(WorldBuild& w) {
  const xodr::Map& map = w.map;
  StaticMesh band;
  band.name = "road seams";
  for (size_t r = 0; r < map.road_count(); ++r) {
    if (map.road(r).length <= 0.0) {
      continue;
    }
    side_seams(map, r, band, w.report.seam_length);
    end_seams(map, r, band, w.report.seam_length);
  }
  if (!band.triangles.empty()) {
    w.scene.add_static_mesh(std::move(band));
  }
}

}  // namespace corsa::sensors::detail
