// Entry points of the OpenDRIVE reader: XML well-formedness, the root element and its children
// (header, roads, junctions), the header itself. The element kinds below the root have their
// own parse functions (parse_road.cpp, parse_lanes.cpp, parse_junction.cpp, parse_objects.cpp).

#include "corsa/xodr/parser.h"

#include <algorithm>
#include <array>

#include "corsa/core/atomic_file.h"
#include "corsa/core/strings.h"
#include "parse_elements.h"

namespace corsa::xodr {
namespace detail {

bool is_ignored_element(std::string_view name) {
  // Parts of OpenDRIVE 1.4-1.8 that carry nothing Corsa evaluates (data quality, materials,
  // lane access rules and heights, controllers, railroads, surface CRG, ...).
  static constexpr std::array<std::string_view, 38> kIgnored = {"userData",
                                                                "include",
                                                                "dataQuality",
                                                                "material",
                                                                "access",
                                                                "height",
                                                                "rule",
                                                                "visibility",
                                                                "controller",
                                                                "junctionGroup",
                                                                "station",
                                                                "surface",
                                                                "railroad",
                                                                "neighbor",
                                                                "crossfall",
                                                                "priority",
                                                                "sway",
                                                                "explicit",
                                                                "repeat",
                                                                "outline",
                                                                "outlines",
                                                                "validity",
                                                                "parkingSpace",
                                                                "markings",
                                                                "borders",
                                                                "objectReference",
                                                                "tunnel",
                                                                "bridge",
                                                                "signalReference",
                                                                "dependency",
                                                                "reference",
                                                                "positionInertial",
                                                                "positionRoad",
                                                                "semantics",
                                                                "boundary",
                                                                "roadMark",
                                                                "crossPath",
                                                                "elementDir"};
  return std::find(kIgnored.begin(), kIgnored.end(), name) != kIgnored.end();
}

Header parse_header(const XmlReader& reader, const XMLElement* e) {
  Header header;
  header.line = e->line();
  header.rev_major = reader.integer(e, "revMajor");
  header.rev_minor = reader.integer(e, "revMinor");
  if (header.rev_major != 1 || header.rev_minor < 4 || header.rev_minor > 8) {
    reader.warn_once("revision", e,
                     "OpenDRIVE " + std::to_string(header.rev_major) + "." +
                         std::to_string(header.rev_minor) +
                         " is outside 1.4-1.8; reading it as 1.8");
  }
  header.name = reader.text_or(e, "name", "");
  header.version = reader.text_or(e, "version", "");
  header.date = reader.text_or(e, "date", "");
  header.vendor = reader.text_or(e, "vendor", "");
  header.north = reader.number_or(e, "north", 0.0);
  header.south = reader.number_or(e, "south", 0.0);
  header.east = reader.number_or(e, "east", 0.0);
  header.west = reader.number_or(e, "west", 0.0);
  for (const XMLElement* child : children(e)) {
    if (named(child, "geoReference")) {
      header.geo_reference = std::string(corsa::trim(child->text()));
    } else if (named(child, "offset")) {
      header.offset_x = reader.number_or(child, "x", 0.0);
      header.offset_y = reader.number_or(child, "y", 0.0);
      header.offset_z = reader.number_or(child, "z", 0.0);
      header.offset_hdg = reader.number_or(child, "hdg", 0.0);
    } else if (!is_ignored_element(child->name()) && !named(child, "license") &&
               !named(child, "defaultRegulations")) {
      reader.unknown_child(e, child);
    }
  }
  return header;
}

}  // namespace detail

namespace {

MapData parse_document(const detail::XmlReader& reader, const detail::XmlElement* root) {
  using namespace detail;
  if (root == nullptr || !named(root, "OpenDRIVE")) {
    reader.fail(root, "not an OpenDRIVE document (the root element must be <OpenDRIVE>)");
  }
  MapData map;
  map.source_file = reader.file();
  bool have_header = false;
  for (const XMLElement* child : children(root)) {
    if (named(child, "road")) {
      map.roads.push_back(parse_road(reader, child));
    } else if (named(child, "junction")) {
      map.junctions.push_back(parse_junction(reader, child));
    } else if (named(child, "controller")) {
      map.controllers.push_back(parse_controller(reader, child));
    } else if (named(child, "header")) {
      if (have_header) {
        reader.fail(child, "a second <header>");
      }
      map.header = parse_header(reader, child);
      have_header = true;
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(root, child);
    }
  }
  if (!have_header) {
    reader.fail(root, "<OpenDRIVE> has no <header>");
  }
  map.lenient_readings = reader.take_lenient_readings();
  return map;
}

}  // namespace

namespace {

MapData parse_owned_text(std::string text, const std::string& source_name,
                         corsa::Diagnostics& diagnostics) {
  const detail::XmlDocument document(std::move(text), source_name);
  const detail::XmlReader reader(source_name, diagnostics);
  return parse_document(reader, document.root());
}

}  // namespace

MapData parse_xodr_text(std::string_view text, const std::string& source_name,
                        corsa::Diagnostics& diagnostics) {
  return parse_owned_text(std::string(text), source_name, diagnostics);
}

MapData parse_xodr(const std::filesystem::path& path, corsa::Diagnostics& diagnostics) {
  return parse_owned_text(corsa::read_file(path), path.string(), diagnostics);
}

void refuse_lenient_readings(const MapData& data) {
  if (data.lenient_readings.empty()) return;
  std::vector<corsa::Diagnostic> errors;
  for (const LenientReading& reading : data.lenient_readings) {
    errors.push_back(corsa::make_error(
        data.source_file, reading.line,
        reading.message + " (an error under --strict; otherwise read as " + reading.read_as + ")",
        reading.path));
  }
  throw corsa::InputError(std::move(errors));
}

}  // namespace corsa::xodr
