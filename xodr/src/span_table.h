#pragma once

// The lanes of every lane section as a lane's span reads them (Map::lane_span_in_section),
// packed one after the other: a lane's id and, for the usual lane of one width (or border)
// record, that record. A span walks the lanes from the centre out to the one asked for; read
// from the sections' Lane records it touched each lane's record (about 250 bytes, with its
// names, links and marks) and the heap block of its widths, and with hundreds of vehicles on a
// large map those reads were cache misses on every move. Sections whose lanes' widths are all
// constant (b = c = d = 0, one record or several along the section: CARLA's maps, most generated
// ones) also keep those widths, max(0, a), in rows of doubles, a row per stretch of the section
// over which no lane's width record changes: a span there finds its row among the stretches'
// starts and reads a line of doubles instead of a 56-byte record per lane from the centre out.

#include <cstdint>
#include <vector>

#include "corsa/xodr/map.h"
#include "corsa/xodr/model.h"

namespace corsa::xodr::detail {

/// How a packed lane's outer border follows from its inner one.
enum class SpanRule : uint8_t {
  kWidth,    ///< inner + side x max(0, poly) (one width record)
  kBorder,   ///< poly (no width, one border record)
  kNone,     ///< the inner border (neither)
  kRecords,  ///< the lane's own records (more than one): read from `lane`
};

struct SpanLane {
  int id = 0;
  SpanRule rule = SpanRule::kNone;
  Poly3 poly;                  ///< with kWidth and kBorder
  const Lane* lane = nullptr;  ///< with kRecords
};

struct SpanSection {
  double s = 0.0;      ///< m, the section's start (LaneSection::s)
  double end = 0.0;    ///< m, its end (Map::section_end: the next section's s, else the length)
  uint32_t first = 0;  ///< its first lane in SpanTable::lanes
  uint32_t count = 0;
  uint32_t center = 0;  ///< center_index of the section
  bool has_center = false;
  bool widths_only = true;  ///< every lane's outer border from widths (none from borders alone)
  /// Every lane's width records (one or more, in s order) with b = c = d = 0, and the lanes' ids
  /// 1, 2, ... and -1, -2, ... outward from the centre: the widths are kept in rows (below).
  bool constant_widths = false;
  /// With constant_widths: the starts (ds from the section's s) of the stretches after the
  /// first, from `break_first` in SpanTable::breaks_; row k (k = the number of starts <= ds) of
  /// `count` doubles from `width_first` in SpanTable::widths_ holds each lane's max(0, a), at its
  /// lane's index in the section.
  uint32_t break_first = 0;
  uint32_t break_count = 0;
  uint32_t width_first = 0;
};

class SpanTable {
 public:
  /// Packs the lane sections of `roads`, which must outlive the table unchanged (a Map's data).
  void build(const std::vector<Road>& roads);
  /// What compute_span(road's section, s, offset, lane_id, out) gives, to the bit.
  bool span(size_t road, size_t section, double s, double offset, int lane_id, LaneSpan& out) const;
  const SpanSection& section(size_t road, size_t section) const {
    return sections_[road_first_[road] + section];
  }
  /// Map::section_widths_only, read from the packed section.
  bool widths_only(size_t road, size_t section) const {
    return sections_[road_first_[road] + section].widths_only;
  }

 private:
  /// The rows of widths of a section with constant_widths (SpanSection::break_first ...).
  void pack_width_rows(const LaneSection& section, SpanSection& packed);

  std::vector<SpanLane> lanes_;
  /// The rows of widths of the sections with constant_widths (SpanSection::width_first).
  std::vector<double> widths_;
  std::vector<double> breaks_;  ///< their stretches' starts (SpanSection::break_first)
  std::vector<SpanSection> sections_;
  std::vector<uint32_t> road_first_;  ///< by road: its first section in sections_
};

}  // namespace corsa::xodr::detail
