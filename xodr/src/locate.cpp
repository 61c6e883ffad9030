// World -> lane queries over the spatial index: candidate chunks from the grid, then a Newton
// projection onto the reference line and the lane spans at the foot point.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "road_eval.h"
#include "spatial_index.h"

namespace corsa::xodr::detail {
namespace {

/// A candidate answer with what ranks it: distance first, then the offset from the lane centre
/// (overlapping junction lanes), then road index and s for determinism.
struct Candidate {
  LanePosition position;
  double center_offset = 0.0;
  double height_gap = 0.0;  ///< |surface height - query z| (m), 0 without a query z

  bool better_than(const Candidate& other) const {
    if (position.distance != other.position.distance) {
      return position.distance < other.position.distance;
    }
    // Another level (stacked roads) before the centre offset; same level within a metre.
    if (std::abs(height_gap - other.height_gap) > 1.0) {
      return height_gap < other.height_gap;
    }
    if (center_offset != other.center_offset) {
      return center_offset < other.center_offset;
    }
    if (position.road != other.position.road) {
      return position.road < other.position.road;
    }
    return position.s < other.position.s;
  }
};

/// Foot point of (x, y) on the reference line within [chunk.s0, chunk.s1]: the root of
/// f(s) = (P - r(s)) · T(s). The first step is Newton's with f'(s) = -(1 - κ t), exact for
/// arc-length parametrised lines and arcs; later steps are secant steps, which also converge
/// where s is not arc length (paramPoly3 with pRange="normalized"). Clamped to the chunk.
struct Foot {
  double s = 0.0;
  RefPoint ref;
  double along = 0.0;    ///< (P - r) · T, non-zero only when clamped at a chunk end
  double lateral = 0.0;  ///< (P - r) · N, horizontal
};

/// Closed-form foot point on a line or arc chunk (false when it falls outside the chunk, or
/// the chunk has another shape): no reference-line evaluation at all.
bool project_exact(const Chunk& chunk, double x, double y, Foot& foot) {
  const double along0 = (x - chunk.x0) * chunk.tx0 + (y - chunk.y0) * chunk.ty0;
  const double lateral0 = (y - chunk.y0) * chunk.tx0 - (x - chunk.x0) * chunk.ty0;
  if (chunk.shape == Chunk::Shape::kLine) {
    foot.s = chunk.s0 + along0;
    if (foot.s < chunk.s0 || foot.s > chunk.s1) {
      return false;
    }
    foot.ref =
        RefPoint{chunk.x0 + along0 * chunk.tx0, chunk.y0 + along0 * chunk.ty0, chunk.hdg0, 0.0};
    foot.along = 0.0;
    foot.lateral = lateral0;
    return true;
  }
  if (chunk.shape != Chunk::Shape::kArc) {
    return false;
  }
  // Circle of radius 1/k about C = r0 + N0 / k; the foot is where the radius through P meets
  // it: s from the angle swept, t = 1/k - sign(k) |P - C| (§7.5).
  const double k = chunk.k0;
  const double cx = chunk.x0 - chunk.ty0 / k;
  const double cy = chunk.y0 + chunk.tx0 / k;
  const double dx = x - cx;
  const double dy = y - cy;
  const double distance = std::sqrt(dx * dx + dy * dy);
  // Angle from the start radius (r0 - C) to (P - C), counter-clockwise.
  const double rx = chunk.x0 - cx;
  const double ry = chunk.y0 - cy;
  const double swept = std::atan2(rx * dy - ry * dx, rx * dx + ry * dy);
  foot.s = chunk.s0 + swept / k;
  if (foot.s < chunk.s0 || foot.s > chunk.s1 || distance == 0.0) {
    return false;
  }
  const double scale = std::abs(1.0 / k) / distance;
  foot.ref = RefPoint{cx + dx * scale, cy + dy * scale, chunk.hdg0 + k * (foot.s - chunk.s0), k};
  foot.along = 0.0;
  foot.lateral = 1.0 / k - (k > 0.0 ? distance : -distance);
  return true;
}

Foot project(const Map& map, const Chunk& chunk, double x, double y) {
  Foot exact;
  if (project_exact(chunk, x, y, exact)) {
    return exact;
  }
  const auto foot_at = [&](double s) {
    const RefFrame frame = MapAccess::reference_frame(map, chunk.road, s);
    Foot foot;
    foot.s = s;
    foot.ref = frame.point;
    const double dx = x - foot.ref.x;
    const double dy = y - foot.ref.y;
    foot.along = dx * frame.tx + dy * frame.ty;
    foot.lateral = dy * frame.tx - dx * frame.ty;
    return foot;
  };
  // First guess: one Newton step from the chunk start, from the cached tangent and curvature
  // there (exact on lines, so a line needs a single evaluation to confirm it).
  const double along0 = (x - chunk.x0) * chunk.tx0 + (y - chunk.y0) * chunk.ty0;
  const double lateral0 = (y - chunk.y0) * chunk.tx0 - (x - chunk.x0) * chunk.ty0;
  const double s =
      std::clamp(chunk.s0 + along0 / std::max(0.1, 1.0 - chunk.k0 * lateral0), chunk.s0, chunk.s1);
  Foot foot = foot_at(s);
  Foot previous;
  bool have_previous = false;
  for (int iteration = 0; iteration < 16; ++iteration) {
    if (std::abs(foot.along) < 1e-9) {
      break;
    }
    double next;
    const double df = have_previous ? foot.along - previous.along : 0.0;
    if (have_previous && df != 0.0) {
      next = foot.s - foot.along * (foot.s - previous.s) / df;
    } else {
      next = foot.s + foot.along / std::max(0.1, 1.0 - foot.ref.curvature * foot.lateral);
    }
    next = std::clamp(next, chunk.s0, chunk.s1);
    if (std::abs(next - foot.s) < 1e-10) {
      break;
    }
    previous = foot;
    have_previous = true;
    foot = foot_at(next);
  }
  return foot;
}

/// Ranks one candidate answer against the best so far.
void record(const Map& map, const Chunk& chunk, const Foot& foot, double t, int lane, double gap,
            double center_offset, double cos_r, const LocateOptions& options, Candidate& best,
            bool& have) {
  Candidate candidate;
  candidate.position.road = chunk.road;
  candidate.position.section = chunk.section;
  candidate.position.lane = lane;
  candidate.position.s = foot.s;
  candidate.position.t = t;
  candidate.position.heading = foot.ref.hdg;
  const double along = std::abs(foot.along) < 1e-6 ? 0.0 : foot.along;
  candidate.position.distance = along == 0.0 && gap == 0.0 ? 0.0 : std::hypot(along, gap * cos_r);
  candidate.center_offset = center_offset;
  if (candidate.position.distance > options.max_distance) {
    return;
  }
  if (options.z) {
    candidate.height_gap = std::abs(map.world_pose(chunk.road, foot.s, t).z - *options.z);
  }
  if (!have || candidate.better_than(best)) {
    best = candidate;
    have = true;
  }
}

/// Projects (x, y) onto the chunk's road and ranks the lane there. With `inside_only`, only a
/// lane that contains the point counts (the first pass: on-road points, which are most).
void evaluate_chunk(const Map& map, const Chunk& chunk, double x, double y,
                    const LocateOptions& options, bool inside_only, Candidate& best, bool& have) {
  const Foot foot = project(map, chunk, x, y);
  const Road& road = map.road(chunk.road);
  const LaneSection& section = road.lane_sections[chunk.section];
  const double roll = road.superelevation.empty() ? 0.0 : map.superelevation(chunk.road, foot.s);
  const double cos_r = roll == 0.0 ? 1.0 : std::cos(roll);
  const double t = foot.lateral / cos_r;
  const double offset = section_lane_offset(map, chunk.road, chunk.section, foot.s);
  LaneSpan hit;
  if (!options.drivable_only && find_lane_at(section, foot.s, offset, t, hit)) {
    // Fast path: the point is on a lane (the common case).
    record(map, chunk, foot, t, hit.id, 0.0, std::abs(t - hit.t_center()), 1.0, options, best,
           have);
    return;
  }
  if (inside_only && !options.drivable_only) {
    return;
  }
  NearestLane nearest;
  if (nearest_lane(section, foot.s, offset, t, options.drivable_only, nearest)) {
    record(map, chunk, foot, t, nearest.lane, nearest.gap, nearest.center_offset, cos_r, options,
           best, have);
  }
}

}  // namespace

std::optional<LanePosition> SpatialIndex::locate(const Map& map, double x, double y,
                                                 const LocateOptions& options) const {
  if (sections_.empty()) {
    return std::nullopt;
  }
  Candidate best;
  bool have = false;
  std::vector<uint32_t> near;
  // Pass 1: chunks whose rectangle contains the point, in map order (road, section, s).
  sections_near(x, y, 0.0, near);
  for (const uint32_t index : near) {
    if (sections_[index]->bounded && !sections_[index]->bounds.contains(x, y)) {
      continue;
    }
    const Section& section = built(map, index);
    for (const Block& block : section.blocks) {
      if (!(x >= block.x0 && x <= block.x1 && y >= block.y0 && y <= block.y1)) {
        continue;
      }
      for (uint32_t k = block.first; k < block.end; ++k) {
        const Chunk& chunk = section.chunks[k];
        if (chunk.near(x, y, 0.0) && chunk.spans(x, y)) {
          evaluate_chunk(map, chunk, x, y, options, true, best, have);
        }
      }
    }
  }
  if (have && best.position.distance == 0.0) {
    return best.position;
  }
  // Pass 2: every chunk within max_distance (off-road points) whose box meets the square about
  // the point (those beyond cannot be within max_distance).
  const double r = options.max_distance;
  sections_near(x, y, r, near);
  // Nearest rectangles first: a chunk's lanes lie inside its rectangle, so the distance to the
  // rectangle bounds the answer from below and the search stops once it exceeds the best. Ties
  // in map order.
  struct Near {
    double bound;
    uint64_t order;  ///< section << 32 | chunk
    const Chunk* chunk;
  };
  std::vector<Near> order;
  for (const uint32_t index : near) {
    if (sections_[index]->bounded && !sections_[index]->bounds.meets(x, y, r)) {
      continue;
    }
    const Section& section = built(map, index);
    for (const Block& block : section.blocks) {
      if (!(x + r >= block.x0 && x - r <= block.x1 && y + r >= block.y0 && y - r <= block.y1)) {
        continue;
      }
      for (uint32_t k = block.first; k < block.end; ++k) {
        const Chunk& chunk = section.chunks[k];
        if (section.boxes[k].meets(x, y, r) && chunk.near(x, y, r)) {
          order.push_back({chunk.distance_to(x, y), (uint64_t{index} << 32) | k, &chunk});
        }
      }
    }
  }
  std::sort(order.begin(), order.end(), [](const Near& a, const Near& b) {
    return a.bound < b.bound || (a.bound == b.bound && a.order < b.order);
  });
  for (const Near& candidate : order) {
    if (have && candidate.bound > best.position.distance) {
      break;
    }
    evaluate_chunk(map, *candidate.chunk, x, y, options, false, best, have);
  }
  return have ? std::optional<LanePosition>(best.position) : std::nullopt;
}

double SpatialIndex::clear_of_lanes(const Map& map, double x, double y, double max_distance,
                                    double reach) const {
  if (!std::isfinite(x) || !std::isfinite(y) || !(max_distance >= 0.0) || !(reach > 0.0)) {
    return 0.0;
  }
  if (sections_.empty()) {
    return reach;  // locate answers nothing anywhere
  }
  // A query at (x', y') examines only chunks whose rectangle it is near (Chunk::near with r at
  // most max_distance; the first pass with r = 0), of sections that sections_near lists for
  // the square of half side max_distance about it and whose bound meets that square. Within
  // `reach` of (x, y) along each axis those are among the chunks listed here for the square of
  // half side r (the grid's cells and the bounds are monotone in the square). A chunk's excess
  // changes by at most the point's move, at most sqrt(2) times its largest change along an
  // axis. The margin covers the rounding of those tests, far above it at map coordinates.
  constexpr double kSqrt2 = 1.4142135623730951;
  const double margin = 1e-6 + 1e-9 * (std::abs(x) + std::abs(y));
  const double r = max_distance + kSqrt2 * reach + margin;
  std::vector<uint32_t> near;
  sections_near(x, y, r, near);
  double least = std::numeric_limits<double>::infinity();
  for (const uint32_t index : near) {
    if (sections_[index]->bounded && !sections_[index]->bounds.meets(x, y, r)) {
      continue;
    }
    for (const Chunk& chunk : built(map, index).chunks) {
      least = std::min(least, chunk.excess(x, y));
    }
  }
  // A chunk with a NaN among its numbers is never near (its comparisons fail), and std::min
  // leaves its NaN excess out alike.
  const double clear = (least - max_distance - margin) / kSqrt2 - margin;
  return clear > 0.0 ? std::min(clear, reach) : 0.0;
}

}  // namespace corsa::xodr::detail
