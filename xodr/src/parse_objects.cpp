// <objects>/<object>, <tunnel>, <bridge> and <signals>/<signal>: kept with their road positions
// (OpenDRIVE 1.8 §13, §14), objects with their outlines, repeats and markings, signals with their
// lane validities. The rest of their sub-structure (object validity, materials, ...) is read past.

#include <optional>

#include "corsa/core/strings.h"
#include "parse_elements.h"

namespace corsa::xodr::detail {

namespace {

Outline parse_outline(const XmlReader& reader, const XMLElement* e) {
  Outline outline;
  outline.id = static_cast<int>(reader.number_or(e, "id", 0.0));
  outline.closed = reader.text_or(e, "closed", "true") != "false";
  outline.fill_type = reader.text_or(e, "fillType", "");
  bool road = false;
  bool local = false;
  for (const XMLElement* child : children(e)) {
    if (named(child, "cornerRoad")) {
      road = true;
      outline.corners.push_back(
          OutlineCorner{true, reader.number(child, "s"), reader.number(child, "t"),
                        reader.number_or(child, "dz", 0.0), reader.number_or(child, "height", 0.0),
                        static_cast<int>(reader.number_or(child, "id", 0.0))});
    } else if (named(child, "cornerLocal")) {
      local = true;
      outline.corners.push_back(
          OutlineCorner{false, reader.number(child, "u"), reader.number(child, "v"),
                        reader.number_or(child, "z", 0.0), reader.number_or(child, "height", 0.0),
                        static_cast<int>(reader.number_or(child, "id", 0.0))});
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
  if (road && local) {
    reader.fail(e, "an outline mixes cornerRoad and cornerLocal (§13.2: one kind per outline)");
  }
  return outline;
}

/// <repeat> (§13.4); the attributes left out take the object's own values.
ObjectRepeat parse_repeat(const XmlReader& reader, const XMLElement* e, const Object& object) {
  ObjectRepeat r;
  r.s = reader.number(e, "s");
  r.length = reader.number(e, "length");
  r.distance = reader.number_or(e, "distance", 0.0);
  r.t_start = reader.number_or(e, "tStart", object.t);
  r.t_end = reader.number_or(e, "tEnd", r.t_start);
  r.height_start = reader.number_or(e, "heightStart", object.height);
  r.height_end = reader.number_or(e, "heightEnd", r.height_start);
  r.z_offset_start = reader.number_or(e, "zOffsetStart", object.z_offset);
  r.z_offset_end = reader.number_or(e, "zOffsetEnd", r.z_offset_start);
  if (e->attribute("widthStart") != nullptr) {
    r.width_start = reader.number(e, "widthStart");
    r.width_end = reader.number_or(e, "widthEnd", *r.width_start);
  }
  if (e->attribute("lengthStart") != nullptr) {
    r.length_start = reader.number(e, "lengthStart");
    r.length_end = reader.number_or(e, "lengthEnd", *r.length_start);
  }
  return r;
}

ObjectMarking parse_marking(const XmlReader& reader, const XMLElement* e) {
  ObjectMarking marking;
  marking.color = reader.text_or(e, "color", "white");
  marking.width = reader.non_negative_or(e, "width", marking.width);
  marking.z_offset = reader.non_negative_or(e, "zOffset", 0.0);
  marking.space_length = reader.non_negative_or(e, "spaceLength", 0.0);
  marking.line_length = reader.non_negative_or(e, "lineLength", 0.0);
  for (const XMLElement* child : children(e)) {
    if (named(child, "cornerReference")) {
      marking.corner_references.push_back(reader.integer(child, "id"));
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
  return marking;
}

// The first <repeat> of an object that gives s, or null.
const XMLElement* first_repeat_with_s(const XMLElement* object) {
  for (const XMLElement* child : children(object)) {
    if (named(child, "repeat") && child->attribute("s") != nullptr) return child;
  }
  return nullptr;
}

// s and t are required of every <object> (1.4 to 1.8). esmini's crest-curve.xodr has a barrier
// written only by its <repeat> (s 200, length 55, t 15 to 40): a repeat's attributes overrule
// the object's (1.8 §13.4, "Attributes of the repeated object shall overrule the attributes from
// the original object"), so the object's own s and t say nothing it does not, and its first
// repeat's s and tStart are read for them. An object without s (or t) and no repeat to give it
// has no place on its road: it is left out. Returns false when the object is left out.
bool place_object_by_repeat(const XmlReader& reader, const XMLElement* e, Object& object) {
  const bool has_s = e->attribute("s") != nullptr;
  const bool has_t = e->attribute("t") != nullptr;
  if (has_s && has_t) {
    object.s = reader.number(e, "s");
    object.t = reader.number(e, "t");
    return true;
  }
  const std::string missing = !has_s && !has_t ? "s and t" : !has_s ? "s" : "t";
  const std::string what = "<object> '" + corsa::clip(object.id) + "' without " + missing;
  const XMLElement* repeat = first_repeat_with_s(e);
  if (repeat == nullptr || (!has_t && repeat->attribute("tStart") == nullptr)) {
    reader.lenient(e, what, "no object: nothing places it on its road");
    return false;
  }
  object.s = has_s ? reader.number(e, "s") : reader.number(repeat, "s");
  object.t = has_t ? reader.number(e, "t") : reader.number(repeat, "tStart");
  reader.lenient(e, what,
                 "s " + corsa::format_double(object.s) + ", t " + corsa::format_double(object.t) +
                     ": its <repeat>'s start, whose attributes overrule the object's");
  return true;
}

}  // namespace

void add_user_data(const XmlReader& reader, const XMLElement* e, std::vector<UserData>& out) {
  std::string code = reader.text_or(e, "code", "");
  if (!code.empty()) {
    out.push_back(UserData{std::move(code), reader.text_or(e, "value", "")});
  }
}

std::optional<Object> parse_object(const XmlReader& reader, const XMLElement* e) {
  Object object;
  object.line = e->line();
  object.id = reader.text(e, "id");
  object.name = reader.text_or(e, "name", "");
  object.type = reader.text_or(e, "type", "none");
  if (!place_object_by_repeat(reader, e, object)) {
    return std::nullopt;
  }
  object.z_offset = reader.number_or(e, "zOffset", 0.0);
  object.hdg = reader.number_or(e, "hdg", 0.0);
  object.pitch = reader.number_or(e, "pitch", 0.0);
  object.roll = reader.number_or(e, "roll", 0.0);
  object.length = reader.number_or(e, "length", 0.0);
  object.width = reader.number_or(e, "width", 0.0);
  object.height = reader.number_or(e, "height", 0.0);
  object.radius = reader.number_or(e, "radius", 0.0);
  object.orientation = reader.text_or(e, "orientation", "none");
  object.subtype = reader.text_or(e, "subtype", "");
  for (const XMLElement* child : children(e)) {
    if (named(child, "outline")) {
      object.outlines.push_back(parse_outline(reader, child));
    } else if (named(child, "outlines")) {
      for (const XMLElement* outline : children(child)) {
        if (named(outline, "outline")) {
          object.outlines.push_back(parse_outline(reader, outline));
        } else if (!is_ignored_element(outline->name())) {
          reader.unknown_child(child, outline);
        }
      }
    } else if (named(child, "repeat")) {
      object.repeats.push_back(parse_repeat(reader, child, object));
    } else if (named(child, "markings")) {
      for (const XMLElement* marking : children(child)) {
        if (named(marking, "marking")) {
          object.markings.push_back(parse_marking(reader, marking));
        } else if (!is_ignored_element(marking->name())) {
          reader.unknown_child(child, marking);
        }
      }
    } else if (named(child, "userData")) {
      add_user_data(reader, child, object.user_data);
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
  return object;
}

void parse_objects(const XmlReader& reader, const XMLElement* e, Road& road) {
  for (const XMLElement* child : children(e)) {
    if (named(child, "object")) {
      if (std::optional<Object> object = parse_object(reader, child)) {
        road.objects.push_back(std::move(*object));
      }
    } else if (named(child, "tunnel")) {
      road.tunnels.push_back(Tunnel{
          reader.text(child, "id"), reader.text_or(child, "name", ""),
          reader.non_negative(child, "s"), reader.non_negative(child, "length"),
          reader.text_or(child, "type", "standard"), reader.number_or(child, "lighting", 0.0),
          reader.number_or(child, "daylight", 0.0)});
    } else if (named(child, "bridge")) {
      road.bridges.push_back(Bridge{reader.text(child, "id"), reader.text_or(child, "name", ""),
                                    reader.non_negative(child, "s"),
                                    reader.non_negative(child, "length"),
                                    reader.text_or(child, "type", "concrete")});
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
  signal.length = reader.number_or(e, "length", 0.0);
  signal.text = reader.text_or(e, "text", "");
  for (const XMLElement* child : children(e)) {
    if (named(child, "validity")) {
      signal.validities.push_back(
          LaneValidity{reader.integer(child, "fromLane"), reader.integer(child, "toLane")});
    } else if (named(child, "userData")) {
      add_user_data(reader, child, signal.user_data);
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
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
