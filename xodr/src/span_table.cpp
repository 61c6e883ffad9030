#include "span_table.h"

#include <algorithm>

#include "road_eval.h"

namespace corsa::xodr::detail {
namespace {

SpanLane pack_span_lane(const Lane& lane) {
  SpanLane packed;
  packed.id = lane.id;
  // The same choice as compute_span's: widths win over borders (OpenDRIVE 1.8 §9.5.2).
  const std::vector<Poly3>& records = !lane.widths.empty() ? lane.widths : lane.borders;
  if (records.empty()) {
    packed.rule = SpanRule::kNone;
  } else if (records.size() == 1) {
    packed.rule = !lane.widths.empty() ? SpanRule::kWidth : SpanRule::kBorder;
    packed.poly = records.front();
  } else {
    packed.rule = SpanRule::kRecords;
    packed.lane = &lane;
  }
  return packed;
}

// compute_span's outer_border, on a packed lane: the same operations in the same order.
double packed_outer_border(const SpanLane& lane, double ds, double inner, double side) {
  switch (lane.rule) {
    case SpanRule::kWidth:
      return inner + side * std::max(0.0, lane.poly.value(ds));
    case SpanRule::kBorder:
      return lane.poly.value(ds);
    case SpanRule::kNone:
      return inner;
    case SpanRule::kRecords:
      break;
  }
  const Lane& whole = *lane.lane;
  if (!whole.widths.empty()) {
    return inner + side * std::max(0.0, offset_poly_value(whole.widths, ds));
  }
  return offset_poly_value(whole.borders, ds);
}

}  // namespace

void SpanTable::build(const std::vector<Road>& roads) {
  lanes_.clear();
  sections_.clear();
  road_first_.clear();
  for (const Road& road : roads) {
    road_first_.push_back(static_cast<uint32_t>(sections_.size()));
    for (size_t i = 0; i < road.lane_sections.size(); ++i) {
      const LaneSection& section = road.lane_sections[i];
      SpanSection packed;
      packed.s = section.s;
      packed.end = i + 1 < road.lane_sections.size() ? road.lane_sections[i + 1].s : road.length;
      packed.first = static_cast<uint32_t>(lanes_.size());
      packed.count = static_cast<uint32_t>(section.lanes.size());
      packed.center = static_cast<uint32_t>(center_index(section));
      packed.has_center = packed.center < packed.count && section.lanes[packed.center].id == 0;
      for (const Lane& lane : section.lanes) {
        lanes_.push_back(pack_span_lane(lane));
        packed.widths_only = packed.widths_only && !(lane.widths.empty() && !lane.borders.empty());
      }
      sections_.push_back(packed);
    }
  }
}

bool SpanTable::span(size_t road, size_t section, double s, double offset, int lane_id,
                     LaneSpan& out) const {
  const SpanSection& packed = sections_[road_first_[road] + section];
  const SpanLane* lanes = lanes_.data() + packed.first;
  const double ds = s - packed.s;
  const size_t n = packed.count;
  const size_t center = packed.center;
  // As compute_span: a positive id on the left first, then every id on the right.
  if (lane_id > 0) {
    double t = offset;
    for (size_t i = center; i-- > 0;) {
      const double outer = packed_outer_border(lanes[i], ds, t, 1.0);
      if (lanes[i].id == lane_id) {
        out = LaneSpan{lanes[i].id, t, outer};
        return true;
      }
      t = outer;
    }
  }
  double t = offset;
  for (size_t i = center + (packed.has_center ? 1 : 0); i < n; ++i) {
    const double outer = packed_outer_border(lanes[i], ds, t, -1.0);
    if (lanes[i].id == lane_id) {
      out = LaneSpan{lanes[i].id, t, outer};
      return true;
    }
    t = outer;
  }
  return false;
}

}  // namespace corsa::xodr::detail
