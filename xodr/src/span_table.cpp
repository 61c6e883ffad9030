#include "span_table.h"

#include <algorithm>
#include <cmath>

#include "pose_table.h"
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

// Bound on |ds| and on a record's sOffset under which ds - sOffset is finite (the pose table's
// bound for zero offsets): then a record of b = c = d = 0 gives a + (+-0), whose max with 0 is
// max(0, a) to the bit (a + +-0 is a for a != 0, and max(0, +-0) is +0).
constexpr double kConstantBound = PoseTable::kZeroBound;

// Width records all of b = c = d = 0, in s order (record_index then picks the last one starting
// at or before ds, the first before them all).
bool constant_width(const Lane& lane) {
  const std::vector<Poly3>& widths = lane.widths;
  for (size_t i = 0; i < widths.size(); ++i) {
    const Poly3& width = widths[i];
    if (width.b != 0.0 || width.c != 0.0 || width.d != 0.0 ||
        !(std::abs(width.s) <= kConstantBound) || (i > 0 && !(widths[i - 1].s <= width.s))) {
      return false;
    }
  }
  return !widths.empty();
}

// Whether every lane but the centre one has a constant width and the ids run 1, 2, ... leftward
// and -1, -2, ... rightward from the centre (so a lane's index follows from its id).
bool constant_widths(const LaneSection& section, size_t center, bool has_center) {
  const std::vector<Lane>& lanes = section.lanes;
  for (size_t i = 0; i < center; ++i) {
    if (lanes[i].id != static_cast<int>(center - i) || !constant_width(lanes[i])) {
      return false;
    }
  }
  const size_t right = center + (has_center ? 1 : 0);
  for (size_t i = right; i < lanes.size(); ++i) {
    if (lanes[i].id != -static_cast<int>(i - right + 1) || !constant_width(lanes[i])) {
      return false;
    }
  }
  return true;
}

// SpanTable::span on a section with constant_widths: the same additions in the same order, each
// lane's max(0, width) read from `widths` (indexed as the section's lanes).
bool constant_span(const double* widths, const SpanSection& packed, double offset, int lane_id,
                   LaneSpan& out) {
  const size_t center = packed.center;
  if (lane_id > 0) {
    const auto k = static_cast<size_t>(lane_id);
    if (k > center) {
      return false;  // not on the left; the right has negative ids only
    }
    double t = offset;
    for (size_t i = center - 1;; --i) {
      const double outer = t + widths[i];
      if (i == center - k) {
        out = LaneSpan{lane_id, t, outer};
        return true;
      }
      t = outer;
    }
  }
  const size_t right = center + (packed.has_center ? 1 : 0);
  const auto k = static_cast<size_t>(-static_cast<int64_t>(lane_id));
  if (k == 0 || k > packed.count - right) {
    return false;
  }
  double t = offset;
  for (size_t i = right;; ++i) {
    const double outer = t - widths[i];
    if (i == right + k - 1) {
      out = LaneSpan{lane_id, t, outer};
      return true;
    }
    t = outer;
  }
}

}  // namespace

void SpanTable::build(const std::vector<Road>& roads) {
  lanes_.clear();
  widths_.clear();
  breaks_.clear();
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
      packed.constant_widths = constant_widths(section, packed.center, packed.has_center);
      for (const Lane& lane : section.lanes) {
        lanes_.push_back(pack_span_lane(lane));
        packed.widths_only = packed.widths_only && !(lane.widths.empty() && !lane.borders.empty());
      }
      if (packed.constant_widths) {
        pack_width_rows(section, packed);
      }
      sections_.push_back(packed);
    }
  }
}

void SpanTable::pack_width_rows(const LaneSection& section, SpanSection& packed) {
  // Every record start is where a stretch may begin; row k holds what offset_poly_value picks
  // for ds with k starts at or before it (record_index at the k-th start, the first record for
  // none). Rows equal to the one before are merged with it.
  std::vector<double> starts;
  for (const Lane& lane : section.lanes) {
    for (const Poly3& width : lane.widths) {
      starts.push_back(width.s);
    }
  }
  std::sort(starts.begin(), starts.end());
  starts.erase(std::unique(starts.begin(), starts.end()), starts.end());
  const auto row_at = [&](bool before_all, double ds) {
    std::vector<double> row(section.lanes.size(), 0.0);
    for (size_t i = 0; i < section.lanes.size(); ++i) {
      const std::vector<Poly3>& widths = section.lanes[i].widths;
      if (section.lanes[i].id != 0 && !widths.empty()) {
        const size_t k =
            before_all ? 0 : record_index(widths, ds, [](const Poly3& p) { return p.s; });
        row[i] = std::max(0.0, widths[k].a);
      }
    }
    return row;
  };
  packed.break_first = static_cast<uint32_t>(breaks_.size());
  packed.width_first = static_cast<uint32_t>(widths_.size());
  std::vector<double> last = row_at(true, 0.0);
  widths_.insert(widths_.end(), last.begin(), last.end());
  for (const double start : starts) {
    std::vector<double> row = row_at(false, start);
    if (row != last) {
      breaks_.push_back(start);
      widths_.insert(widths_.end(), row.begin(), row.end());
      last = std::move(row);
    }
  }
  packed.break_count = static_cast<uint32_t>(breaks_.size()) - packed.break_first;
}

[[gnu::hot]] bool SpanTable::span(size_t road, size_t section, double s, double offset, int lane_id,
                                  LaneSpan& out) const {
  const SpanSection& packed = sections_[road_first_[road] + section];
  const SpanLane* lanes = lanes_.data() + packed.first;
  const double ds = s - packed.s;
  if (packed.constant_widths && std::abs(ds) <= kConstantBound) {
    const double* breaks = breaks_.data() + packed.break_first;
    const auto row =
        static_cast<size_t>(std::upper_bound(breaks, breaks + packed.break_count, ds) - breaks);
    return constant_span(widths_.data() + packed.width_first + row * packed.count, packed, offset,
                         lane_id, out);
  }
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
