#include "spatial_index.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "road_eval.h"

namespace corsa::xodr::detail {
namespace {

constexpr double kMaxChunkLength = 5.0;   // m
constexpr double kMaxChunkTurn = 0.1;     // rad of heading per chunk
constexpr double kMinChunkLength = 0.05;  // m
constexpr int kSamples = 5;               // per chunk, ends included
constexpr size_t kMaxCells = size_t{1} << 23;
// Grid entries (chunk, cell) allowed per chunk on average: absurd lane widths (a fuzzed 1e20 m)
// make every chunk cover the whole grid, which the cell size then grows to avoid.
constexpr double kMaxEntriesPerChunk = 64.0;
// Coordinates (m) beyond any real map; bounds are clamped to it (NaN to its low end) so that the
// grid arithmetic stays finite whatever a map's numbers overflow to.
constexpr double kCoordinateLimit = 1e15;

double clamp_coordinate(double v) {
  if (!(v >= -kCoordinateLimit)) {
    return -kCoordinateLimit;
  }
  return std::min(v, kCoordinateLimit);
}

struct Extent {
  double t_min = 0.0;
  double t_max = 0.0;
};

Extent section_extent(const Map& map, uint32_t road, uint32_t section_index,
                      const LaneSection& section, double s) {
  LaneSpan spans[kMaxLanesPerSection];
  const size_t n =
      compute_spans(section, s, section_lane_offset(map, road, section_index, s), spans);
  Extent extent{std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest()};
  for (size_t i = 0; i < n; ++i) {
    extent.t_min = std::min(extent.t_min, spans[i].t_min());
    extent.t_max = std::max(extent.t_max, spans[i].t_max());
  }
  if (n == 0) {
    extent = Extent{0.0, 0.0};
  }
  return extent;
}

/// Length of the chunk starting at s: at most 5 m and 0.1 rad of heading, no sliver before the
/// section's end, and cut at a planView record boundary so that most chunks lie in one record.
double chunk_length(const Map& map, uint32_t road, double s, double s_stop) {
  const double k0 = std::abs(map.reference(road, s).curvature);
  double length = std::min(kMaxChunkLength, s_stop - s);
  if (k0 * length > kMaxChunkTurn) {
    length = std::max(kMinChunkLength, kMaxChunkTurn / k0);
  }
  if (s_stop - (s + length) < kMinChunkLength) {
    length = s_stop - s;  // no sliver at the end
  }
  const auto& records = map.road(road).plan_view;
  const size_t g = record_index(records, s, [](const Geometry& x) { return x.s; });
  if (g + 1 < records.size()) {
    const double boundary = records[g + 1].s;
    if (boundary > s + kMinChunkLength && boundary < s + length - 1e-9) {
      length = boundary - s;
    }
  }
  return length;
}

Chunk::Shape chunk_shape(const Road& road, double s0, double s1) {
  const auto& records = road.plan_view;
  const size_t g = record_index(records, s0, [](const Geometry& x) { return x.s; });
  if (g + 1 < records.size() && s1 > records[g + 1].s + 1e-12) {
    return Chunk::Shape::kGeneral;  // spans two records
  }
  if (std::holds_alternative<LineGeometry>(records[g].shape)) {
    return Chunk::Shape::kLine;
  }
  if (const auto* arc = std::get_if<ArcGeometry>(&records[g].shape)) {
    return arc->curvature == 0.0 ? Chunk::Shape::kLine : Chunk::Shape::kArc;
  }
  return Chunk::Shape::kGeneral;
}

}  // namespace

void SpatialIndex::add_section_chunks(const Map& map, uint32_t road, uint32_t section_index) {
  const Road& r = map.road(road);
  const LaneSection& section = r.lane_sections[section_index];
  const double s_begin = std::min(section.s, r.length);
  const double s_stop = std::min(map.section_end(road, section_index), r.length);
  double s = s_begin;
  while (s < s_stop - 1e-9) {
    const double length = chunk_length(map, road, s, s_stop);
    const double s_end = s + length;
    Chunk chunk;
    chunk.shape = chunk_shape(map.road(road), s, s_end);
    chunk.road = road;
    chunk.section = section_index;
    chunk.s0 = s;
    chunk.s1 = s_end;
    RefPoint refs[kSamples];
    Extent extents[kSamples];
    double max_curvature = 0.0;
    double max_t = 0.0;
    for (int i = 0; i < kSamples; ++i) {
      const double si = s + length * i / (kSamples - 1);
      refs[i] = map.reference(road, si);
      extents[i] = section_extent(map, road, section_index, section, si);
      max_curvature = std::max(max_curvature, std::abs(refs[i].curvature));
      max_t = std::max({max_t, std::abs(extents[i].t_min), std::abs(extents[i].t_max)});
    }
    chunk.x0 = refs[0].x;
    chunk.y0 = refs[0].y;
    chunk.tx0 = std::cos(refs[0].hdg);
    chunk.ty0 = std::sin(refs[0].hdg);
    chunk.k0 = refs[0].curvature;
    chunk.hdg0 = refs[0].hdg;
    chunk.x1 = refs[kSamples - 1].x;
    chunk.y1 = refs[kSamples - 1].y;
    chunk.tx1 = std::cos(refs[kSamples - 1].hdg);
    chunk.ty1 = std::sin(refs[kSamples - 1].hdg);
    chunk.ox = refs[0].x;
    chunk.oy = refs[0].y;
    const double dx = refs[kSamples - 1].x - refs[0].x;
    const double dy = refs[kSamples - 1].y - refs[0].y;
    const double chord = std::hypot(dx, dy);
    chunk.ux = chord > 1e-9 ? dx / chord : std::cos(refs[0].hdg);
    chunk.uy = chord > 1e-9 ? dy / chord : std::sin(refs[0].hdg);
    chunk.a0 = chunk.b0 = std::numeric_limits<double>::max();
    chunk.a1 = chunk.b1 = std::numeric_limits<double>::lowest();
    for (int i = 0; i < kSamples; ++i) {
      const double nx = -std::sin(refs[i].hdg);
      const double ny = std::cos(refs[i].hdg);
      for (const double t : {extents[i].t_min, extents[i].t_max, 0.0}) {
        const double px = refs[i].x + t * nx - chunk.ox;
        const double py = refs[i].y + t * ny - chunk.oy;
        const double a = px * chunk.ux + py * chunk.uy;
        const double b = py * chunk.ux - px * chunk.uy;
        chunk.a0 = std::min(chunk.a0, a);
        chunk.a1 = std::max(chunk.a1, a);
        chunk.b0 = std::min(chunk.b0, b);
        chunk.b1 = std::max(chunk.b1, b);
      }
    }
    // Between samples the boundaries bow out by at most ~ (|t| + step) * heading change.
    const double step = length / (kSamples - 1);
    const double margin = 0.1 + (max_t + step) * (1.5 * max_curvature * step + 0.01);
    chunk.a0 -= margin;
    chunk.a1 += margin;
    chunk.b0 -= margin;
    chunk.b1 += margin;
    chunks_.push_back(chunk);
    s = s_end;
  }
}

void SpatialIndex::build(const Map& map) {
  chunks_.clear();
  for (uint32_t road = 0; road < map.road_count(); ++road) {
    for (uint32_t section = 0; section < map.road(road).lane_sections.size(); ++section) {
      add_section_chunks(map, road, section);
    }
  }
  build_grid();
}

namespace {

/// World bounding box of a chunk's rectangle.
void chunk_bounds(const Chunk& c, double& x0, double& y0, double& x1, double& y1) {
  x0 = y0 = std::numeric_limits<double>::max();
  x1 = y1 = std::numeric_limits<double>::lowest();
  for (const double a : {c.a0, c.a1}) {
    for (const double b : {c.b0, c.b1}) {
      const double x = c.ox + a * c.ux - b * c.uy;
      const double y = c.oy + a * c.uy + b * c.ux;
      x0 = std::min(x0, clamp_coordinate(x));
      x1 = std::max(x1, clamp_coordinate(x));
      y0 = std::min(y0, clamp_coordinate(y));
      y1 = std::max(y1, clamp_coordinate(y));
    }
  }
}

}  // namespace

void SpatialIndex::cell_range(double x0, double y0, double x1, double y1, int& i0, int& j0, int& i1,
                              int& j1) const {
  const auto cell = [&](double v, double origin, int n) {
    const double c = std::floor((v - origin) / cell_);
    if (!(c >= 0.0)) {
      return 0;  // also NaN (a query at a non-finite point)
    }
    return static_cast<int>(std::min(c, static_cast<double>(n - 1)));
  };
  i0 = cell(x0, min_x_, nx_);
  i1 = cell(x1, min_x_, nx_);
  j0 = cell(y0, min_y_, ny_);
  j1 = cell(y1, min_y_, ny_);
}

double SpatialIndex::grid_entries() const {
  double entries = 0.0;
  for (const Chunk& chunk : chunks_) {
    double x0, y0, x1, y1;
    chunk_bounds(chunk, x0, y0, x1, y1);
    int i0, j0, i1, j1;
    cell_range(x0, y0, x1, y1, i0, j0, i1, j1);
    entries += static_cast<double>(i1 - i0 + 1) * static_cast<double>(j1 - j0 + 1);
  }
  return entries;
}

void SpatialIndex::build_grid() {
  double max_x = 0.0, max_y = 0.0;
  min_x_ = min_y_ = std::numeric_limits<double>::max();
  max_x = max_y = std::numeric_limits<double>::lowest();
  for (const Chunk& c : chunks_) {
    double x0, y0, x1, y1;
    chunk_bounds(c, x0, y0, x1, y1);
    min_x_ = std::min(min_x_, x0);
    min_y_ = std::min(min_y_, y0);
    max_x = std::max(max_x, x1);
    max_y = std::max(max_y, y1);
  }
  if (chunks_.empty()) {
    min_x_ = min_y_ = max_x = max_y = 0.0;
  }
  cell_ = 4.0;
  // Count whole cells (+1 each way): a long thin extent (two roads 1e12 m apart on one line)
  // must not give a row of billions of cells just because the product of the fractions is small.
  const auto grid_cells = [&] {
    return (std::floor((max_x - min_x_) / cell_) + 1.0) *
           (std::floor((max_y - min_y_) / cell_) + 1.0);
  };
  while (grid_cells() > static_cast<double>(kMaxCells)) {
    cell_ *= 2.0;
  }
  const double max_entries = kMaxEntriesPerChunk * static_cast<double>(chunks_.size()) +
                             static_cast<double>(kMaxCells / 8);
  while (true) {
    nx_ = static_cast<int>((max_x - min_x_) / cell_) + 1;
    ny_ = static_cast<int>((max_y - min_y_) / cell_) + 1;
    if ((nx_ == 1 && ny_ == 1) || grid_entries() <= max_entries) {
      break;
    }
    cell_ *= 2.0;
  }
  const size_t cells = static_cast<size_t>(nx_) * static_cast<size_t>(ny_);
  cell_start_.assign(cells + 1, 0);
  // Two passes (count, fill): a compact CSR layout keeps a query's candidates contiguous.
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<uint32_t> fill;
    if (pass == 1) {
      for (size_t i = 0; i < cells; ++i) {
        cell_start_[i + 1] += cell_start_[i];
      }
      cell_items_.assign(cell_start_[cells], 0);
      fill.assign(cell_start_.begin(), cell_start_.end() - 1);
    }
    for (uint32_t index = 0; index < chunks_.size(); ++index) {
      double x0, y0, x1, y1;
      chunk_bounds(chunks_[index], x0, y0, x1, y1);
      int i0, j0, i1, j1;
      cell_range(x0, y0, x1, y1, i0, j0, i1, j1);
      for (int j = j0; j <= j1; ++j) {
        for (int i = i0; i <= i1; ++i) {
          const size_t cell = static_cast<size_t>(j) * static_cast<size_t>(nx_) + i;
          if (pass == 0) {
            ++cell_start_[cell + 1];
          } else {
            cell_items_[fill[cell]++] = index;
          }
        }
      }
    }
  }
}

}  // namespace corsa::xodr::detail
