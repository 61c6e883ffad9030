// MapData -> OpenDRIVE 1.8 text, element order as in the 1.7/1.8 XSD (document: header, road,
// controller, junction; road: link, type, planView, elevationProfile, lateralProfile, lanes,
// objects, signals, userData; lane: link, width|border, roadMark, speed, height, userData).
// Optional attributes whose value the XSD forbids (roadMark height 0, an empty signal unit) are
// left out, so the output validates against the ASAM 1.7 XSD (a junction's <boundary>, new in
// 1.8, is written only at revMinor 8).

#include "corsa/xodr/writer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>
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

void write_user_data(XmlWriter& w, const std::vector<UserData>& data) {
  for (const UserData& d : data) {
    w.open("userData").attr("code", d.code).attr("value", d.value).end_empty();
  }
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

void write_lane(XmlWriter& w, const Lane& lane, const WriteOptions& options) {
  w.open("lane").attr("id", lane.id);
  w.attr("type", lane.type_name.empty() ? std::string(lane_type_name(lane.type)) : lane.type_name);
  w.attr("level", lane.level ? "true" : "false").children();
  // Pre-1.7 readers (compat) know one predecessor and one successor per lane (1.4 §3.5.2).
  const size_t most = options.single_lane_links ? 1 : SIZE_MAX;
  if (!lane.predecessors.empty() || !lane.successors.empty()) {
    w.open("link").children();
    for (size_t i = 0; i < lane.predecessors.size() && i < most; ++i) {
      w.open("predecessor").attr("id", lane.predecessors[i]).end_empty();
    }
    for (size_t i = 0; i < lane.successors.size() && i < most; ++i) {
      w.open("successor").attr("id", lane.successors[i]).end_empty();
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
    if (m.height > 0.0) {
      w.attr("height", m.height);
    }
    w.end_empty();
  }
  for (const LaneSpeed& speed : lane.speeds) {
    w.open("speed").attr("sOffset", speed.s_offset).attr("max", speed.max_speed);
    w.attr("unit", "m/s").end_empty();
  }
  for (const LaneHeight& height : lane.heights) {
    w.open("height").attr("sOffset", height.s_offset).attr("inner", height.inner);
    w.attr("outer", height.outer).end_empty();
  }
  write_user_data(w, lane.user_data);
  w.close();
}

void write_lane_section(XmlWriter& w, const LaneSection& section, const WriteOptions& options) {
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
        write_lane(w, lane, options);
      }
    }
    w.close();
  }
  w.close();
}

void write_outline(XmlWriter& w, const Outline& outline) {
  w.open("outline").attr("id", outline.id);
  if (!outline.fill_type.empty()) {
    w.attr("fillType", outline.fill_type);
  }
  w.attr("closed", outline.closed ? "true" : "false").children();
  for (const OutlineCorner& c : outline.corners) {
    if (c.road) {
      w.open("cornerRoad").attr("s", c.u).attr("t", c.v).attr("dz", c.z);
    } else {
      w.open("cornerLocal").attr("u", c.u).attr("v", c.v).attr("z", c.z);
    }
    w.attr("height", c.height).attr("id", c.id).end_empty();
  }
  w.close();
}

/// <repeat> (§13.4; every attribute the 1.7 XSD requires, the optional sizes when given).
void write_repeat(XmlWriter& w, const ObjectRepeat& r) {
  w.open("repeat").attr("s", r.s).attr("length", r.length).attr("distance", r.distance);
  w.attr("tStart", r.t_start).attr("tEnd", r.t_end);
  w.attr("heightStart", r.height_start).attr("heightEnd", r.height_end);
  w.attr("zOffsetStart", r.z_offset_start).attr("zOffsetEnd", r.z_offset_end);
  if (r.width_start) {
    w.attr("widthStart", *r.width_start).attr("widthEnd", r.width_end.value_or(*r.width_start));
  }
  if (r.length_start) {
    w.attr("lengthStart", *r.length_start)
        .attr("lengthEnd", r.length_end.value_or(*r.length_start));
  }
  w.end_empty();
}

/// Object types of the OpenDRIVE 1.7 enumeration (e_objectType); the 1.8 additions would fail
/// the 1.7 XSD that readers validate against.
bool standard_object_type(const std::string& type) {
  static constexpr std::array<std::string_view, 26> kTypes = {
      "none",      "obstacle",   "car",          "pole",         "tree",    "vegetation",
      "barrier",   "building",   "parkingSpace", "patch",        "railing", "trafficIsland",
      "crosswalk", "streetLamp", "gantry",       "soundBarrier", "van",     "bus",
      "trailer",   "bike",       "motorbike",    "tram",         "train",   "pedestrian",
      "wind",      "roadMark"};
  return std::find(kTypes.begin(), kTypes.end(), type) != kTypes.end();
}

void write_object(XmlWriter& w, const Object& o) {
  // A type outside the enumeration (older or vendor files: "-1", "guide-post") is written as
  // "none" with the original kept as the subtype, so the output stays valid.
  const bool standard = standard_object_type(o.type);
  w.open("object").attr("id", o.id).attr("name", o.name);
  w.attr("type", standard ? o.type : std::string("none"));
  if (!o.subtype.empty()) {
    w.attr("subtype", o.subtype);
  } else if (!standard) {
    w.attr("subtype", o.type);
  }
  w.attr("s", o.s).attr("t", o.t).attr("zOffset", o.z_offset).attr("hdg", o.hdg);
  w.attr("pitch", o.pitch).attr("roll", o.roll);
  // Either a box or a cylinder (§13.2: radius excludes length and width); 0 sizes are left out.
  if (o.radius > 0.0) {
    w.attr("radius", o.radius);
  } else {
    if (o.length > 0.0) w.attr("length", o.length);
    if (o.width > 0.0) w.attr("width", o.width);
  }
  if (o.height > 0.0) {
    w.attr("height", o.height);
  }
  w.attr("orientation", o.orientation);
  if (o.repeats.empty() && o.outlines.empty() && o.markings.empty() && o.user_data.empty()) {
    w.end_empty();
    return;
  }
  w.children();
  for (const ObjectRepeat& r : o.repeats) {
    write_repeat(w, r);
  }
  if (!o.outlines.empty()) {
    w.open("outlines").children();
    for (const Outline& outline : o.outlines) {
      write_outline(w, outline);
    }
    w.close();
  }
  if (!o.markings.empty()) {
    w.open("markings").children();
    for (const ObjectMarking& m : o.markings) {
      w.open("marking").attr("color", m.color).attr("width", m.width).attr("zOffset", m.z_offset);
      w.attr("spaceLength", m.space_length).attr("lineLength", m.line_length);
      w.attr("startOffset", 0.0).attr("stopOffset", 0.0);
      if (m.corner_references.empty()) {
        w.end_empty();
        continue;
      }
      w.children();
      for (const int id : m.corner_references) {
        w.open("cornerReference").attr("id", id).end_empty();
      }
      w.close();
    }
    w.close();
  }
  write_user_data(w, o.user_data);
  w.close();
}

void write_objects_and_signals(XmlWriter& w, const Road& road) {
  if (!road.objects.empty() || !road.tunnels.empty() || !road.bridges.empty()) {
    w.open("objects").children();
    for (const Object& o : road.objects) {
      write_object(w, o);
    }
    for (const Tunnel& t : road.tunnels) {
      w.open("tunnel").attr("id", t.id).attr("name", t.name).attr("s", t.s);
      w.attr("length", t.length).attr("type", t.type).attr("lighting", t.lighting);
      w.attr("daylight", t.daylight).end_empty();
    }
    for (const Bridge& b : road.bridges) {
      w.open("bridge").attr("id", b.id).attr("name", b.name).attr("s", b.s);
      w.attr("length", b.length).attr("type", b.type).end_empty();
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
      if (!g.unit.empty()) {
        w.attr("unit", g.unit);
      }
      w.attr("height", g.height).attr("width", g.width).attr("text", g.text);
      // A signal's length (new in OpenDRIVE 1.8) is not written: every map Corsa writes stays
      // within the 1.7 schema, which xmllint can check (it cannot compile the 1.8 one).
      if (g.user_data.empty() && g.validities.empty()) {
        w.end_empty();
        continue;
      }
      w.children();
      for (const LaneValidity& v : g.validities) {
        w.open("validity").attr("fromLane", v.from_lane).attr("toLane", v.to_lane).end_empty();
      }
      write_user_data(w, g.user_data);
      w.close();
    }
    w.close();
  }
}

void write_road(XmlWriter& w, const Road& road, const WriteOptions& options) {
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
    write_lane_section(w, section, options);
  }
  w.close();
  write_objects_and_signals(w, road);
  write_user_data(w, road.user_data);
  w.close();
}

void write_controller(XmlWriter& w, const Controller& controller) {
  w.open("controller").attr("id", controller.id).attr("name", controller.name);
  if (controller.sequence) {
    w.attr("sequence", static_cast<int>(*controller.sequence));
  }
  w.children();
  for (const Control& control : controller.controls) {
    w.open("control").attr("signalId", control.signal_id);
    if (!control.type.empty()) {
      w.attr("type", control.type);
    }
    w.end_empty();
  }
  write_user_data(w, controller.user_data);
  w.close();
}

/// <boundary> (OpenDRIVE 1.8 §10.9): a lane segment's "end" (infinite s) written as the keyword.
void write_boundary(XmlWriter& w, const std::vector<JunctionBoundarySegment>& boundary) {
  w.open("boundary").children();
  for (const JunctionBoundarySegment& segment : boundary) {
    w.open("segment")
        .attr("type", segment.joint ? "joint" : "lane")
        .attr("roadId", segment.road_id);
    if (segment.joint) {
      w.attr("contactPoint", contact_name(segment.contact_point));
      if (segment.joint_lane_start) {
        w.attr("jointLaneStart", *segment.joint_lane_start);
      }
      if (segment.joint_lane_end) {
        w.attr("jointLaneEnd", *segment.joint_lane_end);
      }
    } else {
      w.attr("boundaryLane", segment.boundary_lane);
      for (const auto& [name, s] :
           {std::pair{"sStart", segment.s_start}, std::pair{"sEnd", segment.s_end}}) {
        if (std::isinf(s)) {
          w.attr(name, "end");
        } else {
          w.attr(name, s);
        }
      }
    }
    w.end_empty();
  }
  w.close();
}

void write_junction(XmlWriter& w, const Junction& junction, const WriteOptions& options) {
  const char* types[] = {"default", "direct", "virtual", "crossing"};
  const bool legacy = options.legacy_junctions && junction.type == JunctionType::kDirect;
  w.open("junction").attr("id", junction.id).attr("name", junction.name);
  if (!legacy) {
    w.attr("type", types[static_cast<int>(junction.type)]);
  }
  w.children();
  for (const Connection& c : junction.connections) {
    w.open("connection").attr("id", c.id).attr("incomingRoad", c.incoming_road);
    if (!c.connecting_road.empty()) {
      w.attr("connectingRoad", c.connecting_road);
    }
    if (!c.linked_road.empty()) {
      w.attr(legacy ? "connectingRoad" : "linkedRoad", c.linked_road);
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
  for (const JunctionPriority& priority : junction.priorities) {
    w.open("priority");
    if (!priority.high.empty()) {
      w.attr("high", priority.high);
    }
    if (!priority.low.empty()) {
      w.attr("low", priority.low);
    }
    w.end_empty();
  }
  for (const JunctionController& controller : junction.controllers) {
    w.open("controller").attr("id", controller.id);
    if (!controller.type.empty()) {
      w.attr("type", controller.type);
    }
    if (controller.sequence) {
      w.attr("sequence", static_cast<int>(*controller.sequence));
    }
    w.end_empty();
  }
  if (!junction.boundary.empty() && options.rev_minor >= 8) {
    write_boundary(w, junction.boundary);
  }
  w.close();
}

}  // namespace

std::string write_xodr_text(const MapData& map, const WriteOptions& options) {
  XmlWriter w;
  w.open("OpenDRIVE").children();
  write_header(w, map.header, options);
  for (const Road& road : map.roads) {
    write_road(w, road, options);
  }
  for (const Controller& controller : map.controllers) {
    write_controller(w, controller);
  }
  for (const Junction& junction : map.junctions) {
    write_junction(w, junction, options);
  }
  w.close();
  return w.text();
}

WriteOptions compat_options(int rev_minor) {
  WriteOptions options;
  options.rev_minor = rev_minor;
  options.single_lane_links = rev_minor < 7;
  options.legacy_junctions = rev_minor < 7;
  return options;
}

void write_xodr(const MapData& map, const std::filesystem::path& path,
                const WriteOptions& options) {
  corsa::write_file_atomic(path, write_xodr_text(map, options));
}

}  // namespace corsa::xodr
