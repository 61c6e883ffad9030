#include "spatial_index.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "corsa/xodr/map_parts.h"
#include "region_bounds.h"
#include "road_eval.h"

namespace corsa::xodr::detail {
namespace {

constexpr double kMaxChunkLength = 5.0;   // m
constexpr double kMaxChunkTurn = 0.1;     // rad of heading per chunk
constexpr double kMinChunkLength = 0.05;  // m
constexpr int kSamples = 5;               // per chunk, ends included
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
  const double k0 = std::abs(reference_curvature(map, road, s));
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

// The chunks of one lane section, in s order.
void add_section_chunks(const Map& map, uint32_t road, uint32_t section_index,
                        std::vector<Chunk>& chunks_) {
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

namespace {

constexpr uint32_t kBlockChunks = 8;
constexpr size_t kMaxCoarseCells = size_t{1} << 20;
// A section whose bound covers more coarse cells than this is looked at by every query instead.
constexpr double kMaxCellsPerSection = 4096.0;

}  // namespace

SpatialIndex::SpatialIndex() = default;
SpatialIndex::~SpatialIndex() = default;

size_t SpatialIndex::section_count() const { return sections_.size(); }
size_t SpatialIndex::built_sections() const { return built_count_.load(); }

void SpatialIndex::prepare(const Map& map) {
  for (uint32_t road = 0; road < map.road_count(); ++road) {
    for (uint32_t section = 0; section < map.road(road).lane_sections.size(); ++section) {
      auto entry = std::make_unique<Section>();
      entry->road = road;
      entry->section = section;
      entry->bounded = section_bounds(map, road, section, entry->bounds);
      sections_.push_back(std::move(entry));
    }
  }
  // The coarse grid over the bounded sections: cells of 64 m, larger when the map is huge.
  double max_x = 0.0, max_y = 0.0;
  bool any = false;
  for (const auto& section : sections_) {
    if (!section->bounded) {
      continue;
    }
    const Bounds& b = section->bounds;
    min_x_ = any ? std::min(min_x_, b.x0) : b.x0;
    min_y_ = any ? std::min(min_y_, b.y0) : b.y0;
    max_x = any ? std::max(max_x, b.x1) : b.x1;
    max_y = any ? std::max(max_y, b.y1) : b.y1;
    any = true;
  }
  min_x_ = clamp_coordinate(min_x_), min_y_ = clamp_coordinate(min_y_);
  max_x = clamp_coordinate(max_x), max_y = clamp_coordinate(max_y);
  cell_ = 64.0;
  while ((std::floor((max_x - min_x_) / cell_) + 1.0) *
             (std::floor((max_y - min_y_) / cell_) + 1.0) >
         static_cast<double>(kMaxCoarseCells)) {
    cell_ *= 2.0;
  }
  nx_ = static_cast<int>((max_x - min_x_) / cell_) + 1;
  ny_ = static_cast<int>((max_y - min_y_) / cell_) + 1;
  const size_t cells = static_cast<size_t>(nx_) * static_cast<size_t>(ny_);
  cell_start_.assign(cells + 1, 0);
  const auto range = [&](const Bounds& b, int& i0, int& j0, int& i1, int& j1) {
    const auto cell = [&](double v, double origin, int n) {
      const double c = std::floor((v - origin) / cell_);
      return !(c >= 0.0) ? 0 : static_cast<int>(std::min(c, static_cast<double>(n - 1)));
    };
    i0 = cell(b.x0, min_x_, nx_), i1 = cell(b.x1, min_x_, nx_);
    j0 = cell(b.y0, min_y_, ny_), j1 = cell(b.y1, min_y_, ny_);
  };
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<uint32_t> fill;
    if (pass == 1) {
      for (size_t i = 0; i < cells; ++i) {
        cell_start_[i + 1] += cell_start_[i];
      }
      cell_items_.assign(cell_start_[cells], 0);
      fill.assign(cell_start_.begin(), cell_start_.end() - 1);
    }
    for (uint32_t index = 0; index < sections_.size(); ++index) {
      const Section& section = *sections_[index];
      int i0 = 0, j0 = 0, i1 = 0, j1 = 0;
      if (section.bounded) {
        range(section.bounds, i0, j0, i1, j1);
      }
      if (!section.bounded || static_cast<double>(i1 - i0 + 1) * static_cast<double>(j1 - j0 + 1) >
                                  kMaxCellsPerSection) {
        if (pass == 0) {
          everywhere_.push_back(index);
        }
        continue;
      }
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

SpatialIndex::Section& SpatialIndex::built(const Map& map, uint32_t index) const {
  Section& section = *sections_[index];
  std::call_once(section.once, [&] {
    add_section_chunks(map, section.road, section.section, section.chunks);
    for (const Chunk& chunk : section.chunks) {
      Bounds box;
      chunk_bounds(chunk, box.x0, box.y0, box.x1, box.y1);
      section.boxes.push_back(box);
    }
    for (uint32_t first = 0; first < section.chunks.size(); first += kBlockChunks) {
      Block block;
      block.first = first;
      block.end =
          std::min<uint32_t>(first + kBlockChunks, static_cast<uint32_t>(section.chunks.size()));
      for (uint32_t k = block.first; k < block.end; ++k) {
        const Bounds& box = section.boxes[k];
        block.x0 = k == block.first ? box.x0 : std::min(block.x0, box.x0);
        block.y0 = k == block.first ? box.y0 : std::min(block.y0, box.y0);
        block.x1 = k == block.first ? box.x1 : std::max(block.x1, box.x1);
        block.y1 = k == block.first ? box.y1 : std::max(block.y1, box.y1);
      }
      section.blocks.push_back(block);
    }
    built_count_.fetch_add(1);
  });
  return section;
}

size_t SpatialIndex::chunks_outside_bounds() const {
  size_t outside = 0;
  for (const auto& section : sections_) {
    if (!section->bounded) {
      continue;
    }
    const Bounds& b = section->bounds;
    for (const Bounds& box : section->boxes) {
      outside += box.x0 < b.x0 || box.y0 < b.y0 || box.x1 > b.x1 || box.y1 > b.y1 ? 1 : 0;
    }
  }
  return outside;
}

void SpatialIndex::build_all(const Map& map) const {
  for (uint32_t index = 0; index < sections_.size(); ++index) {
    built(map, index);
  }
}

void SpatialIndex::sections_near(double x, double y, double r, std::vector<uint32_t>& out) const {
  out.assign(everywhere_.begin(), everywhere_.end());
  if (nx_ > 0 && ny_ > 0 && std::isfinite(x) && std::isfinite(y)) {
    const auto cell = [&](double v, double origin, int n) {
      const double c = std::floor((v - origin) / cell_);
      return !(c >= 0.0) ? -1 : c >= n ? n : static_cast<int>(c);  // NaN: below the grid
    };
    const int i0 = std::max(0, cell(x - r, min_x_, nx_)),
              i1 = std::min(nx_ - 1, cell(x + r, min_x_, nx_));
    const int j0 = std::max(0, cell(y - r, min_y_, ny_)),
              j1 = std::min(ny_ - 1, cell(y + r, min_y_, ny_));
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const size_t c = static_cast<size_t>(j) * static_cast<size_t>(nx_) + i;
        out.insert(out.end(), cell_items_.begin() + cell_start_[c],
                   cell_items_.begin() + cell_start_[c + 1]);
      }
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace corsa::xodr::detail
