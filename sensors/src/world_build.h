#pragma once

// Shared state of the world builder (private; see corsa/sensors/world.h).

#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "corsa/core/random.h"
#include "corsa/sensors/world.h"
#include "corsa/xodr/road_mesh.h"
#include "mesh_builder.h"
#include "vegetation.h"

namespace corsa::sensors::detail {

/// The outermost lane span on one side of a road (+1 left, -1 right) at s: its outer border,
/// its inner border (`kerb`, the border towards the road when it is a sidewalk) and whether it
/// is a sidewalk or walkway. `valid` is false when the side has no lane there.
struct Edge {
  double t_outer = 0.0;
  double kerb = 0.0;
  bool sidewalk = false;
  bool valid = false;
};
/// `spans` is scratch space kept between calls.
Edge edge_at(const xodr::Map& map, size_t road, double s, int side,
             std::vector<xodr::LaneSpan>& spans);
/// True within `margin` metres of a road end that meets a junction.
bool next_to_junction(const xodr::Map& map, size_t road, double s, double margin);
/// True when the road's type at s is a motorway, or its speed limit there is 80 km/h or more.
bool motorway_at(const xodr::Road& road, double s);

/// The ground's height field (build_ground): vertices every `cell` metres from (x0, y0), nx by
/// ny, each cell split along its (i, j)-(i+1, j+1) diagonal as the ground mesh is.
struct GroundField {
  double x0 = 0.0;
  double y0 = 0.0;
  double cell = 4.0;
  int nx = 0;
  int ny = 0;
  std::vector<double> h;
  /// The ground mesh's height at (x, y); nothing outside the field (or before it is built).
  std::optional<double> height_at(double x, double y) const;
};

struct WorldBuild {
  const xodr::Map& map;
  Scene& scene;
  const WorldOptions& options;
  Diagnostics& diagnostics;
  WorldReport report;
  /// Props placed so far, by 4 m grid cell: their positions and clearance radii.
  std::unordered_map<int64_t, std::vector<std::array<double, 3>>> placed;
  GroundField ground;
  /// Lamp heads of the street lights placed so far (map frame): tree crowns are pruned clear of
  /// them, as street crews keep them.
  std::vector<Vec3> lamp_heads;

  /// Adds a prop mesh placed in the map frame; returns its instance id.
  uint32_t place(const ArticulatedMesh& mesh, const Rigid& pose, const std::string& name,
                 const ObjectInfo& info = {}, const std::string& signal_id = {});
  /// Adds paint on the road (class lane_marking) placed in the map frame as one labelled object
  /// with an instance id of its own (paint is stuff by its class); returns that id.
  uint32_t place_paint(const ArticulatedMesh& mesh, const Rigid& pose, const std::string& name,
                       const ObjectInfo& info);
  /// True when no prop stands within `radius` (plus theirs) of (x, y).
  bool clear_of_props(double x, double y, double radius) const;
  void remember(double x, double y, double radius);
  /// The lamp heads within `reach` metres (horizontally) of where `pose` stands, as the room a
  /// crown leaves them in the frame `pose` places it in.
  std::vector<Clearance> lamp_clearances(const Rigid& pose, double reach) const;
  /// True when a drivable lane is within `margin` metres.
  bool near_drivable(double x, double y, double margin) const;
  /// True when a building or wall stands over (x, y) (a ray down from high above hits one).
  bool under_building(double x, double y, double z) const;
};

/// Ground: a terrain height field under and around the road surface, and a skirt to the horizon.
void build_ground(WorldBuild& w, const xodr::RoadMesh& road);
/// Verges: strips of terrain from the outer edge of roads and sidewalks down to the ground,
/// carrying their distance from the edge so that the grass thins into a trodden verge there.
void build_verges(WorldBuild& w);
/// Bands of lane surface under the cracks where two roads' outer borders meet side by side.
void build_seams(WorldBuild& w);
/// Road surface in the small holes that junctions' roads enclose (xodr::find_junction_holes).
void build_junction_paving(WorldBuild& w, const xodr::RoadMesh& road);
/// Trees, bushes and street lights along the roads.
void build_roadside(WorldBuild& w);
/// True for the OpenDRIVE country codes of Korea ("KR", "KOR", "Korea", any case).
bool is_korean(const std::string& country);
/// The labels every drawn signal carries: its id, country, type and subtype.
ObjectInfo signal_info(const xodr::Signal& s);
/// OpenDRIVE signals as traffic lights and signs.
void build_signals(WorldBuild& w);
/// A signal that stands for paint on the road (German StVO or Korean 5xx numbers: stop line,
/// crosswalk, give-way line, crosswalk-ahead diamond) painted across the lanes it covers (a
/// marking Corsa does not paint is left out with a warning); false when it is no road marking.
bool build_signal_marking(WorldBuild& w, size_t road, const xodr::Signal& signal);
/// OpenDRIVE objects.
void build_objects(WorldBuild& w);
/// An object's outline corners in its frame (cornerRoad ones converted through the road).
std::vector<Vec3> outline_points(const xodr::Map& map, size_t road, const xodr::Outline& o,
                                 const Rigid& frame);
/// The object's extent in its frame: its outline's bounds, or its length x width box.
void object_extent(const xodr::Object& o, const std::vector<Vec3>& outline, double& x0, double& x1,
                   double& y0, double& y1);
/// Where an object stands: once, or along its repeats (a copy every `distance` metres, or
/// pieces of at most 10 m following the road for stretched ones, with their lengths).
void object_frames(const xodr::Map& map, size_t r, const xodr::Object& o,
                   std::vector<Rigid>& frames, std::vector<double>& lengths);
/// Guard rails and right-of-way fences along the outer edges of motorways.
void build_rails(WorldBuild& w);
/// Generated buildings along streets, where no building stands.
void build_buildings(WorldBuild& w);
/// Street furniture (bus stops, street-name signs, hydrants, bins, benches, bollards) in the
/// kerb-side zone of sidewalks, clear of the walking path, crosswalks, junction mouths and props.
void build_furniture(WorldBuild& w);
/// Parked cars in the map's parking lanes and parking spaces, and (when asked) along the kerbs
/// of streets without parking markup, clear of props, crosswalks, bus stops and hydrants.
void build_parked_vehicles(WorldBuild& w);

}  // namespace corsa::sensors::detail
