#include "bundled_maps.h"

#include <array>
#include <cmath>
#include <numbers>
#include <string>

namespace corsa::xodr::bundled {
namespace {

constexpr double kPi = std::numbers::pi;
// A local transverse Mercator frame (Seoul), so that the sun's position can be computed.
constexpr const char* kGeoReference =
    "+proj=tmerc +lat_0=37.5665 +lon_0=126.978 +k=1 +x_0=0 +y_0=0 +ellps=WGS84 +units=m +no_defs";

Header header(const char* name) {
  Header h;
  h.rev_major = 1;
  h.rev_minor = 8;
  h.name = name;
  h.version = "1";
  h.date = "2026-01-01";
  h.vendor = "Corsa";
  h.geo_reference = kGeoReference;
  return h;
}

RoadMark mark(const char* type, const char* color, double width, const char* lane_change) {
  RoadMark m;
  m.type = type;
  m.color = color;
  m.width = width;
  m.lane_change = lane_change;
  return m;
}

Lane lane(int id, LaneType type, double width) {
  Lane l;
  l.id = id;
  l.type = type;
  if (id != 0) {
    l.widths.push_back(Poly3{0.0, width, 0.0, 0.0, 0.0});
  }
  return l;
}

Geometry geometry(double s, double x, double y, double hdg, double length, GeometryShape shape) {
  return Geometry{.s = s, .x = x, .y = y, .hdg = hdg, .length = length, .shape = shape};
}

RoadType road_type(const char* type, double kmh) {
  RoadType t;
  t.type = type;
  t.country = "KR";
  t.max_speed = kmh / 3.6;
  return t;
}

}  // namespace

MapData motorway() {
  MapData map;
  map.header = header("Corsa motorway 2 km");
  map.header.north = 12.5;
  map.header.south = -12.5;
  map.header.east = 2000.0;
  map.header.west = 0.0;
  Road road;
  road.id = "1";
  road.name = "Motorway";
  road.length = 2000.0;
  road.types.push_back(road_type("motorway", 130.0));
  road.plan_view.push_back(geometry(0.0, 0.0, 0.0, 0.0, 2000.0, LineGeometry{}));
  road.elevation.push_back(Poly3{});
  LaneSection section;
  for (int id = 4; id >= -4; --id) {
    const int n = std::abs(id);
    Lane l = lane(id,
                  n == 4    ? LaneType::kShoulder
                  : id == 0 ? LaneType::kNone
                            : LaneType::kDriving,
                  n == 4 ? 2.5 : 3.75);
    // Marks sit on a lane's outer border; the centre lane's on the reference line.
    if (id == 0) {
      l.road_marks.push_back(mark("solid solid", "standard", 0.15, "none"));
    } else if (n < 3) {
      l.road_marks.push_back(mark("broken", "standard", 0.15, "both"));
    } else if (n == 3) {
      l.road_marks.push_back(mark("solid", "standard", 0.30, "none"));
    } else {
      l.road_marks.push_back(mark("none", "standard", 0.0, "none"));
    }
    section.lanes.push_back(l);
  }
  road.lane_sections.push_back(section);
  map.roads.push_back(road);
  return map;
}

namespace {

constexpr double kJunctionRadius = 12.0;  // m from the centre to where the arms start
constexpr double kArmLength = 100.0;
constexpr double kLaneWidth = 3.5;
constexpr double kSidewalkWidth = 2.0;

struct Arm {
  const char* id;
  double hdg;  // pointing away from the junction
};
constexpr std::array<Arm, 4> kArms = {
    {{"1", 0.0}, {"2", 0.5 * kPi}, {"3", kPi}, {"4", -0.5 * kPi}}};

Lane sidewalk(int id) {
  Lane l = lane(id, LaneType::kSidewalk, kSidewalkWidth);
  l.heights.push_back(LaneHeight{0.0, 0.15, 0.15});  // a 15 cm kerb
  return l;
}

Road arm_road(const Arm& arm) {
  Road road;
  road.id = arm.id;
  road.name = std::string("Arm ") + arm.id;
  road.length = kArmLength;
  road.predecessor = RoadLink{LinkElement::kJunction, "100", ContactPoint::kNone};
  road.types.push_back(road_type("town", 50.0));
  road.plan_view.push_back(geometry(0.0, kJunctionRadius * std::cos(arm.hdg),
                                    kJunctionRadius * std::sin(arm.hdg), arm.hdg, kArmLength,
                                    LineGeometry{}));
  LaneSection section;
  section.lanes.push_back(sidewalk(2));
  section.lanes.push_back(lane(1, LaneType::kDriving, kLaneWidth));
  section.lanes.back().road_marks.push_back(mark("solid", "standard", 0.15, "none"));
  section.lanes.push_back(lane(0, LaneType::kNone, 0.0));
  section.lanes.back().road_marks.push_back(mark("solid", "yellow", 0.15, "none"));
  section.lanes.push_back(lane(-1, LaneType::kDriving, kLaneWidth));
  section.lanes.back().road_marks.push_back(mark("solid", "standard", 0.15, "none"));
  section.lanes.push_back(sidewalk(-2));
  road.lane_sections.push_back(section);
  return road;
}

/// A connecting road from arm `from` (its incoming lane 1) to arm `to` (its lane -1). Its
/// reference line runs from one arm's start to the other's, so that its lane -1 continues the
/// arms' lanes; `turn` is 0 straight, +1 left, -1 right.
Road connecting_road(const std::string& id, const Arm& from, const Arm& to, int turn) {
  Road road;
  road.id = id;
  road.junction = "100";
  road.predecessor = RoadLink{LinkElement::kRoad, from.id, ContactPoint::kStart};
  road.successor = RoadLink{LinkElement::kRoad, to.id, ContactPoint::kStart};
  road.types.push_back(road_type("town", 50.0));
  const double x = kJunctionRadius * std::cos(from.hdg);
  const double y = kJunctionRadius * std::sin(from.hdg);
  const double hdg = std::remainder(from.hdg + kPi, 2.0 * kPi);
  if (turn == 0) {
    road.length = 2.0 * kJunctionRadius;
    road.plan_view.push_back(geometry(0.0, x, y, hdg, road.length, LineGeometry{}));
  } else {
    // A quarter circle of radius kJunctionRadius, centred on the corner between the two arms.
    road.length = 0.5 * kPi * kJunctionRadius;
    road.plan_view.push_back(
        geometry(0.0, x, y, hdg, road.length, ArcGeometry{turn / kJunctionRadius}));
  }
  LaneSection section;
  section.lanes.push_back(lane(0, LaneType::kNone, 0.0));
  Lane driving = lane(-1, LaneType::kDriving, kLaneWidth);
  driving.predecessors.push_back(1);
  driving.successors.push_back(-1);
  section.lanes.push_back(driving);
  if (turn < 0) {
    // The corner sidewalk: continues arm `from`'s left sidewalk into arm `to`'s right one.
    Lane corner = sidewalk(-2);
    corner.predecessors.push_back(2);
    corner.successors.push_back(-2);
    section.lanes.push_back(corner);
  }
  road.lane_sections.push_back(section);
  return road;
}

}  // namespace

MapData intersection() {
  MapData map;
  map.header = header("Corsa four-way intersection");
  const double extent = kJunctionRadius + kArmLength + kLaneWidth + kSidewalkWidth;
  map.header.north = extent;
  map.header.south = -extent;
  map.header.east = extent;
  map.header.west = -extent;
  for (const Arm& arm : kArms) {
    map.roads.push_back(arm_road(arm));
  }
  Junction junction;
  junction.id = "100";
  junction.name = "Intersection";
  int next_id = 101;
  for (size_t a = 0; a < kArms.size(); ++a) {
    // Arms are counter-clockwise. Driving in from arm a, a right turn leaves by arm a+1, straight
    // on by a+2 and a left turn by a+3.
    for (const int turn : {0, 1, -1}) {
      const size_t b = (a + (turn == 0 ? 2 : turn == 1 ? 3 : 1)) % kArms.size();
      const std::string id = std::to_string(next_id++);
      map.roads.push_back(connecting_road(id, kArms[a], kArms[b], turn));
      Connection connection;
      connection.id = std::to_string(junction.connections.size());
      connection.incoming_road = kArms[a].id;
      connection.connecting_road = id;
      connection.contact_point = ContactPoint::kStart;
      connection.lane_links.push_back(LaneLink{1, -1});
      if (turn < 0) {
        connection.lane_links.push_back(LaneLink{2, -2});
      }
      junction.connections.push_back(connection);
    }
  }
  map.junctions.push_back(junction);
  return map;
}

}  // namespace corsa::xodr::bundled
