// MapData -> OpenDRIVE 1.8 text, element order as in the 1.8 XSD (road: link, type, planView,
// elevationProfile, lateralProfile, lanes, objects, signals; lane: link, width|border, roadMark,
// speed, height).

#include "corsa/xodr/writer.h"

#include <type_traits>

#include "corsa/core/atomic_file.h"
#include "corsa/xodr/parser.h"
#include "xml_writer.h"

namespace corsa::xodr {
namespace {

using detail::XmlWriter;

const char* contact_name(ContactPoint c) { return c == ContactPoint::kEnd ? "end" : "start"; }

void write_poly(XmlWriter& w, const char* name, const char* s_name, const Poly3& p) {
  w.open(name).attr(s_name, p.s).attr("a", p.a).attr("b", p.b).attr("c", p.c).attr("d", p.d);
  w.end_empty();
}

void write_header(XmlWriter& w, const Header& h, const WriteOptions& options) {
  w.open("header").attr("revMajor", 1).attr("revMinor", options.rev_minor);
  w.attr("name", h.name).attr("version", h.version).attr("date", h.date);
  w.attr("north", h.north).attr("south", h.south).attr("east", h.east).attr("west", h.west);
  w.attr("vendor", h.vendor.empty() ? std::string("Corsa") : h.vendor);
  const bool offset =
      h.offset_x != 0.0 || h.offset_y != 0.0 || h.offset_z != 0.0 || h.offset_hdg != 0.0;
  if (h.geo_reference.empty() && !offset) {
    w.end_empty();
    return;
  }
  w.children();
  if (!h.geo_reference.empty()) {
    w.cdata_element("geoReference", h.geo_reference);
  }
  if (offset) {
    w.open("offset").attr("x", h.offset_x).attr("y", h.offset_y).attr("z", h.offset_z);
    w.attr("hdg", h.offset_hdg).end_empty();
  }
  w.close();
}

void write_link_target(XmlWriter& w, const char* name, const RoadLink& link) {
  if (link.element_type == LinkElement::kNone) {
    return;
  }
  w.open(name).attr("elementType", link.element_type == LinkElement::kRoad ? "road" : "junction");
  w.attr("elementId", link.element_id);
  if (link.contact_point != ContactPoint::kNone) {
    w.attr("contactPoint", contact_name(link.contact_point));
  }
  w.end_empty();
}

void write_geometry(XmlWriter& w, const Geometry& g) {
  w.open("geometry").attr("s", g.s).attr("x", g.x).attr("y", g.y).attr("hdg", g.hdg);
  w.attr("length", g.length).children();
  std::visit(
      [&](const auto& shape) {
        using T = std::decay_t<decltype(shape)>;
        if constexpr (std::is_same_v<T, LineGeometry>) {
          w.open("line").end_empty();
        } else if constexpr (std::is_same_v<T, ArcGeometry>) {
          w.open("arc").attr("curvature", shape.curvature).end_empty();
        } else if constexpr (std::is_same_v<T, SpiralGeometry>) {
          w.open("spiral").attr("curvStart", shape.curv_start).attr("curvEnd", shape.curv_end);
          w.end_empty();
        } else if constexpr (std::is_same_v<T, Poly3Geometry>) {
          w.open("poly3").attr("a", shape.a).attr("b", shape.b).attr("c", shape.c);
          w.attr("d", shape.d).end_empty();
        } else {
          w.open("paramPoly3").attr("aU", shape.au).attr("bU", shape.bu).attr("cU", shape.cu);
          w.attr("dU", shape.du).attr("aV", shape.av).attr("bV", shape.bv).attr("cV", shape.cv);
          w.attr("dV", shape.dv);
          w.attr("pRange", shape.range == ParamRange::kArcLength ? "arcLength" : "normalized");
          w.end_empty();
        }
      },
      g.shape);
  w.close();
}

void write_lane(XmlWriter& w, const Lane& lane) {
  w.open("lane").attr("id", lane.id);
  w.attr("type", lane.type_name.empty() ? std::string(lane_type_name(lane.type)) : lane.type_name);
  w.attr("level", lane.level ? "true" : "false").children();
  if (!lane.predecessors.empty() || !lane.successors.empty()) {
    w.open("link").children();
    for (const int id : lane.predecessors) {
      w.open("predecessor").attr("id", id).end_empty();
    }
    for (const int id : lane.successors) {
      w.open("successor").attr("id", id).end_empty();
    }
    w.close();
  }
  for (const Poly3& p : lane.widths) {
    write_poly(w, "width", "sOffset", p);
  }
  for (const Poly3& p : lane.borders) {
    write_poly(w, "border", "sOffset", p);
  }
  for (const RoadMark& m : lane.road_marks) {
    w.open("roadMark").attr("sOffset", m.s_offset).attr("type", m.type).attr("weight", m.weight);
    w.attr("color", m.color).attr("laneChange", m.lane_change).attr("width", m.width);
    w.attr("height", m.height).end_empty();
  }
  for (const LaneSpeed& speed : lane.speeds) {
    w.open("speed").attr("sOffset", speed.s_offset).attr("max", speed.max_speed);
    w.attr("unit", "m/s").end_empty();
  }
  for (const LaneHeight& height : lane.heights) {
    w.open("height").attr("sOffset", height.s_offset).attr("inner", height.inner);
    w.attr("outer", height.outer).end_empty();
  }
  w.close();
}

void write_lane_section(XmlWriter& w, const LaneSection& section) {
  w.open("laneSection").attr("s", section.s);
  if (section.single_side) {
    w.attr("singleSide", "true");
  }
  w.children();
  const char* groups[] = {"left", "center", "right"};
  for (int group = 0; group < 3; ++group) {
    const auto in_group = [&](const Lane& lane) {
      return group == 0 ? lane.id > 0 : group == 1 ? lane.id == 0 : lane.id < 0;
    };
    bool any = false;
    for (const Lane& lane : section.lanes) {
      any = any || in_group(lane);
    }
    if (!any) {
      continue;
    }
    w.open(groups[group]).children();
    for (const Lane& lane : section.lanes) {  // already left to right, ids descending
      if (in_group(lane)) {
        write_lane(w, lane);
      }
    }
    w.close();
  }
  w.close();
}

void write_objects_and_signals(XmlWriter& w, const Road& road) {
  if (!road.objects.empty()) {
    w.open("objects").children();
    for (const Object& o : road.objects) {
      w.open("object").attr("id", o.id).attr("name", o.name).attr("type", o.type);
      w.attr("s", o.s).attr("t", o.t).attr("zOffset", o.z_offset).attr("hdg", o.hdg);
      w.attr("pitch", o.pitch).attr("roll", o.roll).attr("length", o.length);
      w.attr("width", o.width).attr("height", o.height).attr("radius", o.radius);
      w.attr("orientation", o.orientation).end_empty();
    }
    w.close();
  }
  if (!road.signals.empty()) {
    w.open("signals").children();
    for (const Signal& g : road.signals) {
      w.open("signal").attr("id", g.id).attr("name", g.name).attr("s", g.s).attr("t", g.t);
      w.attr("zOffset", g.z_offset).attr("hOffset", g.h_offset);
      w.attr("orientation", g.orientation).attr("dynamic", g.dynamic ? "yes" : "no");
      w.attr("country", g.country).attr("type", g.type).attr("subtype", g.subtype);
      if (g.value) {
        w.attr("value", *g.value);
      }
      w.attr("unit", g.unit).attr("height", g.height).attr("width", g.width);
      w.attr("text", g.text).end_empty();
    }
    w.close();
  }
}

void write_road(XmlWriter& w, const Road& road) {
  w.open("road").attr("name", road.name).attr("length", road.length).attr("id", road.id);
  w.attr("junction", road.junction.empty() ? std::string("-1") : road.junction);
  w.attr("rule", road.rule == TrafficRule::kLeftHand ? "LHT" : "RHT").children();
  if (road.predecessor.element_type != LinkElement::kNone ||
      road.successor.element_type != LinkElement::kNone) {
    w.open("link").children();
    write_link_target(w, "predecessor", road.predecessor);
    write_link_target(w, "successor", road.successor);
    w.close();
  }
  for (const RoadType& type : road.types) {
    w.open("type").attr("s", type.s).attr("type", type.type);
    if (!type.country.empty()) {
      w.attr("country", type.country);
    }
    if (!type.max_speed) {
      w.end_empty();
      continue;
    }
    w.children();
    w.open("speed").attr("max", *type.max_speed).attr("unit", "m/s").end_empty();
    w.close();
  }
  w.open("planView").children();
  for (const Geometry& g : road.plan_view) {
    write_geometry(w, g);
  }
  w.close();
  if (!road.elevation.empty()) {
    w.open("elevationProfile").children();
    for (const Poly3& p : road.elevation) {
      write_poly(w, "elevation", "s", p);
    }
    w.close();
  }
  if (!road.superelevation.empty() || !road.shapes.empty()) {
    w.open("lateralProfile").children();
    for (const Poly3& p : road.superelevation) {
      write_poly(w, "superelevation", "s", p);
    }
    for (const ShapeRecord& p : road.shapes) {
      w.open("shape").attr("s", p.s).attr("t", p.t).attr("a", p.a).attr("b", p.b);
      w.attr("c", p.c).attr("d", p.d).end_empty();
    }
    w.close();
  }
  w.open("lanes").children();
  for (const Poly3& p : road.lane_offsets) {
    write_poly(w, "laneOffset", "s", p);
  }
  for (const LaneSection& section : road.lane_sections) {
    write_lane_section(w, section);
  }
  w.close();
  write_objects_and_signals(w, road);
  w.close();
}

void write_junction(XmlWriter& w, const Junction& junction) {
  const char* types[] = {"default", "direct", "virtual", "crossing"};
  w.open("junction").attr("id", junction.id).attr("name", junction.name);
  w.attr("type", types[static_cast<int>(junction.type)]).children();
  for (const Connection& c : junction.connections) {
    w.open("connection").attr("id", c.id).attr("incomingRoad", c.incoming_road);
    if (!c.connecting_road.empty()) {
      w.attr("connectingRoad", c.connecting_road);
    }
    if (!c.linked_road.empty()) {
      w.attr("linkedRoad", c.linked_road);
    }
    if (c.contact_point != ContactPoint::kNone) {
      w.attr("contactPoint", contact_name(c.contact_point));
    }
    if (c.lane_links.empty()) {
      w.end_empty();
      continue;
    }
    w.children();
    for (const LaneLink& link : c.lane_links) {
      w.open("laneLink").attr("from", link.from).attr("to", link.to).end_empty();
    }
    w.close();
  }
  w.close();
}

}  // namespace

std::string write_xodr_text(const MapData& map, const WriteOptions& options) {
  XmlWriter w;
  w.open("OpenDRIVE").children();
  write_header(w, map.header, options);
  for (const Road& road : map.roads) {
    write_road(w, road);
  }
  for (const Junction& junction : map.junctions) {
    write_junction(w, junction);
  }
  w.close();
  return w.text();
}

void write_xodr(const MapData& map, const std::filesystem::path& path,
                const WriteOptions& options) {
  corsa::write_file_atomic(path, write_xodr_text(map, options));
}

}  // namespace corsa::xodr
