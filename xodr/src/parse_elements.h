#pragma once

// One parse function per OpenDRIVE element kind (private to the parser).

#include "corsa/xodr/model.h"
#include "xml_reader.h"

namespace corsa::xodr::detail {

Header parse_header(const XmlReader& reader, const XMLElement* e);
Road parse_road(const XmlReader& reader, const XMLElement* e);
void parse_road_link(const XmlReader& reader, const XMLElement* e, Road& road);
RoadType parse_road_type(const XmlReader& reader, const XMLElement* e);
void parse_plan_view(const XmlReader& reader, const XMLElement* e, Road& road);
Geometry parse_geometry(const XmlReader& reader, const XMLElement* e);
void parse_elevation_profile(const XmlReader& reader, const XMLElement* e, Road& road);
void parse_lateral_profile(const XmlReader& reader, const XMLElement* e, Road& road);
/// <elevation>, <superelevation>, <laneOffset>: s, a, b, c, d.
Poly3 parse_poly3_record(const XmlReader& reader, const XMLElement* e);
void parse_lanes(const XmlReader& reader, const XMLElement* e, Road& road);
LaneSection parse_lane_section(const XmlReader& reader, const XMLElement* e);
Lane parse_lane(const XmlReader& reader, const XMLElement* e, bool center);
/// <width>, <border>: sOffset, a, b, c, d.
Poly3 parse_width_record(const XmlReader& reader, const XMLElement* e);
RoadMark parse_road_mark(const XmlReader& reader, const XMLElement* e);
LaneSpeed parse_lane_speed(const XmlReader& reader, const XMLElement* e);
void parse_objects(const XmlReader& reader, const XMLElement* e, Road& road);
/// nullopt for an object left out (a lenient reading: nothing places it on its road).
std::optional<Object> parse_object(const XmlReader& reader, const XMLElement* e);
void parse_signals(const XmlReader& reader, const XMLElement* e, Road& road);
Signal parse_signal(const XmlReader& reader, const XMLElement* e);
Junction parse_junction(const XmlReader& reader, const XMLElement* e);
/// Top-level <controller> with its <control>s (§14.6).
Controller parse_controller(const XmlReader& reader, const XMLElement* e);
/// Appends <userData code value> to `out` (its free content is read past). Pre-1.5 files (CARLA's)
/// carry userData without a code, holding only child elements: nothing to keep, skipped.
void add_user_data(const XmlReader& reader, const XMLElement* e, std::vector<UserData>& out);
/// `sequence` attributes: a non-negative integer, or nothing when absent.
std::optional<uint32_t> parse_sequence(const XmlReader& reader, const XMLElement* e);
Connection parse_connection(const XmlReader& reader, const XMLElement* e);

/// A speed in m/s from a value and an OpenDRIVE unit ("m/s", "km/h", "mph"); unknown unit ->
/// error at `e`.
double speed_in_mps(const XmlReader& reader, const XMLElement* e, double value,
                    const std::string& unit);

/// Elements of the standard that Corsa reads past on purpose (user data, materials, ...): these
/// are skipped without a warning.
bool is_ignored_element(std::string_view name);

}  // namespace corsa::xodr::detail
