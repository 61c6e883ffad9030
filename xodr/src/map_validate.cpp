// Map::build's checks: ids, references, record order, lengths and planView joints. Errors are
// located at the element of the offending record (its source line when it came from a file).

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <string_view>

#include "corsa/core/strings.h"
#include "map_impl.h"
#include "road_eval.h"

namespace corsa::xodr::detail {
namespace {

class Checker {
 public:
  Checker(const MapData& data, corsa::Diagnostics& diagnostics)
      : file_(data.source_file), diagnostics_(diagnostics) {}

  [[noreturn]] void fail(int line, const std::string& message) const {
    // Clipped: ids quoted in a message come from the file and may be megabytes long.
    throw corsa::InputError(corsa::make_error(file_, line, corsa::clip(message, 1024)));
  }
  void warn(const std::string& key, int line, const std::string& message) const {
    diagnostics_.add_once(key, corsa::make_warning(file_, line, corsa::clip(message, 1024)));
  }

 private:
  std::string file_;
  corsa::Diagnostics& diagnostics_;
};

/// Real files sometimes list records out of s order (e.g. ASAM's Ex_Slip_Lane elevation);
/// the standard requires ascending s, so they are put in order (stable) with a warning.
template <typename T, typename StartOf>
void sort_records(const Checker& check, const Road& road, std::vector<T>& records, StartOf start_of,
                  const char* what) {
  const auto before = [&](const T& a, const T& b) { return start_of(a) < start_of(b); };
  if (!std::is_sorted(records.begin(), records.end(), before)) {
    check.warn(std::string("order:") + what, road.line,
               std::string(what) + " records of road '" + road.id +
                   "' are not in ascending s order; sorted (further roads not reported)");
    std::stable_sort(records.begin(), records.end(), before);
  }
}

double wrap_angle(double angle) { return std::remainder(angle, 2.0 * std::numbers::pi); }

void check_plan_view(const Checker& check, const Road& road, const BuildOptions& options) {
  double total = 0.0;
  for (size_t i = 0; i < road.plan_view.size(); ++i) {
    const Geometry& g = road.plan_view[i];
    total += g.length;
    if (i + 1 == road.plan_view.size()) {
      break;
    }
    const Geometry& next = road.plan_view[i + 1];
    const RefPoint end = evaluate_geometry(g, g.length);
    const double gap = std::hypot(end.x - next.x, end.y - next.y);
    const double turn = std::abs(wrap_angle(end.hdg - next.hdg));
    if (gap > options.max_joint_gap || turn > options.max_joint_heading) {
      check.warn("joint:" + road.id, next.line,
                 "road '" + road.id + "': planView records do not join at s=" +
                     corsa::format_fixed(next.s, 3) + " (gap " + corsa::format_fixed(gap, 4) +
                     " m, heading jump " + corsa::format_fixed(turn, 4) + " rad)");
    }
    if (std::abs(g.s + g.length - next.s) > 1e-3) {
      check.warn("geometry s:" + road.id, next.line,
                 "road '" + road.id + "': geometry at s=" + corsa::format_fixed(next.s, 3) +
                     " does not start where the previous one ends (s=" +
                     corsa::format_fixed(g.s + g.length, 3) + ")");
    }
  }
  if (std::abs(total - road.length) > 0.01) {
    check.warn("length", road.line,
               "road '" + road.id + "': length " + corsa::format_double(road.length) +
                   " differs from the sum of its geometry lengths " + corsa::format_double(total) +
                   " (further roads not reported)");
  }
}

void sort_road_records(const Checker& check, Road& road) {
  const auto by_s = [](const Poly3& p) { return p.s; };
  sort_records(
      check, road, road.plan_view, [](const Geometry& g) { return g.s; }, "planView");
  sort_records(
      check, road, road.lane_sections, [](const LaneSection& x) { return x.s; }, "laneSection");
  sort_records(check, road, road.elevation, by_s, "elevation");
  sort_records(check, road, road.superelevation, by_s, "superelevation");
  sort_records(check, road, road.lane_offsets, by_s, "laneOffset");
  sort_records(
      check, road, road.types, [](const RoadType& t) { return t.s; }, "type");
  for (LaneSection& section : road.lane_sections) {
    for (Lane& lane : section.lanes) {
      sort_records(check, road, lane.widths, by_s, "lane width");
      sort_records(check, road, lane.borders, by_s, "lane border");
      sort_records(
          check, road, lane.road_marks, [](const RoadMark& m) { return m.s_offset; }, "roadMark");
      sort_records(
          check, road, lane.speeds, [](const LaneSpeed& m) { return m.s_offset; }, "lane speed");
      sort_records(
          check, road, lane.heights, [](const LaneHeight& m) { return m.s_offset; }, "lane height");
    }
  }
}

/// Longest road Corsa accepts (m). The standard sets no upper bound, but every map structure is
/// linear in road length (spatial index chunks of <= 5 m, mesh strips, lane spans): 1e7 m and more
/// is a typo or a fuzzed file, and would otherwise run for minutes or exhaust memory.
constexpr double kMaxRoadLength = 1e6;

/// Largest heading change of one arc or spiral record (rad). The standard sets no bound, but
/// evaluating a clothoid costs time in proportion to how much it turns (and everything sampled
/// along it is linear in that): curvatures like 1e20 1/m are fuzzed or corrupt files.
constexpr double kMaxRecordTurn = 2000.0;

/// ∫|curvature| ds over the record: exact for arcs and for spirals that keep their sign, an upper
/// bound otherwise. NaN for non-finite curvatures, so the check rejects them too.
double record_turn(const Geometry& g) {
  if (const auto* arc = std::get_if<ArcGeometry>(&g.shape)) {
    return std::abs(arc->curvature) * g.length;
  }
  if (const auto* spiral = std::get_if<SpiralGeometry>(&g.shape)) {
    return 0.5 * (std::abs(spiral->curv_start) + std::abs(spiral->curv_end)) * g.length;
  }
  return 0.0;
}

const char* geometry_kind_name(const Geometry& g) {
  return std::holds_alternative<ArcGeometry>(g.shape) ? "arc" : "spiral";
}

void check_road_length(const Checker& check, const Road& road) {
  if (!(road.length <= kMaxRoadLength)) {
    check.fail(road.line, "road '" + road.id + "': length " + corsa::format_double(road.length) +
                              " m is beyond the " + corsa::format_double(kMaxRoadLength) +
                              " m a road may have");
  }
  // A planView record is evaluated at its end (joint checks below) whatever the road's length.
  for (const Geometry& g : road.plan_view) {
    if (!(g.length <= kMaxRoadLength)) {
      check.fail(g.line, "road '" + road.id + "': geometry length " +
                             corsa::format_double(g.length) + " m is beyond the " +
                             corsa::format_double(kMaxRoadLength) + " m a road may have");
    }
    const double turn = record_turn(g);
    if (!(turn <= kMaxRecordTurn)) {
      check.fail(g.line, "road '" + road.id + "': the " + std::string(geometry_kind_name(g)) +
                             " record turns " + corsa::format_double(turn) + " rad, beyond the " +
                             corsa::format_double(kMaxRecordTurn) +
                             " rad (about 300 full turns) a road may turn in one record");
    }
  }
}

/// How far below zero a lane width may dip before it is reported (m): a lane tapering to zero
/// may end a rounding error below it.
constexpr double kNegativeWidthTolerance = 1e-3;

// A width polynomial below zero at either end of its record: lane_spans.cpp takes it as 0 there
// (a lane has no negative width, OpenDRIVE 1.8 §9.5.2), which the file should not need.
void check_lane_widths(const Checker& check, const Road& road, const LaneSection& section,
                       double section_length) {
  for (const Lane& lane : section.lanes) {
    for (size_t i = 0; i < lane.widths.size(); ++i) {
      const Poly3& width = lane.widths[i];
      const double end = i + 1 < lane.widths.size() ? lane.widths[i + 1].s : section_length;
      const double lowest = std::min(width.a, width.value(std::max(end, width.s)));
      if (lowest < -kNegativeWidthTolerance) {
        check.warn(
            "negative width:" + std::to_string(lane.line) + ":" + std::to_string(i), lane.line,
            "road '" + road.id + "': lane " + std::to_string(lane.id) + " has a negative width (" +
                corsa::format_double(lowest) + " m in its width record at sOffset " +
                corsa::format_double(width.s) + "); taken as 0 m where it is negative");
      }
    }
  }
}

void check_lane_sections(const Checker& check, const Road& road) {
  for (size_t i = 0; i < road.lane_sections.size(); ++i) {
    const LaneSection& section = road.lane_sections[i];
    if (section.lanes.size() > kMaxLanesPerSection) {
      check.fail(section.line,
                 "more than " + std::to_string(kMaxLanesPerSection) + " lanes in one lane section");
    }
    if (section.s > road.length + 1e-6) {
      check.warn("section beyond:" + std::to_string(section.line), section.line,
                 "road '" + road.id + "': laneSection at s=" + corsa::format_double(section.s) +
                     " starts beyond the road's end (length " + corsa::format_double(road.length) +
                     " m); it covers nothing");
    }
    const double end =
        i + 1 < road.lane_sections.size() ? road.lane_sections[i + 1].s : road.length;
    check_lane_widths(check, road, section, std::max(0.0, end - section.s));
  }
  if (road.lane_sections.front().s > 1e-6) {
    check.warn("first section", road.lane_sections.front().line,
               "road '" + road.id + "': its first laneSection starts at s=" +
                   corsa::format_double(road.lane_sections.front().s) + ", not 0");
  }
}

// A road linked to itself closes a loop only from its end to its start (a ring road such as a
// velodrome) and only when its end meets its start; any other self-link leads nowhere.
void check_self_link(const Checker& check, const Road& road, const RoadLink& link,
                     const char* which, const BuildOptions& options) {
  if (link.element_type != LinkElement::kRoad || link.element_id != road.id) return;
  const bool successor = std::string_view(which) == "successor";
  const ContactPoint closing = successor ? ContactPoint::kStart : ContactPoint::kEnd;
  const std::string key = std::string("self link:") + which + ":" + std::to_string(road.line);
  if (link.contact_point != closing) {
    check.warn(key, road.line,
               "road '" + road.id + "' is its own " + which + " at its " +
                   (successor ? "end" : "start") + "; a road cannot continue into the same end");
    return;
  }
  const Geometry& first = road.plan_view.front();
  const Geometry& last = road.plan_view.back();
  const RefPoint end = evaluate_geometry(last, last.length);
  const double gap = std::hypot(end.x - first.x, end.y - first.y);
  if (gap > options.max_joint_gap) {
    check.warn(key, road.line,
               "road '" + road.id + "' is its own " + which + ", closing a loop, but its end is " +
                   corsa::format_fixed(gap, 3) + " m from its start");
  }
}

void check_road_link(const Checker& check, const IdIndex& impl, const Road& road,
                     const RoadLink& link, const char* which) {
  if (link.element_type == LinkElement::kRoad && !impl.road_by_id.contains(link.element_id)) {
    check.fail(road.line, "road '" + road.id + "': " + which + " road '" + link.element_id +
                              "' does not exist");
  }
  if (link.element_type == LinkElement::kJunction &&
      !impl.junction_by_id.contains(link.element_id)) {
    check.fail(road.line, "road '" + road.id + "': " + which + " junction '" + link.element_id +
                              "' does not exist");
  }
}

void check_junction(const Checker& check, const IdIndex& impl, const Junction& junction) {
  for (const Connection& c : junction.connections) {
    for (const std::string* id : {&c.incoming_road, &c.connecting_road, &c.linked_road}) {
      if (!id->empty() && !impl.road_by_id.contains(*id)) {
        check.fail(c.line, "junction '" + junction.id + "': connection refers to road '" + *id +
                               "', which does not exist");
      }
    }
  }
  for (const JunctionBoundarySegment& segment : junction.boundary) {
    if (!impl.road_by_id.contains(segment.road_id)) {
      check.fail(segment.line, "junction '" + junction.id + "': boundary segment refers to road '" +
                                   segment.road_id + "', which does not exist");
    }
  }
}

}  // namespace

void sort_map_records(MapData& data, corsa::Diagnostics& diagnostics) {
  const Checker check(data, diagnostics);
  for (Road& road : data.roads) {
    sort_road_records(check, road);
  }
}

void validate_map(const MapData& data, IdIndex& impl, corsa::Diagnostics& diagnostics,
                  const BuildOptions& options) {
  const Checker check(data, diagnostics);
  for (size_t i = 0; i < data.roads.size(); ++i) {
    if (!impl.road_by_id.emplace(data.roads[i].id, i).second) {
      check.fail(data.roads[i].line, "road id '" + data.roads[i].id + "' is used twice");
    }
  }
  for (size_t i = 0; i < data.junctions.size(); ++i) {
    if (!impl.junction_by_id.emplace(data.junctions[i].id, i).second) {
      check.fail(data.junctions[i].line,
                 "junction id '" + data.junctions[i].id + "' is used twice");
    }
  }
  for (const Road& road : data.roads) {
    if (road.plan_view.empty() || road.lane_sections.empty()) {
      check.fail(road.line, "road '" + road.id + "' needs planView geometry and a laneSection");
    }
    if (road.in_junction() && !impl.junction_by_id.contains(road.junction)) {
      check.fail(road.line, "road '" + road.id + "' belongs to junction '" + road.junction +
                                "', which does not exist");
    }
    check_road_link(check, impl, road, road.predecessor, "predecessor");
    check_road_link(check, impl, road, road.successor, "successor");
    check_road_length(check, road);
    check_self_link(check, road, road.predecessor, "predecessor", options);
    check_self_link(check, road, road.successor, "successor", options);
    if (road.length <= 0.0) {
      check.warn("zero length:" + std::to_string(road.line), road.line,
                 "road '" + road.id +
                     "' has length 0, which OpenDRIVE does not allow (its "
                     "schema type t_grZero is greater than zero); the road covers nothing");
    }
    check_plan_view(check, road, options);
    check_lane_sections(check, road);
  }
  for (const Junction& junction : data.junctions) {
    check_junction(check, impl, junction);
  }
}

}  // namespace corsa::xodr::detail
