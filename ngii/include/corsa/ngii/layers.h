#pragma once

// The NGII HD road layers (정밀도로지도) as plain data: A1_NODE, A2_LINK and, when present,
// B2_SURFACELINEMARK and C1_TRAFFICLIGHT. Coordinates are in the layers' own projected CRS
// (metres; easting x, northing y, height z), text is UTF-8 (the DBF files are CP949).
// Field meanings follow ../shared/data/ngii/README.md.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/core/vec.h"

namespace corsa::ngii {

/// A vertex in the layer CRS: metres.
using Point3 = corsa::Vec3;

/// The coordinate reference system named by a layer's .prj.
struct Crs {
  std::string wkt;          ///< the .prj text as found (ESRI WKT)
  std::string proj_string;  ///< PROJ's reading of it, e.g. "+proj=utm +zone=52 +datum=WGS84 ..."
  std::string name;         ///< e.g. "WGS_1984_UTM_Zone_52N"
  std::string authority;    ///< e.g. "EPSG:32652" when PROJ identifies it, else empty
};

/// A1_NODE: a point where links start or end.
struct Node {
  std::string id;
  std::string node_type;  ///< NodeType code: 1 intersection, 7 lane-count change, 99 other, ...
  Point3 position;
  int64_t record = 0;  ///< 0-based record number in A1_NODE
};

/// A2_LINK: the centre line of one lane between two nodes, digitised in the driving direction.
struct Link {
  std::string id;
  std::string link_type;     ///< LinkType code: "1" intersection path, "6" ordinary lane, ...
  std::string road_rank;     ///< RoadRank code
  std::string road_type;     ///< RoadType code: 1 ordinary, 2 tunnel, 3 bridge, ...
  std::string road_no;       ///< RoadNo, empty in real data
  int lane_no = 0;           ///< LaneNo: 1 innermost, 9x left-turn pockets; 0 when missing
  int max_speed = 0;         ///< MaxSpeed in km/h; 0 means missing
  std::string right_id;      ///< R_LinkID: same-direction neighbour to the right, or empty
  std::string left_id;       ///< L_LinkID
  std::string from_node;     ///< FromNodeID
  std::string to_node;       ///< ToNodeID
  double length_attr = 0.0;  ///< the Length attribute (m), not the geometry length
  std::vector<Point3> points;
  int64_t record = 0;  ///< 0-based record number in A2_LINK
};

/// B2_SURFACELINEMARK: a painted line along (or across) the lanes.
struct SurfaceMark {
  std::string id;
  std::string type;        ///< Type: colour, multiplicity, pattern digits (e.g. "211"), "999" other
  std::string kind;        ///< Kind: 501 centre line, 503 lane line, 530 stop line, ...
  std::string right_link;  ///< R_linkID: the link on the right of the marking
  std::string left_link;   ///< L_linkID
  std::vector<Point3> points;
  int64_t record = 0;
};

/// C1_TRAFFICLIGHT: a signal head controlling one link.
struct TrafficLight {
  std::string id;
  std::string type;     ///< Type code: 1 horizontal 3-colour, 11 pedestrian, ...
  std::string link_id;  ///< LinkID: the A2 link it controls
  int ref_lane = 0;     ///< Ref_Lane
  Point3 position;
  int64_t record = 0;
};

/// The layers of road furniture and areas (NGII data model 2020, manual 2023.07 §9.4) that the
/// converter turns into OpenDRIVE objects, signals and tunnel/bridge records.
enum class FeatureLayer : uint8_t {
  kSafetySign,   ///< B1_SAFETYSIGN (PolygonZ): the sign board
  kSurfaceMark,  ///< B3_SURFACEMARK (PolygonZ): arrows (Type 1), crosswalks (Type 5)
  kBarrier,      ///< C3_VEHICLEPROTECTIONSAFETY (PolyLineZ): guard rails, walls, kerbs
  kSpeedBump,    ///< C4_SPEEDBUMP (PolygonZ)
  kPost,         ///< C6_POSTPOINT (PointZ): posts of signs and lights
  kSection,      ///< A3_DRIVEWAYSECTION (PolygonZ): bridges, tunnels, underpasses
  kSubsidiary,   ///< A4_SUBSIDIARYSECTION (PolygonZ): rest areas, sidewalks, cycle paths
  kParkingLot,   ///< A5_PARKINGLOT (PolygonZ)
};

/// One record of a feature layer. Fields a layer does not have are empty.
struct Feature {
  FeatureLayer layer = FeatureLayer::kSafetySign;
  std::string id;
  std::string type;            ///< Type (B1, B3, C3, C4, C6, A5), SubType (A4)
  std::string kind;            ///< Kind (B3 4-digit mark code, A3 section kind), RoadType (A3)
  std::string link_id;         ///< LinkID: the A2 link it concerns (B1, B3, C4), or empty
  std::string remark;          ///< Remark (B1: a speed or weight limit), Name (A4)
  std::vector<Point3> points;  ///< outline ring (polygons), line, or the point
  int64_t record = 0;
};

/// All layers of one area. File paths are as the user named them (for messages).
struct Layers {
  std::filesystem::path dir;
  Crs crs;
  std::vector<Node> nodes;
  std::vector<Link> links;
  std::vector<SurfaceMark> marks;    ///< empty when B2 is absent
  std::vector<TrafficLight> lights;  ///< empty when C1 is absent
  std::string node_file;             ///< ".../A1_NODE.dbf"
  std::string link_file;             ///< ".../A2_LINK.dbf"
  std::string mark_file;             ///< empty when absent
  std::string light_file;            ///< empty when absent
  /// The feature layers present (B1, B3, C3, C4, C6, A3, A4, A5), in that layer order, each
  /// in record order; `feature_files` names each layer's .dbf by FeatureLayer (empty: absent).
  std::vector<Feature> features;
  std::string feature_files[8];
};

/// Reads the layers from `path`: a folder holding A1_NODE.* and A2_LINK.* (B2, C1 and the feature
/// layers optional), or the path of A2_LINK.shp itself. File names are matched case-insensitively.
///
/// Throws corsa::InputError naming the file (and the record, when one is at fault) for: a missing
/// .shp/.shx/.dbf/.prj, a wrong shape type, a truncated or corrupt .shp, a .dbf whose record
/// count differs from the .shp, a missing required field, a link pointing to a node that does
/// not exist, duplicate ids, or a .prj PROJ cannot read. Tolerated oddities (missing Z, duplicate
/// consecutive vertices, text that is not valid CP949) are warned about once per kind.
Layers read_layers(const std::filesystem::path& path, corsa::Diagnostics& diagnostics);

}  // namespace corsa::ngii
