// Street furniture along the kerb of sidewalks, placed from the run seed and the road's id (the
// same seed gives the same street): bus stops (a shelter where the sidewalk is wide enough, else
// the sign alone), street-name signs near the junctions, fire hydrants, litter bins, benches and
// groups of bollards at the corners. As on a real street, everything stands in the furniture
// zone at the kerb and leaves the walking path behind it clear (at least kClearPath metres of
// the sidewalk's outer part), and keeps away from junction mouths, crosswalks (and the
// sidewalk where they land), buildings, trees, street lights and other props.

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

#include "scalar_math.h"
#include "scene_data.h"
#include "street_furniture.h"
#include "world_build.h"

namespace corsa::sensors::detail {
namespace {

/// Metres of sidewalk kept clear for walking, on its outer (building) side: a wheelchair and a
/// walker passing (1.5 m, the least clear width of a footway in the common guides, where 1.8-2 m
/// is wanted). CARLA's towns have 2 m sidewalks: they get only slim things (bollards, sign
/// posts), as narrow sidewalks do.
constexpr double kClearPath = 1.5;
/// Metres between the kerb's edge and the furniture (car doors, mirrors hanging over the kerb).
constexpr double kKerbSetback = 0.25;
/// No furniture closer than this to a junction's mouth (the corner radius and its sight lines).
constexpr double kJunctionMargin = 12.0;
/// Metres kept clear either side of a crosswalk, across the whole sidewalk where it lands.
constexpr double kCrosswalkMargin = 2.0;

/// What one piece of furniture needs: its footprint along the kerb and across, and the
/// clearance it keeps from other props.
struct KerbItemSize {
  double along = 0.5;
  double across = 0.5;
  double clearance = 0.5;  ///< radius kept free of other props (m)
};

/// A crosswalk painted on the map: the road it lies on, its s along it (± half) and its bounds.
struct CrosswalkSpan {
  uint32_t road = 0;
  double s = 0.0;
  double half = 0.0;
  Bounds bounds;
};

class KerbPlacer {
 public:
  explicit KerbPlacer(WorldBuild& w) : w_(w) { collect_crosswalks(); }

  /// Places `make()` with its footprint centred at s on `side` of road `r`, facing away from
  /// the road (`towards_road`: facing the road), when every rule allows; true when placed.
  bool place(size_t r, int side, double s, const KerbItemSize& size, const char* kind,
             bool towards_road, const std::function<ArticulatedMesh()>& make) {
    const xodr::Road& road = w_.map.road(r);
    const double half = 0.5 * size.along;
    if (s - half < 0.0 || s + half > road.length ||
        next_to_junction(w_.map, r, s - half, kJunctionMargin) ||
        next_to_junction(w_.map, r, s + half, kJunctionMargin)) {
      return false;
    }
    // The furniture zone must hold the footprint along its whole length.
    double kerb = 0.0;
    for (const double at : {s - half, s, s + half}) {
      const Edge e = edge_at(w_.map, r, at, side, spans_);
      if (!e.valid || !e.sidewalk ||
          std::fabs(e.t_outer - e.kerb) < kClearPath + kKerbSetback + size.across) {
        return false;
      }
      kerb = at == s ? e.kerb : kerb;
    }
    const double t = kerb + side * (kKerbSetback + 0.5 * size.across);
    const xodr::WorldPose p = w_.map.world_pose(r, s, t);
    const double radius = 0.5 * std::hypot(size.along, size.across);
    if (near_crosswalk(r, s, half, p.x, p.y, radius) || w_.near_drivable(p.x, p.y, 0.2) ||
        w_.under_building(p.x, p.y, p.z) || !w_.clear_of_props(p.x, p.y, size.clearance)) {
      return false;
    }
    const double away = p.h + side * 0.5 * kPi;
    const double facing = towards_road ? away + kPi : away;
    ObjectInfo info;
    info.kind = kind;
    w_.place(make(), rigid_from_pose(p.x, p.y, p.z, facing, 0, 0),
             std::string(kind) + " " + road.id, info);
    w_.remember(p.x, p.y, size.clearance);
    ++w_.report.street_furniture;
    return true;
  }

 private:
  /// The crosswalks drawn so far (from signals and objects): labelled objects of kind
  /// "crosswalk", each located on its road.
  void collect_crosswalks() {
    for (const auto& [id, record] : w_.scene.data().objects) {
      if (record.info.kind != "crosswalk") {
        continue;
      }
      const Bounds& b = record.bounds;
      CrosswalkSpan c;
      c.bounds = b;
      const double cx = 0.5 * (b.min.x + b.max.x);
      const double cy = 0.5 * (b.min.y + b.max.y);
      // A strip across the road: its length along the road is at most the box's smaller side.
      c.half = 0.5 * std::min(b.max.x - b.min.x, b.max.y - b.min.y);
      xodr::LocateOptions near;
      near.max_distance = 2.0;
      const auto at = w_.map.locate(cx, cy, near);
      c.road = at ? at->road : UINT32_MAX;
      c.s = at ? at->s : 0.0;
      crosswalks_.push_back(c);
    }
  }

  /// True when an item of half length `half` at s on road r (world x, y, radius) would stand on
  /// the sidewalk where a crosswalk lands, or within the margin of its paint.
  bool near_crosswalk(size_t r, double s, double half, double x, double y, double radius) const {
    for (const auto& c : crosswalks_) {
      if (c.road == r && std::fabs(c.s - s) < c.half + half + kCrosswalkMargin) {
        return true;
      }
      const double dx = std::max({c.bounds.min.x - x, 0.0, x - c.bounds.max.x});
      const double dy = std::max({c.bounds.min.y - y, 0.0, y - c.bounds.max.y});
      if (std::hypot(dx, dy) < radius + kCrosswalkMargin) {
        return true;
      }
    }
    return false;
  }

  WorldBuild& w_;
  std::vector<CrosswalkSpan> crosswalks_;
  std::vector<xodr::LaneSpan> spans_;
};

/// Tries at s, then a little further along (`tries` - 1 nudges of `nudge` metres), so that a
/// tree or a light in the way moves the item instead of dropping it. Returns the s where it
/// stands.
std::optional<double> place_near(KerbPlacer& placer, size_t r, int side, double s, double nudge,
                                 const KerbItemSize& size, const char* kind, bool towards_road,
                                 const std::function<ArticulatedMesh()>& make, int tries = 4) {
  for (int k = 0; k < tries; ++k) {
    if (placer.place(r, side, s + k * nudge, size, kind, towards_road, make)) {
      return s + k * nudge;
    }
  }
  return std::nullopt;
}

/// Items spaced `spacing` metres apart on average (±25%) along one side of a road.
void place_spaced(KerbPlacer& placer, RandomStream& rng, size_t r, int side, double length,
                  double spacing, const KerbItemSize& size, const char* kind, bool towards_road,
                  const std::function<ArticulatedMesh(RandomStream&)>& make) {
  double s = rng.uniform(0.3, 1.0) * spacing;
  while (s < length) {
    RandomStream look(rng.next_u64());
    place_near(placer, r, side, s, 1.5, size, kind, towards_road, [&] { return make(look); });
    s += spacing * rng.uniform(0.75, 1.25);
  }
}

void place_bus_stops(KerbPlacer& placer, RandomStream& rng, size_t r, int side, double length) {
  // About one stop every 300 m of street on each side (stops are 300-500 m apart along a line).
  for (double start = 0.0; start + 80.0 <= length; start += 300.0) {
    const double s = start + rng.uniform(30.0, std::min(270.0, length - start - 30.0));
    RandomStream look(rng.next_u64());
    if (rng.uniform01() < 0.4) {
      continue;
    }
    const double shelter_length = look.uniform(3.0, 4.5);
    // A shelter needs a gap between the street trees: looked for over 12 m.
    const KerbItemSize shelter{shelter_length, 1.7, 0.5 * shelter_length};
    const auto at = place_near(
        placer, r, side, s, 2.0, shelter, "bus_shelter", true,
        [&] { return make_bus_shelter(look, shelter_length); }, 7);
    if (at) {
      // The stop's sign just beyond the shelter, where the bus's front door stops.
      placer.place(r, side, *at + 0.5 * shelter_length + 1.2, {0.2, 0.2, 0.3}, "bus_stop_sign",
                   true, [] { return make_bus_stop_sign(); });
      continue;
    }
    place_near(placer, r, side, s, 3.0, {0.2, 0.2, 0.3}, "bus_stop_sign", true,
               [] { return make_bus_stop_sign(); });
  }
}

/// A street-name sign near each end of the road that meets a junction, on the right of the
/// traffic arriving there (the left under left-hand traffic), and now and then a row of three
/// bollards at the corners keeping cars off the sidewalk.
void place_corners(KerbPlacer& placer, RandomStream& rng, const xodr::Road& road, size_t r) {
  const bool left_hand = road.rule == xodr::TrafficRule::kLeftHand;
  for (const bool at_end : {false, true}) {
    const auto& link = at_end ? road.successor : road.predecessor;
    if (link.element_type != xodr::LinkElement::kJunction) {
      continue;
    }
    // Traffic arriving at the end drives towards +s on the right (t < 0) under right-hand
    // traffic; arriving at the start it drives towards -s, on the left.
    const int arriving_side = (at_end ? -1 : 1) * (left_hand ? -1 : 1);
    const double inward = at_end ? -1.0 : 1.0;
    const double from_end = kJunctionMargin + rng.uniform(0.5, 2.0);
    const double s_sign = at_end ? road.length - from_end : from_end;
    RandomStream look(rng.next_u64());
    place_near(placer, r, arriving_side, s_sign, inward * 1.0, {0.2, 0.2, 0.5}, "street_name_sign",
               false, [&] { return make_street_name_sign(look); });
    for (const int side : {-1, 1}) {
      if (rng.uniform01() < 0.5) {
        continue;
      }
      const double first = kJunctionMargin + 0.3 + rng.uniform(0.0, 1.0);
      for (int k = 0; k < 3; ++k) {
        const double from = first + 1.5 * k;
        RandomStream bollard(rng.next_u64());
        placer.place(r, side, at_end ? road.length - from : from, {0.2, 0.2, 0.35}, "bollard",
                     false, [&] { return make_bollard(bollard); });
      }
    }
  }
}

}  // namespace

void build_furniture(WorldBuild& w) {
  const xodr::Map& map = w.map;
  KerbPlacer placer(w);
  for (size_t r = 0; r < map.road_count(); ++r) {
    const xodr::Road& road = map.road(r);
    if (road.in_junction() || road.length < 2.0 * kJunctionMargin + 4.0) {
      continue;
    }
    RandomStream rng(derive_seed(w.options.seed, "street furniture " + road.id));
    for (int side : {-1, 1}) {
      place_bus_stops(placer, rng, r, side, road.length);
      place_spaced(placer, rng, r, side, road.length, 110.0, {0.45, 0.45, 0.6}, "fire_hydrant",
                   false, make_fire_hydrant);
      place_spaced(placer, rng, r, side, road.length, 45.0, {0.5, 0.5, 0.6}, "litter_bin", false,
                   make_litter_bin);
      place_spaced(placer, rng, r, side, road.length, 70.0, {1.8, 0.6, 1.2}, "bench", false,
                   make_bench);
    }
    place_corners(placer, rng, road, r);
  }
}

}  // namespace corsa::sensors::detail
