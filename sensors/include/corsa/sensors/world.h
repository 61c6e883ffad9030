#pragma once

// The world beyond the road surface, built from an OpenDRIVE map and a seed: ground to the
// horizon (terrain under and around the roads), roadside vegetation, street lights and street
// furniture placed deterministically along the roads, OpenDRIVE signals drawn as traffic lights and
// signs (their bulbs follow the scenario's signal states) or painted on the road (stop lines,
// crosswalks), OpenDRIVE objects (crosswalks, stop lines, poles, trees, barriers, buildings,
// parking spaces; outlines and repeats), guard rails and fences along motorways, parked cars in
// the map's parking lanes and spaces (and, when asked, along kerbs), and, when asked, generated
// buildings along the streets.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/sensors/scene.h"
#include "corsa/xodr/map.h"

namespace corsa::sensors {

/// Where parked vehicles stand: nowhere, where the map marks parking (lanes of type parking,
/// parkingSpace objects), or there and along the kerbs of streets without parking markup.
enum class ParkedVehicles { kNone, kMap, kKerb };

/// A place the world keeps clear of parked vehicles (a scenario entity at the start): the point
/// (map frame, m), a radius (m), and the lane it stands in (road id and lane id; empty road: none),
/// which kerb parking leaves empty over its whole length.
struct KeepClear {
  double x = 0.0;
  double y = 0.0;
  double radius = 0.0;
  std::string road;
  int lane = 0;
};

struct WorldOptions {
  uint64_t seed = 0;  ///< run seed: where plants stand, which species, sizes
  /// Terrain around the roads, out to the horizon, lane surface under the cracks between
  /// roads that lie side by side (a centre strip split between two roads), and road surface in
  /// the small holes that a junction's roads enclose (xodr::find_junction_holes).
  bool ground = true;
  bool vegetation = true;     ///< trees and bushes beside the roads
  bool street_lights = true;  ///< street lights along roads with sidewalks
  /// Street furniture at the kerb of sidewalks wide enough to keep a walking path clear: bus
  /// shelters and stop signs, street-name signs, fire hydrants, litter bins, benches, bollards.
  bool street_furniture = true;
  bool signals = true;  ///< OpenDRIVE <signal>s
  bool objects = true;  ///< OpenDRIVE <object>s
  /// Guard rails at the outer edge of motorways (roads typed motorway or limited to 80 km/h or
  /// more) and a right-of-way fence beyond, on sides without a sidewalk, where the map's own
  /// objects bring no rail.
  bool guard_rails = true;
  /// Generated buildings along streets (not motorways), where no building stands: facades with
  /// windows, doors and shop fronts, flat or pitched roofs; no two alike, drawn from the seed.
  bool buildings = false;
  double tree_spacing = 14.0;  ///< m between plants along a road side (on average)
  ParkedVehicles parked = ParkedVehicles::kMap;
  double parked_density = 0.6;  ///< share of parking slots holding a vehicle, 0..1
  std::vector<KeepClear> keep_clear;
};

/// What build_world added.
struct WorldReport {
  size_t ground_triangles = 0;
  size_t verge_triangles = 0;  ///< strips of terrain from road and sidewalk edges to the ground
  double seam_length = 0.0;    ///< m of road borders with a band under the crack to a neighbour
  size_t junction_holes = 0;   ///< holes found in junctions (paved or not)
  size_t junction_holes_paved = 0;   ///< of those, paved as road
  double junction_paved_area = 0.0;  ///< m² paved
  size_t trees = 0;
  size_t bushes = 0;
  size_t street_lights = 0;
  size_t street_furniture = 0;  ///< pieces of street furniture (each bollard is one)
  size_t traffic_lights = 0;
  size_t signs = 0;
  size_t markings = 0;  ///< signals painted on the road (stop lines, crosswalks, give-way lines)
  size_t objects = 0;
  size_t guard_rails = 0;  ///< generated rail pieces (at most 10 m each)
  size_t fences = 0;       ///< generated fence pieces (at most 10 m each)
  size_t buildings = 0;    ///< generated buildings
  size_t parked_vehicles = 0;
};

/// Adds the world to a scene holding the map's road mesh (and any models). The scene must be
/// committed (plants keep clear of buildings found by ray queries); commit it again afterwards.
/// Signals of a type it does not know become a generic sign with one located warning per type;
/// objects of an unknown type a warning and nothing drawn. Deterministic for a seed.
WorldReport build_world(const xodr::Map& map, Scene& scene, const WorldOptions& options,
                        Diagnostics& diagnostics);

}  // namespace corsa::sensors
