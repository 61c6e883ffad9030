// <junction> with its connections and laneLinks (OpenDRIVE 1.8 §10).

#include <limits>

#include "corsa/core/strings.h"
#include "parse_elements.h"

namespace corsa::xodr::detail {

Connection parse_connection(const XmlReader& reader, const XMLElement* e) {
  Connection connection;
  connection.line = e->line();
  connection.id = reader.text_or(e, "id", "");
  connection.incoming_road = reader.text_or(e, "incomingRoad", "");
  connection.connecting_road = reader.text_or(e, "connectingRoad", "");
  connection.linked_road = reader.text_or(e, "linkedRoad", "");
  const std::string contact = reader.text_or(e, "contactPoint", "");
  if (contact == "start") {
    connection.contact_point = ContactPoint::kStart;
  } else if (contact == "end") {
    connection.contact_point = ContactPoint::kEnd;
  } else if (!contact.empty()) {
    reader.fail(e, "contactPoint must be 'start' or 'end', not '" + corsa::clip(contact) + "'");
  }
  for (const XMLElement* child : children(e)) {
    if (named(child, "laneLink")) {
      connection.lane_links.push_back(
          LaneLink{reader.integer(child, "from"), reader.integer(child, "to")});
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
  return connection;
}

namespace {

/// sStart/sEnd of a lane segment: metres, or the keywords "begin"/"start" (0) and "end".
double parse_boundary_s(const XmlReader& reader, const XMLElement* e, const char* name) {
  const std::string text = reader.text(e, name);
  if (text == "begin" || text == "start") {
    return 0.0;
  }
  if (text == "end") {
    return std::numeric_limits<double>::infinity();
  }
  const double s = reader.number(e, name);
  if (s < 0.0) {
    reader.fail(e, std::string(name) + " must not be negative");
  }
  return s;
}

JunctionBoundarySegment parse_boundary_segment(const XmlReader& reader, const XMLElement* e) {
  JunctionBoundarySegment segment;
  segment.line = e->line();
  segment.road_id = reader.text(e, "roadId");
  const std::string type = reader.text(e, "type");
  if (type == "lane") {
    segment.boundary_lane = reader.integer(e, "boundaryLane");
    segment.s_start = parse_boundary_s(reader, e, "sStart");
    segment.s_end = parse_boundary_s(reader, e, "sEnd");
  } else if (type == "joint") {
    segment.joint = true;
    const std::string contact = reader.text(e, "contactPoint");
    if (contact == "start") {
      segment.contact_point = ContactPoint::kStart;
    } else if (contact == "end") {
      segment.contact_point = ContactPoint::kEnd;
    } else {
      reader.fail(e, "contactPoint must be 'start' or 'end', not '" + corsa::clip(contact) + "'");
    }
    if (e->attribute("jointLaneStart") != nullptr) {
      segment.joint_lane_start = reader.integer(e, "jointLaneStart");
    }
    if (e->attribute("jointLaneEnd") != nullptr) {
      segment.joint_lane_end = reader.integer(e, "jointLaneEnd");
    }
  } else {
    reader.fail(e,
                "boundary segment type must be 'lane' or 'joint', not '" + corsa::clip(type) + "'");
  }
  return segment;
}

// <priority high low>: at least one of the two connecting roads is named (t_junction_priority).
JunctionPriority parse_priority(const XmlReader& reader, const XMLElement* e) {
  JunctionPriority priority{reader.text_or(e, "high", ""), reader.text_or(e, "low", ""), e->line()};
  if (priority.high.empty() && priority.low.empty()) {
    reader.fail(e, "<priority> needs attribute 'high' or 'low'");
  }
  return priority;
}

}  // namespace

Junction parse_junction(const XmlReader& reader, const XMLElement* e) {
  Junction junction;
  junction.line = e->line();
  junction.id = reader.text(e, "id");
  junction.name = reader.text_or(e, "name", "");
  const std::string type = reader.text_or(e, "type", "default");
  if (type == "default") {
    junction.type = JunctionType::kDefault;
  } else if (type == "direct") {
    junction.type = JunctionType::kDirect;
  } else if (type == "virtual") {
    junction.type = JunctionType::kVirtual;
  } else if (type == "crossing") {
    junction.type = JunctionType::kCrossing;
  } else {
    reader.fail(e, "unknown junction type '" + corsa::clip(type) + "'");
  }
  for (const XMLElement* child : children(e)) {
    if (named(child, "connection")) {
      Connection connection = parse_connection(reader, child);
      if (connection.incoming_road.empty()) {
        reader.fail(child, "<connection> needs attribute 'incomingRoad'");
      }
      if (connection.connecting_road.empty() && connection.linked_road.empty()) {
        reader.fail(child,
                    "<connection> needs 'connectingRoad' (or 'linkedRoad' in a direct "
                    "junction)");
      }
      junction.connections.push_back(std::move(connection));
    } else if (named(child, "priority")) {
      junction.priorities.push_back(parse_priority(reader, child));
    } else if (named(child, "controller")) {
      junction.controllers.push_back(JunctionController{reader.text(child, "id"),
                                                        reader.text_or(child, "type", ""),
                                                        parse_sequence(reader, child)});
    } else if (named(child, "boundary")) {
      for (const XMLElement* segment : children(child)) {
        if (named(segment, "segment")) {
          junction.boundary.push_back(parse_boundary_segment(reader, segment));
        } else if (!is_ignored_element(segment->name())) {
          reader.unknown_child(child, segment);
        }
      }
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
  return junction;
}

std::optional<uint32_t> parse_sequence(const XmlReader& reader, const XMLElement* e) {
  if (e->attribute("sequence") == nullptr) {
    return std::nullopt;
  }
  const int sequence = reader.integer(e, "sequence");
  if (sequence < 0) {
    reader.fail(e, "sequence must not be negative");
  }
  return static_cast<uint32_t>(sequence);
}

Controller parse_controller(const XmlReader& reader, const XMLElement* e) {
  Controller controller;
  controller.line = e->line();
  controller.id = reader.text(e, "id");
  controller.name = reader.text_or(e, "name", "");
  controller.sequence = parse_sequence(reader, e);
  for (const XMLElement* child : children(e)) {
    if (named(child, "control")) {
      controller.controls.push_back(
          Control{reader.text(child, "signalId"), reader.text_or(child, "type", "")});
    } else if (named(child, "userData")) {
      add_user_data(reader, child, controller.user_data);
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
  return controller;
}

}  // namespace corsa::xodr::detail
