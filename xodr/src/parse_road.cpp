// <road> and its direct children: link, type/speed, planView/geometry, elevationProfile,
// lateralProfile (OpenDRIVE 1.8 §7, §8).

#include <algorithm>
#include <cmath>

#include "corsa/core/strings.h"
#include "parse_elements.h"

namespace corsa::xodr::detail {
namespace {

ContactPoint parse_contact_point(const XmlReader& reader, const XMLElement* e) {
  const std::string_view* value = e->attribute("contactPoint");
  if (value == nullptr) {
    return ContactPoint::kNone;
  }
  if (corsa::iequals(*value, "start")) {
    return ContactPoint::kStart;
  }
  if (corsa::iequals(*value, "end")) {
    return ContactPoint::kEnd;
  }
  reader.fail(e, "contactPoint must be 'start' or 'end', not '" + corsa::clip(*value) + "'");
}

RoadLink parse_link_target(const XmlReader& reader, const XMLElement* e) {
  RoadLink link;
  const std::string type = reader.text(e, "elementType");
  if (type == "road") {
    link.element_type = LinkElement::kRoad;
  } else if (type == "junction") {
    link.element_type = LinkElement::kJunction;
  } else {
    reader.fail(e, "elementType must be 'road' or 'junction', not '" + corsa::clip(type) + "'");
  }
  link.element_id = reader.text(e, "elementId");
  link.contact_point = parse_contact_point(reader, e);
  if (link.element_type == LinkElement::kRoad && link.contact_point == ContactPoint::kNone) {
    reader.fail(e, "a link to road '" + link.element_id + "' needs a contactPoint");
  }
  return link;
}

}  // namespace

void parse_road_link(const XmlReader& reader, const XMLElement* e, Road& road) {
  for (const XMLElement* child : children(e)) {
    if (named(child, "predecessor")) {
      road.predecessor = parse_link_target(reader, child);
    } else if (named(child, "successor")) {
      road.successor = parse_link_target(reader, child);
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
}

double speed_in_mps(const XmlReader& reader, const XMLElement* e, double value,
                    const std::string& unit) {
  if (unit.empty() || unit == "m/s") {
    return value;
  }
  if (unit == "km/h") {
    return value / 3.6;
  }
  if (unit == "mph") {
    return value * 0.44704;
  }
  reader.fail(e, "unknown speed unit '" + corsa::clip(unit) + "' (m/s, km/h or mph)");
}

RoadType parse_road_type(const XmlReader& reader, const XMLElement* e) {
  RoadType type;
  type.s = reader.non_negative(e, "s");
  type.type = reader.text_or(e, "type", "unknown");
  type.country = reader.text_or(e, "country", "");
  for (const XMLElement* child : children(e)) {
    if (named(child, "speed")) {
      const std::string max = reader.text_or(child, "max", "");
      // §8.3.2: max may be "no limit" or "undefined" instead of a number.
      if (!max.empty() && max != "no limit" && max != "undefined") {
        const double value = reader.non_negative(child, "max");
        type.max_speed = speed_in_mps(reader, child, value, reader.text_or(child, "unit", ""));
      }
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
  return type;
}

Geometry parse_geometry(const XmlReader& reader, const XMLElement* e) {
  Geometry geometry;
  geometry.line = e->line();
  geometry.s = reader.non_negative(e, "s");
  geometry.x = reader.number(e, "x");
  geometry.y = reader.number(e, "y");
  geometry.hdg = reader.number(e, "hdg");
  geometry.length = reader.non_negative(e, "length");
  const XMLElement* shape = e->first_child();
  while (shape != nullptr && is_ignored_element(shape->name())) {
    shape = shape->next_sibling();
  }
  if (shape == nullptr) {
    reader.fail(e, "<geometry> has no line, arc, spiral, poly3 or paramPoly3");
  }
  if (named(shape, "line")) {
    geometry.shape = LineGeometry{};
  } else if (named(shape, "arc")) {
    geometry.shape = ArcGeometry{reader.number(shape, "curvature")};
  } else if (named(shape, "spiral")) {
    geometry.shape =
        SpiralGeometry{reader.number(shape, "curvStart"), reader.number(shape, "curvEnd")};
  } else if (named(shape, "poly3")) {
    geometry.shape = Poly3Geometry{reader.number(shape, "a"), reader.number(shape, "b"),
                                   reader.number(shape, "c"), reader.number(shape, "d")};
  } else if (named(shape, "paramPoly3")) {
    ParamPoly3Geometry p;
    p.au = reader.number(shape, "aU");
    p.bu = reader.number(shape, "bU");
    p.cu = reader.number(shape, "cU");
    p.du = reader.number(shape, "dU");
    p.av = reader.number(shape, "aV");
    p.bv = reader.number(shape, "bV");
    p.cv = reader.number(shape, "cV");
    p.dv = reader.number(shape, "dV");
    const std::string range = reader.text_or(shape, "pRange", "normalized");
    if (range == "arcLength") {
      p.range = ParamRange::kArcLength;
    } else if (range == "normalized") {
      p.range = ParamRange::kNormalized;
    } else {
      reader.fail(shape,
                  "pRange must be 'arcLength' or 'normalized', not '" + corsa::clip(range) + "'");
    }
    geometry.shape = p;
  } else {
    reader.fail(shape, "unknown geometry kind <" + std::string(shape->name()) + ">");
  }
  return geometry;
}

void parse_plan_view(const XmlReader& reader, const XMLElement* e, Road& road) {
  for (const XMLElement* child : children(e)) {
    if (named(child, "geometry")) {
      road.plan_view.push_back(parse_geometry(reader, child));
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
}

Poly3 parse_poly3_record(const XmlReader& reader, const XMLElement* e) {
  return Poly3{reader.non_negative(e, "s"), reader.number(e, "a"), reader.number(e, "b"),
               reader.number(e, "c"), reader.number(e, "d")};
}

void parse_elevation_profile(const XmlReader& reader, const XMLElement* e, Road& road) {
  for (const XMLElement* child : children(e)) {
    if (named(child, "elevation")) {
      road.elevation.push_back(parse_poly3_record(reader, child));
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
}

void parse_lateral_profile(const XmlReader& reader, const XMLElement* e, Road& road) {
  for (const XMLElement* child : children(e)) {
    if (named(child, "superelevation")) {
      road.superelevation.push_back(parse_poly3_record(reader, child));
    } else if (named(child, "shape")) {
      road.shapes.push_back(ShapeRecord{reader.non_negative(child, "s"), reader.number(child, "t"),
                                        reader.number(child, "a"), reader.number(child, "b"),
                                        reader.number(child, "c"), reader.number(child, "d")});
    } else if (named(child, "crossfall")) {
      reader.warn_once("crossfall", child, "<crossfall> (deprecated) is not evaluated");
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
}

Road parse_road(const XmlReader& reader, const XMLElement* e) {
  Road road;
  road.line = e->line();
  road.id = reader.text(e, "id");
  road.name = reader.text_or(e, "name", "");
  road.length = reader.non_negative(e, "length");
  road.junction = reader.text_or(e, "junction", "-1");
  const std::string rule = reader.text_or(e, "rule", "RHT");
  if (rule == "LHT" || rule == "lht") {
    road.rule = TrafficRule::kLeftHand;
  } else if (rule != "RHT" && rule != "rht") {
    reader.fail(e, "rule must be 'RHT' or 'LHT', not '" + corsa::clip(rule) + "'");
  }
  for (const XMLElement* child : children(e)) {
    const std::string_view name = child->name();
    if (name == "link") {
      parse_road_link(reader, child, road);
    } else if (name == "type") {
      road.types.push_back(parse_road_type(reader, child));
    } else if (name == "planView") {
      parse_plan_view(reader, child, road);
    } else if (name == "elevationProfile") {
      parse_elevation_profile(reader, child, road);
    } else if (name == "lateralProfile") {
      parse_lateral_profile(reader, child, road);
    } else if (name == "lanes") {
      parse_lanes(reader, child, road);
    } else if (name == "objects") {
      parse_objects(reader, child, road);
    } else if (name == "signals") {
      parse_signals(reader, child, road);
    } else if (name == "userData") {
      add_user_data(reader, child, road.user_data);
    } else if (!is_ignored_element(name)) {
      reader.unknown_child(e, child);
    }
  }
  if (road.plan_view.empty()) {
    reader.fail(e, "road '" + road.id + "' has no <planView> geometry");
  }
  if (road.lane_sections.empty()) {
    reader.fail(e, "road '" + road.id + "' has no <lanes>/<laneSection>");
  }
  return road;
}

}  // namespace corsa::xodr::detail
