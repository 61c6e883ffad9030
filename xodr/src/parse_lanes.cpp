// <lanes>: laneOffset and laneSection/left|center|right/lane with link, width, border, roadMark,
// speed (OpenDRIVE 1.8 §9).

#include <algorithm>

#include "corsa/core/strings.h"
#include "corsa/xodr/parser.h"
#include "parse_elements.h"

namespace corsa::xodr::detail {

Poly3 parse_width_record(const XmlReader& reader, const XMLElement* e) {
  return Poly3{reader.non_negative(e, "sOffset"), reader.number(e, "a"), reader.number(e, "b"),
               reader.number(e, "c"), reader.number(e, "d")};
}

RoadMark parse_road_mark(const XmlReader& reader, const XMLElement* e) {
  RoadMark mark;
  mark.s_offset = reader.non_negative(e, "sOffset");
  mark.type = reader.text_or(e, "type", "none");
  mark.weight = reader.text_or(e, "weight", "standard");
  mark.color = reader.text_or(e, "color", "standard");
  mark.lane_change = reader.text_or(e, "laneChange", "both");
  mark.width = reader.non_negative_or(e, "width", mark.width);
  mark.height = reader.number_or(e, "height", 0.0);
  return mark;
}

LaneSpeed parse_lane_speed(const XmlReader& reader, const XMLElement* e) {
  LaneSpeed speed;
  speed.s_offset = reader.non_negative(e, "sOffset");
  const double max = reader.non_negative(e, "max");
  speed.max_speed = speed_in_mps(reader, e, max, reader.text_or(e, "unit", ""));
  return speed;
}

namespace {

void parse_lane_link(const XmlReader& reader, const XMLElement* e, Lane& lane) {
  for (const XMLElement* child : children(e)) {
    if (named(child, "predecessor")) {
      lane.predecessors.push_back(reader.integer(child, "id"));
    } else if (named(child, "successor")) {
      lane.successors.push_back(reader.integer(child, "id"));
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
}

bool parse_bool(const XmlReader& reader, const XMLElement* e, const char* name) {
  const std::string value = reader.text_or(e, name, "false");
  if (value == "true" || value == "1") {
    return true;
  }
  if (value == "false" || value == "0") {
    return false;
  }
  reader.fail(e, std::string("attribute '") + name + "' must be true or false, not '" +
                     corsa::clip(value) + "'");
}

}  // namespace

Lane parse_lane(const XmlReader& reader, const XMLElement* e, bool center) {
  Lane lane;
  lane.line = e->line();
  lane.id = reader.integer(e, "id");
  lane.type_name = reader.text_or(e, "type", "none");
  lane.type = lane_type_from_name(lane.type_name);
  if (lane.type == LaneType::kOther) {
    reader.warn_once("lane type " + lane.type_name, e,
                     "unknown lane type '" + corsa::clip(lane.type_name) + "' (kept as 'other')");
  }
  lane.level = parse_bool(reader, e, "level");
  for (const XMLElement* child : children(e)) {
    const std::string_view name = child->name();
    if (name == "link") {
      parse_lane_link(reader, child, lane);
    } else if (name == "width") {
      lane.widths.push_back(parse_width_record(reader, child));
    } else if (name == "border") {
      lane.borders.push_back(parse_width_record(reader, child));
    } else if (name == "roadMark") {
      lane.road_marks.push_back(parse_road_mark(reader, child));
    } else if (name == "speed") {
      lane.speeds.push_back(parse_lane_speed(reader, child));
    } else if (name == "height") {
      // §9.5.7 lane height (e.g. raised sidewalks).
      lane.heights.push_back(LaneHeight{reader.non_negative(child, "sOffset"),
                                        reader.number_or(child, "inner", 0.0),
                                        reader.number_or(child, "outer", 0.0)});
    } else if (name == "userData") {
      add_user_data(reader, child, lane.user_data);
    } else if (!is_ignored_element(name)) {
      reader.unknown_child(e, child);
    }
  }
  if (center && (!lane.widths.empty() || !lane.borders.empty())) {
    reader.warn_once("center width", e, "the centre lane has no width (§9.5.1); widths ignored");
    lane.widths.clear();
    lane.borders.clear();
  }
  return lane;
}

LaneSection parse_lane_section(const XmlReader& reader, const XMLElement* e) {
  LaneSection section;
  section.line = e->line();
  section.s = reader.non_negative(e, "s");
  section.single_side = reader.text_or(e, "singleSide", "false") == "true";
  bool have_center = false;
  for (const XMLElement* group : children(e)) {
    const std::string_view name = group->name();
    const int side = name == "left" ? 1 : name == "right" ? -1 : name == "center" ? 0 : 2;
    if (side == 2) {
      if (!is_ignored_element(name)) {
        reader.unknown_child(e, group);
      }
      continue;
    }
    for (const XMLElement* child : children(group)) {
      if (!named(child, "lane")) {
        if (!is_ignored_element(child->name())) {
          reader.unknown_child(group, child);
        }
        continue;
      }
      Lane lane = parse_lane(reader, child, side == 0);
      const bool side_ok = side == 0 ? lane.id == 0 : side > 0 ? lane.id > 0 : lane.id < 0;
      if (!side_ok) {
        reader.fail(child, "lane id " + std::to_string(lane.id) + " does not belong in <" +
                               std::string(name) + ">");
      }
      have_center = have_center || side == 0;
      for (const Lane& other : section.lanes) {
        if (other.id == lane.id) {
          reader.fail(child, "lane id " + std::to_string(lane.id) + " appears twice");
        }
      }
      section.lanes.push_back(std::move(lane));
    }
  }
  if (!have_center) {
    reader.warn_once("no center lane", e, "lane section without a centre lane; one is assumed");
    Lane center;
    center.line = section.line;
    center.type_name = "none";
    section.lanes.push_back(center);
  }
  std::sort(section.lanes.begin(), section.lanes.end(),
            [](const Lane& a, const Lane& b) { return a.id > b.id; });
  return section;
}

void parse_lanes(const XmlReader& reader, const XMLElement* e, Road& road) {
  for (const XMLElement* child : children(e)) {
    if (named(child, "laneSection")) {
      road.lane_sections.push_back(parse_lane_section(reader, child));
    } else if (named(child, "laneOffset")) {
      road.lane_offsets.push_back(parse_poly3_record(reader, child));
    } else if (!is_ignored_element(child->name())) {
      reader.unknown_child(e, child);
    }
  }
}

}  // namespace corsa::xodr::detail
