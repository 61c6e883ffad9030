#pragma once

// The OpenDRIVE data model: plain structs, one per element kind, as read from a file or built by a
// converter (NGII). Units are SI (metres, radians, m/s); s and t follow OpenDRIVE 1.8: s along the
// road reference line, t to its left, headings counter-clockwise from +x.
//
// MapData is mutable while being built; a loaded map is wrapped by Map (map.h), which is read-only
// and adds the evaluation, lane graph and spatial index. The parser, the NGII converter and the
// writer all speak MapData.

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace corsa::xodr {

/// <userData code value>: ancillary data an application attaches to an element (OpenDRIVE 1.7
/// §2.9 / 1.8 §5.5.4), e.g. the source record an element was converted from. Kept in order.
struct UserData {
  std::string code;
  std::string value;
};

/// Cubic a + b ds + c ds^2 + d ds^3 starting at `s` (ds = s_query - s). `s` is absolute road s for
/// elevation/superelevation/laneOffset, and sOffset from the lane section start for widths/borders.
struct Poly3 {
  double s = 0.0;
  double a = 0.0;
  double b = 0.0;
  double c = 0.0;
  double d = 0.0;

  double value(double s_query) const {
    const double ds = s_query - s;
    return a + ds * (b + ds * (c + ds * d));
  }
  double slope(double s_query) const {
    const double ds = s_query - s;
    return b + ds * (2.0 * c + ds * 3.0 * d);
  }
};

// --- plan view (OpenDRIVE 1.8 §7) -----------------------------------------------------------

struct LineGeometry {};
struct ArcGeometry {
  double curvature = 0.0;  ///< 1/m, positive turns left
};
/// Clothoid: curvature changes linearly from start to end over the length.
struct SpiralGeometry {
  double curv_start = 0.0;
  double curv_end = 0.0;
};
/// Deprecated cubic v(u) in the local u/v frame (§7.6.1).
struct Poly3Geometry {
  double a = 0.0, b = 0.0, c = 0.0, d = 0.0;
};
enum class ParamRange { kArcLength, kNormalized };
/// Parametric cubic u(p), v(p); p in [0, length] (arcLength) or [0, 1] (normalized) (§7.6.2).
struct ParamPoly3Geometry {
  double au = 0.0, bu = 0.0, cu = 0.0, du = 0.0;
  double av = 0.0, bv = 0.0, cv = 0.0, dv = 0.0;
  ParamRange range = ParamRange::kNormalized;
};

using GeometryShape =
    std::variant<LineGeometry, ArcGeometry, SpiralGeometry, Poly3Geometry, ParamPoly3Geometry>;

/// One <geometry> record: starts at road `s` at (x, y) heading `hdg`, runs `length` metres.
struct Geometry {
  double s = 0.0;
  double x = 0.0;
  double y = 0.0;
  double hdg = 0.0;
  double length = 0.0;
  GeometryShape shape;
  int line = 0;  ///< source line, 0 when built in memory
};

// --- lateral profile ------------------------------------------------------------------------

/// lateralProfile <shape>: height offset as a cubic in t, at road position s (§8.4.3).
struct ShapeRecord {
  double s = 0.0;
  double t = 0.0;
  double a = 0.0, b = 0.0, c = 0.0, d = 0.0;
};

// --- lanes (§9) -----------------------------------------------------------------------------

enum class LaneType : uint8_t {
  kNone,
  kDriving,
  kStop,
  kShoulder,
  kBiking,
  kSidewalk,
  kWalking,
  kBorder,
  kCurb,
  kRestricted,
  kParking,
  kBidirectional,
  kMedian,
  kSpecial1,
  kSpecial2,
  kSpecial3,
  kRoadWorks,
  kTram,
  kRail,
  kEntry,
  kExit,
  kOffRamp,
  kOnRamp,
  kConnectingRamp,
  kSlipLane,
  kBus,
  kTaxi,
  kHov,
  kShared,
  kOther,  ///< a type name this model does not know; the original text is in Lane::type_name
};

/// True for lane types vehicles drive on (driving, entry, exit, on/off/connecting ramps, slip
/// lanes, bidirectional, bus, taxi, HOV): the one list that routing, lane following, traffic,
/// world -> lane queries and the map's colours use.
bool is_drivable(LaneType type);

/// roadMark record (§9.8), sOffset from the lane section start.
struct RoadMark {
  double s_offset = 0.0;
  std::string type = "none";  ///< none, solid, broken, solid solid, solid broken, broken solid, ...
  std::string weight = "standard";
  std::string color = "standard";
  std::string lane_change = "both";
  double width = 0.12;  ///< m
  double height = 0.0;  ///< m; 0 (flat paint) is not written: the XSD wants height > 0
};

/// <height> record (OpenDRIVE 1.6 §9.5.7 lane height): the lane surface raised by `inner` at
/// its inner border and `outer` at its outer border (m, along z, on top of elevation,
/// superelevation and shape), from s_offset (relative to the section start).
struct LaneHeight {
  double s_offset = 0.0;
  double inner = 0.0;
  double outer = 0.0;
};

struct LaneSpeed {
  double s_offset = 0.0;
  double max_speed = 0.0;  ///< m/s
};

struct Lane {
  int id = 0;  ///< > 0 left of the reference line, 0 the centre lane, < 0 right
  LaneType type = LaneType::kNone;
  std::string type_name;  ///< the type as written in the file
  bool level = false;
  std::vector<int> predecessors;  ///< lane ids in the preceding section / road
  std::vector<int> successors;
  std::vector<Poly3> widths;   ///< width polynomials, s relative to the section start
  std::vector<Poly3> borders;  ///< outer border polynomials (alternative to widths)
  std::vector<RoadMark> road_marks;
  std::vector<LaneSpeed> speeds;
  std::vector<LaneHeight> heights;  ///< lane height records in s order; empty: level with the road
  std::vector<UserData> user_data;
  int line = 0;
};

/// A lane section starting at road `s`. Lanes are ordered left to right: highest id first, the
/// centre lane (id 0) in the middle, lowest id last.
struct LaneSection {
  double s = 0.0;
  bool single_side = false;
  std::vector<Lane> lanes;
  int line = 0;
};

// --- road, links, types ---------------------------------------------------------------------

enum class ContactPoint : uint8_t { kNone, kStart, kEnd };
enum class LinkElement : uint8_t { kNone, kRoad, kJunction };

struct RoadLink {
  LinkElement element_type = LinkElement::kNone;
  std::string element_id;
  ContactPoint contact_point = ContactPoint::kNone;
};

/// <type> record: road type from `s`, with an optional speed limit.
struct RoadType {
  double s = 0.0;
  std::string type;  ///< motorway, rural, town, ...
  std::string country;
  std::optional<double> max_speed;  ///< m/s, converted from the record's unit
};

enum class TrafficRule : uint8_t { kRightHand, kLeftHand };

/// <validity> of a signal (OpenDRIVE 1.8 §14.2): the lanes fromLane..toLane (ids, both ends
/// included) that it applies to.
struct LaneValidity {
  int from_lane = 0;
  int to_lane = 0;
};

struct Signal {
  std::string id;
  std::string name;
  double s = 0.0;
  double t = 0.0;
  double z_offset = 0.0;
  double h_offset = 0.0;
  std::string orientation = "none";  ///< "+", "-" or "none"
  bool dynamic = false;
  std::string country;
  std::string type;
  std::string subtype;
  std::optional<double> value;
  std::string unit;  ///< e_unit (km/h, m, ...); empty: none (only meaningful with a value)
  double height = 0.0;
  double width = 0.0;
  double length = 0.0;  ///< m, the bounding box along u (OpenDRIVE 1.8; 0: not given)
  std::string text;
  /// The lanes it applies to; empty: the lanes its orientation gives (§14.2).
  std::vector<LaneValidity> validities;
  std::vector<UserData> user_data;
  int line = 0;
};

/// A corner of an object outline (OpenDRIVE 1.8 §13.2): cornerRoad (u = s, v = t, z = dz, road
/// coordinates) or cornerLocal (u, v, z in the object's local frame), metres; one kind per
/// outline.
struct OutlineCorner {
  bool road = false;    ///< cornerRoad (s, t) instead of cornerLocal (u, v)
  double u = 0.0;       ///< u, or road s
  double v = 0.0;       ///< v, or road t
  double z = 0.0;       ///< z (local) or dz (road)
  double height = 0.0;  ///< m above the corner
  int id = 0;           ///< unique within the outline (for marking cornerReferences)
};

/// <outline>: a polygon (closed) or polyline outlining an object.
struct Outline {
  int id = 0;
  bool closed = true;
  std::string fill_type;  ///< e_outlineFillType (asphalt, grass, paint, ...) or empty
  std::vector<OutlineCorner> corners;
};

/// <repeat> (§13.4): the object repeated (distance > 0) or stretched (distance 0) along s.
struct ObjectRepeat {
  double s = 0.0;
  double length = 0.0;
  double distance = 0.0;
  double t_start = 0.0, t_end = 0.0;
  double height_start = 0.0, height_end = 0.0;
  double z_offset_start = 0.0, z_offset_end = 0.0;
  std::optional<double> width_start, width_end, length_start, length_end;
};

/// <marking> of an object (§13.10): paint along the outline edges between the referenced
/// corners (crosswalk stripes, stop lines), dashed by line/space lengths (m).
struct ObjectMarking {
  std::string color = "white";
  double width = 0.15;  ///< m
  double z_offset = 0.005;
  double space_length = 0.0;
  double line_length = 0.0;
  std::vector<int> corner_references;  ///< outline corner ids, in order
};

/// <tunnel> or <bridge> record (§13.13, §13.14): from road s over `length` metres.
struct Tunnel {
  std::string id;
  std::string name;
  double s = 0.0;
  double length = 0.0;
  std::string type = "standard";  ///< standard or underpass
  double lighting = 0.0;          ///< 0..1
  double daylight = 0.0;          ///< 0..1
};
struct Bridge {
  std::string id;
  std::string name;
  double s = 0.0;
  double length = 0.0;
  std::string type = "concrete";  ///< concrete, steel, brick, wood
};

struct Object {
  std::string id;
  std::string name;
  std::string type;
  double s = 0.0;
  double t = 0.0;
  double z_offset = 0.0;
  double hdg = 0.0;
  double pitch = 0.0;
  double roll = 0.0;
  double length = 0.0;
  double width = 0.0;
  double height = 0.0;
  double radius = 0.0;
  std::string orientation = "none";
  std::string subtype;
  std::vector<Outline> outlines;
  std::vector<ObjectRepeat> repeats;
  std::vector<ObjectMarking> markings;
  std::vector<UserData> user_data;
  int line = 0;
};

struct Road {
  std::string id;
  std::string name;
  double length = 0.0;
  std::string junction = "-1";  ///< id of the junction this road belongs to, "-1" for none
  TrafficRule rule = TrafficRule::kRightHand;
  RoadLink predecessor;
  RoadLink successor;
  std::vector<RoadType> types;
  std::vector<Geometry> plan_view;
  std::vector<Poly3> elevation;       ///< s absolute
  std::vector<Poly3> superelevation;  ///< radians, s absolute
  std::vector<ShapeRecord> shapes;
  std::vector<Poly3> lane_offsets;  ///< s absolute
  std::vector<LaneSection> lane_sections;
  std::vector<Signal> signals;
  std::vector<Object> objects;
  std::vector<Tunnel> tunnels;
  std::vector<Bridge> bridges;
  std::vector<UserData> user_data;
  int line = 0;

  bool in_junction() const { return junction != "-1" && !junction.empty(); }
};

// --- junctions (§10) ------------------------------------------------------------------------

enum class JunctionType : uint8_t { kDefault, kDirect, kVirtual, kCrossing };

struct LaneLink {
  int from = 0;  ///< lane id on the incoming road
  int to = 0;    ///< lane id on the connecting (or, for direct junctions, linked) road
};

struct Connection {
  std::string id;
  std::string incoming_road;
  std::string connecting_road;  ///< empty for direct junctions
  std::string linked_road;      ///< direct junctions (§10.5)
  ContactPoint contact_point = ContactPoint::kNone;
  std::vector<LaneLink> lane_links;
  int line = 0;
};

/// A junction's <priority> (OpenDRIVE 1.8 §10, t_junction_priority): connecting road `high` has
/// priority over connecting road `low` where their paths meet. Only needed where the signs and
/// signals before or in the junction do not say; at least one of the two is given.
struct JunctionPriority {
  std::string high;  ///< id of the prioritised connecting road (empty: not given)
  std::string low;   ///< id of the connecting road with the lower priority (empty: not given)
  int line = 0;
};

/// A junction's <controller> reference: which signal controller runs in it, and in which order
/// (`sequence`) the junction's controllers take their turn (§10.6 / §14.6).
struct JunctionController {
  std::string id;
  std::string type;
  std::optional<uint32_t> sequence;
};

/// One <segment> of a junction's <boundary> (OpenDRIVE 1.8 §10.9): along the outer border of a
/// lane (`lane`), or across a road's end (`joint`) between two lanes' outer borders.
struct JunctionBoundarySegment {
  bool joint = false;
  std::string road_id;
  int boundary_lane = 0;  ///< lane segments: the lane whose outer border the boundary follows
  /// Lane segments: from s_start to s_end along the road (m; "begin"/"start" are 0, "end" is
  /// +infinity, clamped to the road's length when evaluated).
  double s_start = 0.0;
  double s_end = 0.0;
  ContactPoint contact_point = ContactPoint::kNone;  ///< joint segments: which end
  /// Joint segments: the lanes whose outer borders the segment joins; none: the road's outermost.
  std::optional<int> joint_lane_start;
  std::optional<int> joint_lane_end;
  int line = 0;
};

struct Junction {
  std::string id;
  std::string name;
  JunctionType type = JunctionType::kDefault;
  std::vector<Connection> connections;
  std::vector<JunctionPriority> priorities;  ///< in document order
  std::vector<JunctionController> controllers;
  std::vector<JunctionBoundarySegment> boundary;  ///< the junction's outline, in order
  int line = 0;
};

// --- signal controllers (§14.6) -------------------------------------------------------------

/// <control>: one signal a controller switches.
struct Control {
  std::string signal_id;
  std::string type;
};

/// <controller>: signals that always show the same state (one phase group of an intersection).
struct Controller {
  std::string id;
  std::string name;
  std::optional<uint32_t> sequence;
  std::vector<Control> controls;
  std::vector<UserData> user_data;
  int line = 0;
};

// --- header ---------------------------------------------------------------------------------

struct Header {
  int rev_major = 1;
  int rev_minor = 8;
  std::string name;
  std::string version;
  std::string date;
  std::string vendor;
  double north = 0.0, south = 0.0, east = 0.0, west = 0.0;
  std::string geo_reference;  ///< PROJ string or WKT as written in <geoReference>
  /// <offset>: the file's coordinates are shifted by this to reach the geoReference frame.
  double offset_x = 0.0, offset_y = 0.0, offset_z = 0.0, offset_hdg = 0.0;
  int line = 0;  ///< source line of <header>, 0 when built in memory
};

/// A whole OpenDRIVE document. Roads and junctions in document order.
/// A rule of OpenDRIVE the file broke in a way whose meaning is clear, read as its author meant
/// (docs/opendrive.md "Lenient reading"): warned about as `message (read as read_as)`, and an
/// error where lenient readings are refused (`--strict`, refuse_lenient_readings in parser.h).
struct LenientReading {
  int line = 0;      ///< in MapData::source_file
  std::string path;  ///< element path, e.g. OpenDRIVE/road/objects/object
  std::string message;
  std::string read_as;
};

struct MapData {
  Header header;
  std::vector<Road> roads;
  std::vector<Controller> controllers;
  std::vector<Junction> junctions;
  std::string source_file;  ///< file it was read from, for messages; empty when built in memory
  std::vector<LenientReading> lenient_readings;  ///< in document order
};

}  // namespace corsa::xodr
