// <junction> with its connections and laneLinks (OpenDRIVE 1.8 §10).

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
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
  return junction;
}

}  // namespace corsa::xodr::detail
