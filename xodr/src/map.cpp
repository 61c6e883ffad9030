// Map: construction, lookups and the road-level evaluation (reference line, profiles, poses).

#include "corsa/xodr/map.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <iterator>

#include "corsa/xodr/map_parts.h"
#include "corsa/xodr/parser.h"
#include "geometry_local.h"
#include "map_impl.h"
#include "road_eval.h"

namespace corsa::xodr {
namespace detail {

double section_lane_offset(const Map& map, size_t road, size_t section, double s) {
  return MapAccess::section_lane_offset(map, road, section, s);
}

[[gnu::hot]] double MapAccess::section_lane_offset(const Map& map, size_t road, size_t section,
                                                   double s) {
  const PoseTable& poses = map.impl_->poses;
  const PoseRoad& r = poses.road(road);
  if (r.zero_offsets && std::abs(s) <= PoseTable::kZeroBound) {
    return 0.0;  // what the records give (PoseRoad::zero_offsets), without reading them
  }
  const PolyRun records = poses.lane_offsets(r);
  const SpanSection& bounds = map.impl_->spans.section(road, section);
  if (records.count == 0 || s < bounds.end || s <= bounds.s) {
    return records.value(poses.clamp_s(r, s));
  }
  // Last record starting strictly before s.
  const double* it = std::lower_bound(records.starts, records.starts + records.count, s);
  return it == records.starts ? 0.0 : records.first[it - records.starts - 1].value(s);
}

const PoseTable& MapAccess::poses(const Map& map) { return map.impl_->poses; }

RefFrame MapAccess::reference_frame(const Map& map, size_t road_index, double s) {
  const PoseTable& poses = map.impl_->poses;
  const PoseRoad& r = poses.road(road_index);
  s = poses.clamp_s(r, s);
  const PoseGeometry& record = poses.geometry_at(r, s);
  const Geometry& geometry = record.geometry;
  const double cos_h = record.cos_h;
  const double sin_h = record.sin_h;
  const LocalFrame local = evaluate_local_frame(geometry, s - geometry.s);
  return RefFrame{to_world(geometry, cos_h, sin_h, local.point),
                  cos_h * local.cos_h - sin_h * local.sin_h,
                  sin_h * local.cos_h + cos_h * local.sin_h};
}

}  // namespace detail

Map::Map(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Map::Map(Map&&) noexcept = default;
Map& Map::operator=(Map&&) noexcept = default;
Map::~Map() = default;

Map Map::build(MapData data, corsa::Diagnostics& diagnostics, const BuildOptions& options) {
  auto impl = std::make_unique<Impl>();
  impl->data = std::move(data);
  detail::sort_map_records(impl->data, diagnostics);
  detail::validate_map(impl->data, impl->ids, diagnostics, options);
  impl->poses.build(impl->data.roads);
  impl->spans.build(impl->data.roads);
  Map map(std::move(impl));
  map.impl_->graph = detail::build_lane_graph(map, diagnostics);
  return map;
}

Map Map::load(const std::filesystem::path& path, corsa::Diagnostics& diagnostics,
              const BuildOptions& options) {
  return build(parse_xodr(path, diagnostics), diagnostics, options);
}

const MapData& Map::data() const { return impl_->data; }
size_t Map::road_count() const { return impl_->data.roads.size(); }
const Road& Map::road(size_t road) const { return impl_->data.roads[road]; }
size_t Map::junction_count() const { return impl_->data.junctions.size(); }
const Junction& Map::junction(size_t junction) const { return impl_->data.junctions[junction]; }
const LaneGraph& Map::lane_graph() const { return impl_->graph; }

std::optional<size_t> Map::find_road(std::string_view id) const {
  const auto it = impl_->ids.road_by_id.find(std::string(id));
  return it == impl_->ids.road_by_id.end() ? std::nullopt : std::optional<size_t>(it->second);
}

std::optional<size_t> Map::find_junction(std::string_view id) const {
  const auto it = impl_->ids.junction_by_id.find(std::string(id));
  return it == impl_->ids.junction_by_id.end() ? std::nullopt : std::optional<size_t>(it->second);
}

namespace {

double clamp_s(const Road& road, double s) {
  return s < 0.0 ? 0.0 : s > road.length ? road.length : s;
}

}  // namespace

[[gnu::hot]] RefPoint Map::reference(size_t road_index, double s) const {
  const detail::PoseTable& poses = impl_->poses;
  const detail::PoseRoad& r = poses.road(road_index);
  s = poses.clamp_s(r, s);
  const detail::PoseGeometry& record = poses.geometry_at(r, s);
  const Geometry& geometry = record.geometry;
  return detail::to_world(geometry, record.cos_h, record.sin_h,
                          detail::evaluate_local(geometry, s - geometry.s));
}

[[gnu::hot]] const Geometry* Map::plan_record_at(size_t road_index, double s) const {
  const detail::PoseGeometry* record =
      impl_->poses.geometry_before(impl_->poses.road(road_index), s);
  return record == nullptr ? nullptr : &record->geometry;
}

double Map::elevation(size_t road_index, double s) const {
  const detail::PoseRoad& r = impl_->poses.road(road_index);
  return impl_->poses.elevation(r).value(impl_->poses.clamp_s(r, s));
}

double Map::elevation_slope(size_t road_index, double s) const {
  const Road& r = road(road_index);
  return detail::poly_slope(r.elevation, clamp_s(r, s));
}

double Map::superelevation(size_t road_index, double s) const {
  const detail::PoseRoad& r = impl_->poses.road(road_index);
  return impl_->poses.superelevation(r).value(impl_->poses.clamp_s(r, s));
}

double Map::lane_offset(size_t road_index, double s) const {
  const detail::PoseRoad& r = impl_->poses.road(road_index);
  return impl_->poses.lane_offsets(r).value(impl_->poses.clamp_s(r, s));
}

double Map::shape_height(size_t road_index, double s, double t) const {
  const Road& r = road(road_index);
  if (r.shapes.empty()) {
    return 0.0;
  }
  s = clamp_s(r, s);
  // §8.4.3: shapes are grouped by s; within the group valid at s, the record with the largest
  // t <= query t applies (dt = t - record t). Between two s groups the heights are interpolated
  // linearly in s, as the standard prescribes.
  const auto group_height = [&](double group_s) {
    const ShapeRecord* best = nullptr;  // largest t <= query t, else the smallest t
    for (const ShapeRecord& shape : r.shapes) {
      if (shape.s != group_s) {
        continue;
      }
      const bool better = best == nullptr ||
                          (shape.t <= t ? (best->t > t || shape.t > best->t) : shape.t < best->t);
      if (better) {
        best = &shape;
      }
    }
    const double dt = t - best->t;
    return best->a + dt * (best->b + dt * (best->c + dt * best->d));
  };
  double before = r.shapes.front().s;
  double after = before;
  bool have_after = false;
  for (const ShapeRecord& shape : r.shapes) {
    if (shape.s <= s) {
      before = std::max(before, shape.s);
    } else if (!have_after || shape.s < after) {
      after = shape.s;
      have_after = true;
    }
  }
  const double h0 = group_height(before);
  if (!have_after || after <= before) {
    return h0;
  }
  const double h1 = group_height(after);
  const double w = (s - before) / (after - before);
  return h0 + w * (h1 - h0);
}

namespace {

/// The surface at a road point and its roll's cosine and sine (world_pose tilts t by them).
struct Surface {
  SurfacePose pose;
  double cos_r = 1.0;
  double sin_r = 0.0;
};

Surface surface_at(const Map& map, const detail::PoseTable& poses, const detail::PoseRoad& r,
                   size_t road_index, double s, double t, double h) {
  const double cs = poses.clamp_s(r, s);
  // Flat roads are the common case: no superelevation, no slope. The shortcuts give the bits
  // the library would (cos(+0) = 1, sin(+0) = +0, atan(+-0) = +-0) without calling it.
  const double roll = r.level && std::abs(cs) <= detail::PoseTable::kZeroBound
                          ? 0.0
                          : poses.superelevation(r).value(cs);
  const bool level = roll == 0.0 && !std::signbit(roll);
  const double cos_r = level ? 1.0 : std::cos(roll);
  const double sin_r = level ? 0.0 : std::sin(roll);
  double elevation = 0.0;
  double slope = 0.0;
  const detail::PolyRun profile = poses.elevation(r);
  if (profile.count != 0 && cs >= profile.starts[0]) {
    const Poly3& record = profile.first[profile.index(cs)];
    elevation = record.value(cs);
    slope = record.slope(cs);
  }
  // §2.3 / §8.4.2: the t axis is the reference line's left normal rotated about s by the
  // superelevation roll, so t moves cos(roll) horizontally and sin(roll) up; h runs along the
  // rotated surface normal.
  Surface surface;
  surface.pose.z =
      elevation + t * sin_r + h * cos_r + (r.has_shapes ? map.shape_height(road_index, s, t) : 0.0);
  surface.pose.p = -(slope == 0.0 ? slope : std::atan(slope));
  surface.pose.r = roll;
  surface.cos_r = cos_r;
  surface.sin_r = sin_r;
  return surface;
}

}  // namespace

[[gnu::hot]] WorldPose Map::world_pose(size_t road_index, double s, double t, double h) const {
  const detail::PoseTable& poses = impl_->poses;
  const detail::PoseRoad& r = poses.road(road_index);
  const double cs = poses.clamp_s(r, s);
  // Map::reference, with its record kept: where the heading is the record's own (a line, an arc
  // at its start) its cosine and sine are the record's, computed by the same functions at build.
  const detail::PoseGeometry& record = poses.geometry_at(r, cs);
  const Geometry& geometry = record.geometry;
  const RefPoint ref = detail::to_world(geometry, record.cos_h, record.sin_h,
                                        detail::evaluate_local(geometry, cs - geometry.s));
  const bool record_heading =
      std::bit_cast<uint64_t>(ref.hdg) == std::bit_cast<uint64_t>(geometry.hdg);
  const double sin_h = record_heading ? record.sin_h : std::sin(ref.hdg);
  const double cos_h = record_heading ? record.cos_h : std::cos(ref.hdg);
  const Surface surface = surface_at(*this, poses, r, road_index, s, t, h);
  const double horizontal = t * surface.cos_r - h * surface.sin_r;
  WorldPose pose;
  pose.x = ref.x - sin_h * horizontal;
  pose.y = ref.y + cos_h * horizontal;
  pose.z = surface.pose.z;
  pose.h = ref.hdg;
  pose.p = surface.pose.p;
  pose.r = surface.pose.r;
  return pose;
}

double reference_curvature(const Map& map, size_t road_index, double s) {
  const detail::PoseTable& poses = detail::MapAccess::poses(map);
  const detail::PoseRoad& r = poses.road(road_index);
  s = poses.clamp_s(r, s);
  const Geometry& geometry = poses.geometry_at(r, s).geometry;
  return detail::local_curvature(geometry, s - geometry.s);
}

SurfacePose surface_pose(const Map& map, size_t road_index, double s, double t, double h) {
  const detail::PoseTable& poses = detail::MapAccess::poses(map);
  return surface_at(map, poses, poses.road(road_index), road_index, s, t, h).pose;
}

size_t Map::section_index(size_t road_index, double s) const {
  const Road& r = road(road_index);
  return detail::record_index(r.lane_sections, clamp_s(r, s),
                              [](const LaneSection& x) { return x.s; });
}

double Map::section_end(size_t road_index, size_t section) const {
  const Road& r = road(road_index);
  return section + 1 < r.lane_sections.size() ? r.lane_sections[section + 1].s : r.length;
}

void Map::lane_spans(size_t road_index, double s, std::vector<LaneSpan>& out) const {
  lane_spans_in_section(road_index, section_index(road_index, s), s, out);
}

void Map::lane_spans_in_section(size_t road_index, size_t section, double s,
                                std::vector<LaneSpan>& out) const {
  const Road& r = road(road_index);
  s = clamp_s(r, s);
  const LaneSection& lanes = r.lane_sections[section];
  out.resize(lanes.lanes.size());
  const size_t n = detail::compute_spans(
      lanes, s, detail::section_lane_offset(*this, road_index, section, s), out.data());
  out.resize(n);
}

std::optional<LaneSpan> Map::lane_span(size_t road_index, double s, int lane_id) const {
  return lane_span_in_section(road_index, section_index(road_index, s), s, lane_id);
}

[[gnu::hot]] bool Map::section_widths_only(size_t road_index, size_t section) const {
  return impl_->spans.widths_only(road_index, section);
}

[[gnu::hot]] std::optional<LaneSpan> Map::lane_span_in_section(size_t road_index, size_t section,
                                                               double s, int lane_id) const {
  s = impl_->poses.clamp_s(impl_->poses.road(road_index), s);
  LaneSpan span;
  if (impl_->spans.span(road_index, section, s,
                        detail::MapAccess::section_lane_offset(*this, road_index, section, s),
                        lane_id, span)) {
    return span;
  }
  return std::nullopt;
}

std::optional<int> Map::lane_at(size_t road_index, double s, double t) const {
  const Road& r = road(road_index);
  s = clamp_s(r, s);
  const LaneSection& section = r.lane_sections[section_index(road_index, s)];
  LaneSpan spans[detail::kMaxLanesPerSection];
  const size_t n = detail::compute_spans(section, s, lane_offset(road_index, s), spans);
  std::optional<int> best;
  for (size_t i = 0; i < n; ++i) {
    // A border belongs to the inner lane (smaller |id|).
    if (spans[i].width() > 0.0 && t >= spans[i].t_min() && t <= spans[i].t_max() &&
        (!best || std::abs(spans[i].id) < std::abs(*best))) {
      best = spans[i].id;
    }
  }
  return best;
}

const Lane* Map::lane(const LaneRef& ref) const {
  if (ref.road >= road_count()) {
    return nullptr;
  }
  const Road& r = road(ref.road);
  if (ref.section >= r.lane_sections.size()) {
    return nullptr;
  }
  for (const Lane& lane : r.lane_sections[ref.section].lanes) {
    if (lane.id == ref.lane) {
      return &lane;
    }
  }
  return nullptr;
}

std::optional<LanePosition> Map::locate(double x, double y, const LocateOptions& options) const {
  std::call_once(impl_->index_built, [this] { impl_->index.prepare(*this); });
  return impl_->index.locate(*this, x, y, options);
}

double Map::clear_of_lanes(double x, double y, double max_distance, double reach) const {
  std::call_once(impl_->index_built, [this] { impl_->index.prepare(*this); });
  return impl_->index.clear_of_lanes(*this, x, y, max_distance, reach);
}

}  // namespace corsa::xodr
