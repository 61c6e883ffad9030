// <objects>/<object> and <signals>/<signal>: kept with their road positions (OpenDRIVE 1.8
// §13, §14), objects with their outlines and repeats. Other sub-structure (validity,
// materials, markings, ...) is read past.

#include "parse_elements.h"

namespace corsa::xodr::detail {

Object parse_object(const XmlReader& reader, const XMLElement* e) {
  Object object;
  object.line = e->line();
  object.id = reader.text(e, "id");
  object.name = reader.text_or(e, "name", "");
  object.type = reader.text_or(e, "type", "none");
  object.s = reader.number(e, "s");
  object.t = reader.number(e, "t");
  object.z_offset = reader.number_or(e, "zOffset", 0.0);
  object.hdg = reader.number_or(e, "hdg", 0.0);
  object.pitch = reader.number_or(e, "pitch", 0.0);
  object.roll = reader.number_or(e, "roll", 0.0);
  object.length = reader.number_or(e, "length", 0.0);
  object.width = reader.number_or(e, "width", 0.0);
  object.height = reader.number_or(e, "height", 0.0);
  object.radius = reader.number_or(e, "radius", 0.0);
  object.orientation = reader.text_or(e, "orientation", "none");
  auto outline = [&](const XMLElement* o) {
    Outline out;
    const std::string closed = reader.text_or(o, "closed", "true");
    out.closed = closed != "false";
    for (const XMLElement* c : children(o)) {
      OutlineCorner corner;
      if (named(c, "cornerLocal")) {
        corner.u = reader.number(c, "u");
        corner.v = reader.number(c, "v");
        corner.z = reader.number_or(c, "z", 0.0);
      } else if (named(c, "cornerRoad")) {
        corner.road = true;
        corner.u = reader.number(c, "s");
        corner.v = reader.number(c, "t");
        corner.z = reader.number_or(c, "dz", 0.0);
      } else {
        continue;
      }
      corner.height = reader.number_or(c, "height", 0.0);
      out.corners.push_back(corner);
    }
    object.outlines.push_back(std::move(out));
  };
  for (const XMLElement* child : children(e)) {
    if (named(child, "outline")) {  // OpenDRIVE 1.4
      outline(child);
    } else if (named(child, "outlines")) {
      for (const XMLElement* o : children(child)) {
        if (named(o, "outline")) {
          outline(o);
        }
      }
    } else if (named(child, "repeat")) {
      ObjectRepeat r;
      r.s = reader.number(child, "s");
      r.length = reader.number(child, "length");
      r.distance = reader.number_or(child, "distance", 0.0);
      r.t_start = reader.number_or(child, "tStart", object.t);
      r.t_end = reader.number_or(child, "tEnd", r.t_start);
      r.height_start = reader.number_or(child, "heightStart", object.height);
      r.height_end = reader.number_or(child, "heightEnd", r.height_start);
      r.z_offset_start = reader.number_or(child, "zOffsetStart", object.z_offset);
      r.z_offset_end = reader.number_or(child, "zOffsetEnd", r.z_offset_start);
      if (child->attribute("widthStart") != nullptr) {
        r.width_start = reader.number(child, "widthStart");
        r.width_end = reader.number_or(child, "widthEnd", *r.width_start);
      }
      if (child->attribute("lengthStart") != nullptr) {
        r.length_start = reader.number(child, "lengthStart");
        r.length_end = reader.number_or(child, "lengthEnd", *r.length_start);
      }
      object.repeats.push_back(r);
    }
  }
  return object;
}

void parse_objects(const XmlReader& reader, const XMLElement* e, Road& road) {
  for (const XMLElement* child : children(e)) {
    if (named(child, "object")) {
      road.objects.push_back(parse_object(reader, child));
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
}

Signal parse_signal(const XmlReader& reader, const XMLElement* e) {
  Signal signal;
  signal.line = e->line();
  signal.id = reader.text(e, "id");
  signal.name = reader.text_or(e, "name", "");
  signal.s = reader.number(e, "s");
  signal.t = reader.number(e, "t");
  signal.z_offset = reader.number_or(e, "zOffset", 0.0);
  signal.h_offset = reader.number_or(e, "hOffset", 0.0);
  signal.orientation = reader.text_or(e, "orientation", "none");
  const std::string dynamic = reader.text_or(e, "dynamic", "no");
  signal.dynamic = dynamic == "yes" || dynamic == "true";
  signal.country = reader.text_or(e, "country", "");
  signal.type = reader.text_or(e, "type", "");
  signal.subtype = reader.text_or(e, "subtype", "");
  const std::string_view* value = e->attribute("value");
  if (value != nullptr && !value->empty()) {
    signal.value = reader.number(e, "value");
  }
  signal.unit = reader.text_or(e, "unit", "");
  signal.height = reader.number_or(e, "height", 0.0);
  signal.width = reader.number_or(e, "width", 0.0);
  signal.text = reader.text_or(e, "text", "");
  return signal;
}

void parse_signals(const XmlReader& reader, const XMLElement* e, Road& road) {
  for (const XMLElement* child : children(e)) {
    if (named(child, "signal")) {
      road.signals.push_back(parse_signal(reader, child));
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
}

}  // namespace corsa::xodr::detail
