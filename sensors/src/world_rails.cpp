// Guard rails and right-of-way fences along motorways: a W-beam rail 0.5 m beyond the outer edge
// of the outermost lane (the shoulder's edge where there is one) and a mesh fence 7 m beyond,
// on every side of a motorway road outside junctions that has no sidewalk, in pieces of at most
// 10 m that follow the curve. A piece is left out where it would stand on or within 0.3 m of a
// drivable lane (another carriageway or a ramp joining), within 10 m of a junction, or inside a
// building; roads whose map objects already bring rails, barriers or fences get none.

#include <algorithm>
#include <cmath>

#include "corsa/core/strings.h"
#include "world_build.h"
#include "world_props.h"

namespace corsa::sensors::detail {
namespace {

constexpr double kPiece = 10.0;            // m, longest straight piece
constexpr double kRailOffset = 0.5;        // m beyond the outer lane edge
constexpr double kFenceOffset = 7.0;       // m beyond the outer lane edge
constexpr double kRailJunctionGap = 10.0;  // m kept clear at road ends meeting a junction

bool has_own_rails(const xodr::Road& road) {
  for (const xodr::Object& o : road.objects) {
    const std::string type = to_lower(o.type);
    if (type == "guardrail" || type == "barrier" || type == "railing" || type == "fence" ||
        type == "soundbarrier") {
      return true;
    }
  }
  return false;
}

/// One piece from s0 to s1 at `offset` beyond the edge on `side`; false when it may not stand.
bool place_piece(WorldBuild& w, size_t r, double s0, double s1, int side, double offset, bool fence,
                 std::vector<xodr::LaneSpan>& spans) {
  const xodr::Map& map = w.map;
  const Edge e0 = edge_at(map, r, s0, side, spans);
  const Edge e1 = edge_at(map, r, s1, side, spans);
  if (!e0.valid || !e1.valid || e0.sidewalk || e1.sidewalk) {
    return false;
  }
  const xodr::WorldPose a = map.world_pose(r, s0, e0.t_outer + side * offset);
  const xodr::WorldPose b = map.world_pose(r, s1, e1.t_outer + side * offset);
  const double margin = fence ? 2.0 : 0.3;
  for (double f : {0.0, 0.5, 1.0}) {
    const double x = a.x + f * (b.x - a.x);
    const double y = a.y + f * (b.y - a.y);
    if (w.near_drivable(x, y, margin) || w.under_building(x, y, a.z + f * (b.z - a.z))) {
      return false;
    }
  }
  // The rail's frame runs along +x with its beam on +y: from a to b on the right side (the
  // road lies to the left), from b to a on the left.
  const xodr::WorldPose& from = side < 0 ? a : b;
  const xodr::WorldPose& to = side < 0 ? b : a;
  const double length = std::hypot(to.x - from.x, to.y - from.y);
  if (length < 0.5) {
    return false;
  }
  const double heading = std::atan2(to.y - from.y, to.x - from.x);
  const double pitch = -std::atan2(to.z - from.z, length);
  // Fences stand on the ground beyond the verge, a little below the road surface.
  const double sink = fence ? 0.15 : 0.0;
  ObjectInfo info;
  info.kind = fence ? "fence" : "guard_rail";
  w.place(make_rail(length, fence),
          rigid_from_pose(from.x, from.y, from.z - sink, heading, pitch, 0),
          std::string(fence ? "fence " : "guard rail ") + map.road(r).id, info);
  // Plants keep clear of the line.
  for (double d = 0.0; d <= length; d += 2.5) {
    w.remember(from.x + d * std::cos(heading), from.y + d * std::sin(heading), 0.6);
  }
  return true;
}

}  // namespace

void build_rails(WorldBuild& w) {
  const xodr::Map& map = w.map;
  std::vector<xodr::LaneSpan> spans;
  for (size_t r = 0; r < map.road_count(); ++r) {
    const xodr::Road& road = map.road(r);
    if (road.in_junction() || road.length < 2.0 * kRailJunctionGap || has_own_rails(road)) {
      continue;
    }
    for (int side : {-1, 1}) {
      for (double s = 0.0; s < road.length - 0.5;) {
        const double s1 = std::min(road.length, s + kPiece);
        const double mid = 0.5 * (s + s1);
        if (motorway_at(road, mid) && !next_to_junction(map, r, s, kRailJunctionGap) &&
            !next_to_junction(map, r, s1, kRailJunctionGap)) {
          if (place_piece(w, r, s, s1, side, kRailOffset, false, spans)) {
            ++w.report.guard_rails;
          }
          if (place_piece(w, r, s, s1, side, kFenceOffset, true, spans)) {
            ++w.report.fences;
          }
        }
        s = s1;
      }
    }
  }
}

}  // namespace corsa::sensors::detail
