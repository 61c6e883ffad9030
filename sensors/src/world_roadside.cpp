// Roadside vegetation and street lights, placed along every road outside junctions from the
// run seed and the road's id (the same seed gives the same plants): street trees and street
// lights at the kerb side of sidewalks, trees and bushes on the ground beside roads without
// them, never on a drivable lane, in a building or crowding another prop.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "scalar_math.h"
#include "world_build.h"
#include "world_props.h"

namespace corsa::sensors::detail {
namespace {

/// Street lights every 30 m on a side of a road where it has a sidewalk (staggered between the
/// two sides), at the kerb, their arms over the road. Placed before the plants of the road, so
/// that the trees keep their distance from the poles and their crowns clear of the lamp heads.
void place_lights(WorldBuild& w, size_t r, int side, std::vector<xodr::LaneSpan>& spans) {
  const xodr::Map& map = w.map;
  const xodr::Road& road = map.road(r);
  constexpr double kHeight = 7.5;
  constexpr double kReach = 1.6;
  for (double sl = side > 0 ? 6.0 : 21.0; sl < road.length; sl += 30.0) {
    const Edge el = edge_at(map, r, sl, side, spans);
    if (!el.valid || !el.sidewalk || next_to_junction(map, r, sl, 10.0)) {
      continue;
    }
    const double t = el.kerb + side * 0.45;
    const xodr::WorldPose p = map.world_pose(r, sl, t);
    if (w.under_building(p.x, p.y, p.z) || !w.clear_of_props(p.x, p.y, 1.0)) {
      continue;
    }
    // The arm reaches over the road: towards -side across the reference line.
    const double facing = p.h + (side > 0 ? -0.5 * kPi : 0.5 * kPi);
    const Rigid pose = rigid_from_pose(p.x, p.y, p.z, facing, 0, 0);
    ObjectInfo info;
    info.kind = "street_light";
    w.place(make_street_light(kHeight, kReach), pose, "street light " + road.id, info);
    w.lamp_heads.push_back(pose.apply(street_lamp_head(kHeight, kReach)));
    w.remember(p.x, p.y, 1.0);
    ++w.report.street_lights;
  }
}

}  // namespace

void build_roadside(WorldBuild& w) {
  const xodr::Map& map = w.map;
  std::vector<xodr::LaneSpan> spans;
  for (size_t r = 0; r < map.road_count(); ++r) {
    const xodr::Road& road = map.road(r);
    if (road.in_junction() || road.length < 5.0) {
      continue;
    }
    RandomStream rng(derive_seed(w.options.seed, "roadside " + road.id));
    for (int side : {1, -1}) {
      if (w.options.street_lights) {
        place_lights(w, r, side, spans);
      }
      double s = rng.uniform(0.0, w.options.tree_spacing);
      while (s < road.length) {
        const double step = w.options.tree_spacing * rng.uniform(0.7, 1.3);
        const double pick = rng.uniform01();
        const double offset = rng.uniform(1.5, 6.0);
        const double tree_height = rng.uniform(5.0, 11.0);
        const double bush_size = rng.uniform(0.8, 1.8);
        RandomStream look(rng.next_u64());
        if (next_to_junction(map, r, s, 10.0)) {
          s += step;
          continue;
        }
        const Edge e = edge_at(map, r, s, side, spans);
        if (!e.valid) {
          s += step;
          continue;
        }
        const bool on_sidewalk = e.sidewalk && std::fabs(e.t_outer - e.kerb) > 2.0;
        if (w.options.vegetation) {
          const bool tree = on_sidewalk || pick < 0.6;
          const double t = on_sidewalk ? e.kerb + side * 0.8 : e.t_outer + side * offset;
          const xodr::WorldPose p = map.world_pose(r, s, t);
          const double radius = tree ? 3.0 : 1.2;
          const double margin = on_sidewalk ? 0.5 : (tree ? 2.5 : 1.2);
          if (!w.near_drivable(p.x, p.y, margin) && !w.under_building(p.x, p.y, p.z) &&
              w.clear_of_props(p.x, p.y, radius)) {
            const double z = on_sidewalk ? p.z : p.z - 0.25;  // roots in the ground
            const Rigid pose = rigid_from_pose(p.x, p.y, z, look.uniform(0.0, 2.0 * kPi), 0, 0);
            ObjectInfo info;
            info.kind = tree ? "tree" : "bush";
            if (tree) {
              // Street trees are broadleaved; conifers grow only away from sidewalks. A crown
              // reaches at most 5 m from its trunk.
              const auto clear = w.lamp_clearances(pose, 5.0);
              w.place(make_tree(look, tree_height, !on_sidewalk, clear), pose, "tree " + road.id,
                      info);
              ++w.report.trees;
            } else {
              w.place(make_bush(look, bush_size), pose, "bush " + road.id, info);
              ++w.report.bushes;
            }
            w.remember(p.x, p.y, radius);
          }
        }
        s += step;
      }
    }
  }
}

}  // namespace corsa::sensors::detail
