// Holes in junctions (junction_holes.h). Each junction's area is sampled on a square grid: a
// cell is covered when its centre lies in a lane triangle of the road mesh; the uncovered cells
// that the outside cannot reach (through uncovered cells, diagonals included, so a gap of one
// cell between two roads is an opening) are the holes. A hole's rim (the covered cells around
// it) says who encloses it: only the drivable lanes of the junction's own roads (connecting,
// incoming and linked) make a hole to pave; a sidewalk, kerb or median lane there means a
// kerbed island, another road a place the junction does not own.

#include "corsa/xodr/junction_holes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>

#include "corsa/xodr/map.h"
#include "junction_area.h"

namespace corsa::xodr {
namespace {

using detail::boundary_outline;
using detail::convex_hull;
using detail::fill_row;
using detail::Vec2d;

// Cell flags: who covers it.
constexpr uint8_t kOwnRoadway = 1;  // a lane of the junction's roads that is not a kerb
constexpr uint8_t kOwnKerb = 2;     // a sidewalk, walkway, kerb or median lane of those roads
constexpr uint8_t kForeign = 4;     // a lane of another road
constexpr uint8_t kCovered = kOwnRoadway | kOwnKerb | kForeign;

constexpr double kBinSize = 16.0;    // m, side of the bins the mesh's triangles are sorted into
constexpr double kLevelBand = 2.0;   // m above or below the junction where other roads count
constexpr double kFlat = 0.05;       // m, height below which an object or signal lies flat
constexpr double kMaxCells = 4e6;    // cells of one junction's grid at most
constexpr double kHeadHeight = 1.5;  // m, zOffset from which a traffic light is a head in the air

/// Lanes that stand for a kerbed or raised border: an island they surround is not roadway.
bool is_kerb_lane(LaneType type) {
  return type == LaneType::kSidewalk || type == LaneType::kWalking || type == LaneType::kCurb ||
         type == LaneType::kMedian;
}

/// The mesh's lane triangles sorted into square bins, for the triangles near a junction.
class TriangleBins {
 public:
  explicit TriangleBins(const RoadMesh& mesh) : mesh_(mesh) {
    for (uint32_t i = 0; i < mesh.triangles.size(); ++i) {
      if (mesh.info[i].kind != SurfaceKind::kLane) {
        continue;
      }
      lanes_.push_back(i);
      const auto [lo, hi] = bounds(i);
      if (!binnable(lo, hi)) {
        unbinned_.push_back(i);
        continue;
      }
      for (int64_t bx = bin(lo.x); bx <= bin(hi.x); ++bx) {
        for (int64_t by = bin(lo.y); by <= bin(hi.y); ++by) {
          bins_[{bx, by}].push_back(i);
        }
      }
    }
  }

  /// Lane triangles whose bins overlap the box, each once, in index order.
  std::vector<uint32_t> near(Vec2d lo, Vec2d hi) const {
    if (!binnable(lo, hi)) {
      return lanes_;
    }
    std::vector<uint32_t> found = unbinned_;
    for (int64_t bx = bin(lo.x); bx <= bin(hi.x); ++bx) {
      for (int64_t by = bin(lo.y); by <= bin(hi.y); ++by) {
        if (const auto it = bins_.find({bx, by}); it != bins_.end()) {
          found.insert(found.end(), it->second.begin(), it->second.end());
        }
      }
    }
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    return found;
  }

  std::pair<Vec2d, Vec2d> bounds(uint32_t t) const {
    Vec2d lo{1e300, 1e300}, hi{-1e300, -1e300};
    for (uint32_t v : mesh_.triangles[t]) {
      lo = {std::min(lo.x, mesh_.vertices[v].x), std::min(lo.y, mesh_.vertices[v].y)};
      hi = {std::max(hi.x, mesh_.vertices[v].x), std::max(hi.y, mesh_.vertices[v].y)};
    }
    return {lo, hi};
  }

 private:
  static int64_t bin(double v) { return static_cast<int64_t>(std::floor(v / kBinSize)); }
  /// A box of at most 4096 bins a side within 1e15 m of the origin: binned. A triangle beyond
  /// (a lane 1e20 m wide, valid numbers) went into 1e36 bins, and `map holes` never ended; such
  /// triangles are kept aside and offered to every query instead.
  static bool binnable(Vec2d lo, Vec2d hi) {
    constexpr double kFar = 1e15, kMaxSpan = 4096 * kBinSize;
    return std::abs(lo.x) < kFar && std::abs(lo.y) < kFar && std::abs(hi.x) < kFar &&
           std::abs(hi.y) < kFar && hi.x - lo.x < kMaxSpan && hi.y - lo.y < kMaxSpan;
  }

  const RoadMesh& mesh_;
  std::map<std::pair<int64_t, int64_t>, std::vector<uint32_t>> bins_;
  std::vector<uint32_t> unbinned_;  ///< lane triangles too large or too far to bin
  std::vector<uint32_t> lanes_;     ///< every lane triangle, in index order
};

/// The junction's area sampled on cells: who covers each cell, the top of its own roads there,
/// which cells lie inside the area.
struct HoleGrid {
  double x0 = 0.0, y0 = 0.0, cell = 0.1;
  int nx = 0, ny = 0;
  std::vector<uint8_t> cover;
  std::vector<float> top;  // m, highest surface of the junction's own roads (-inf: none)
  std::vector<uint8_t> inside;

  size_t at(int ix, int iy) const { return static_cast<size_t>(iy) * nx + ix; }
  double cx(int ix) const { return x0 + (ix + 0.5) * cell; }
  double cy(int iy) const { return y0 + (iy + 0.5) * cell; }
};

/// Marks the cells whose centres lie in triangle t.
void rasterise(const RoadMesh& mesh, uint32_t t, uint8_t flag, bool own, HoleGrid& g) {
  const Vec3& a = mesh.vertices[mesh.triangles[t][0]];
  const Vec3& b = mesh.vertices[mesh.triangles[t][1]];
  const Vec3& c = mesh.vertices[mesh.triangles[t][2]];
  const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (std::abs(area) < 1e-12) {
    return;
  }
  const int ix0 =
      std::max(0, static_cast<int>(std::floor((std::min({a.x, b.x, c.x}) - g.x0) / g.cell)));
  const int ix1 =
      std::min(g.nx - 1, static_cast<int>(std::floor((std::max({a.x, b.x, c.x}) - g.x0) / g.cell)));
  const int iy0 =
      std::max(0, static_cast<int>(std::floor((std::min({a.y, b.y, c.y}) - g.y0) / g.cell)));
  const int iy1 =
      std::min(g.ny - 1, static_cast<int>(std::floor((std::max({a.y, b.y, c.y}) - g.y0) / g.cell)));
  for (int iy = iy0; iy <= iy1; ++iy) {
    for (int ix = ix0; ix <= ix1; ++ix) {
      const double x = g.cx(ix), y = g.cy(iy);
      // Barycentric weights of b and c; the centre is inside when all three are in [0, 1].
      const double u = ((x - a.x) * (c.y - a.y) - (y - a.y) * (c.x - a.x)) / area;
      const double v = ((b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x)) / area;
      if (u < 0.0 || v < 0.0 || u + v > 1.0) {
        continue;
      }
      const size_t i = g.at(ix, iy);
      g.cover[i] |= flag;
      if (own) {
        const double z = a.z + u * (b.z - a.z) + v * (c.z - a.z);
        g.top[i] = std::max(g.top[i], static_cast<float>(z));
      }
    }
  }
}

/// The roads a junction owns: its connecting roads (`inside`: the roads that name it), and the
/// roads its connections join.
std::set<uint32_t> junction_roads(const Map& map, const Junction& junction,
                                  const std::vector<uint32_t>& inside) {
  std::set<uint32_t> roads(inside.begin(), inside.end());
  for (const Connection& c : junction.connections) {
    for (const std::string* id : {&c.incoming_road, &c.connecting_road, &c.linked_road}) {
      if (const auto r = map.find_road(*id)) {
        roads.insert(static_cast<uint32_t>(*r));
      }
    }
  }
  return roads;
}

/// True for an object that stands on the ground: not paint or a surface (OpenDRIVE 1.8 §13.2
/// types roadMark, crosswalk, parkingSpace, roadSurface; untyped flat objects such as CARLA's
/// painted lane lines and stencils, which prove the place is paved rather than an island).
bool stands(const Object& o) {
  const std::string& type = o.type;
  if (type == "roadMark" || type == "crosswalk" || type == "parkingSpace" ||
      type == "roadSurface") {
    return false;
  }
  const bool untyped = type.empty() || type == "-1" || type == "none";
  return !(untyped && o.height <= kFlat && o.radius <= 0.0);
}

/// True for a signal whose position is on the ground: a sign's post, or a traffic light whose
/// zOffset is below 1.5 m (CARLA's lights give their post's foot). A light whose head is in the
/// air (zOffset 1.5 m or more) may hang over the road from an arm (the NGII C1 layer places
/// heads over the lanes they control), so it says nothing about what stands below; paint given as
/// a signal (zOffset and height about 0) stands neither.
bool stands(const Signal& s) {
  const bool light = s.dynamic || s.type.rfind("1000", 0) == 0;
  if (light) {
    return s.z_offset < kHeadHeight;
  }
  return s.z_offset > kFlat || s.height > kFlat;
}

/// Where objects and signals stand on the ground, in the map frame.
std::vector<Vec2d> standing_points(const Map& map) {
  std::vector<Vec2d> points;
  for (size_t r = 0; r < map.road_count(); ++r) {
    for (const Object& o : map.road(r).objects) {
      if (stands(o)) {
        const WorldPose p = map.world_pose(r, o.s, o.t);
        points.push_back({p.x, p.y});
      }
    }
    for (const Signal& s : map.road(r).signals) {
      if (stands(s)) {
        const WorldPose p = map.world_pose(r, s.s, s.t);
        points.push_back({p.x, p.y});
      }
    }
  }
  return points;
}

/// Cells of one hole and what encloses it.
struct HoleCells {
  std::vector<size_t> cells;
  std::vector<size_t> rim;  // covered cells touching it (8-neighbours), each once
  uint8_t rim_cover = 0;
};

/// The largest distance (m) from a hole cell's centre to the nearest covered cell's centre
/// (chamfer 1 / √2), over the hole's bounding box and one cell around it: every straight line out
/// of an enclosed hole first meets a covered cell of its rim, which lies in that box.
double deepest_clearance(const HoleGrid& g, const std::vector<size_t>& cells) {
  int x0 = g.nx, y0 = g.ny, x1 = 0, y1 = 0;
  for (size_t c : cells) {
    const int ix = static_cast<int>(c % g.nx), iy = static_cast<int>(c / g.nx);
    x0 = std::min(x0, ix - 1), y0 = std::min(y0, iy - 1);
    x1 = std::max(x1, ix + 1), y1 = std::max(y1, iy + 1);
  }
  const int w = x1 - x0 + 1, h = y1 - y0 + 1;
  constexpr float kFar = 1e9f;
  std::vector<float> d(static_cast<size_t>(w) * h, kFar);
  for (int iy = 0; iy < h; ++iy) {
    for (int ix = 0; ix < w; ++ix) {
      if ((g.cover[g.at(x0 + ix, y0 + iy)] & kCovered) != 0) {
        d[static_cast<size_t>(iy) * w + ix] = 0.0f;
      }
    }
  }
  const auto step = static_cast<float>(g.cell);
  const auto diagonal = static_cast<float>(g.cell * std::sqrt(2.0));
  auto relax = [&](int ix, int iy, int dx, int dy, float weight) {
    const int jx = ix + dx, jy = iy + dy;
    if (jx >= 0 && jy >= 0 && jx < w && jy < h) {
      float& here = d[static_cast<size_t>(iy) * w + ix];
      here = std::min(here, d[static_cast<size_t>(jy) * w + jx] + weight);
    }
  };
  for (int iy = 0; iy < h; ++iy) {
    for (int ix = 0; ix < w; ++ix) {
      relax(ix, iy, -1, 0, step);
      relax(ix, iy, 0, -1, step);
      relax(ix, iy, -1, -1, diagonal);
      relax(ix, iy, 1, -1, diagonal);
    }
  }
  for (int iy = h - 1; iy >= 0; --iy) {
    for (int ix = w - 1; ix >= 0; --ix) {
      relax(ix, iy, 1, 0, step);
      relax(ix, iy, 0, 1, step);
      relax(ix, iy, 1, 1, diagonal);
      relax(ix, iy, -1, 1, diagonal);
    }
  }
  float deepest = 0.0f;
  for (size_t c : cells) {
    const int ix = static_cast<int>(c % g.nx) - x0, iy = static_cast<int>(c / g.nx) - y0;
    deepest = std::max(deepest, d[static_cast<size_t>(iy) * w + ix]);
  }
  return deepest;
}

/// The uncovered cells inside the area that the outside does not reach, as 8-connected holes.
std::vector<HoleCells> enclosed_cells(const HoleGrid& g) {
  constexpr int kDx[8] = {1, -1, 0, 0, 1, 1, -1, -1};
  constexpr int kDy[8] = {0, 0, 1, -1, 1, -1, 1, -1};
  std::vector<int> label(g.cover.size(), -1);  // -2: reached from outside
  std::vector<size_t> queue;
  auto flood = [&](size_t start, int mark) {
    queue.assign(1, start);
    label[start] = mark;
    for (size_t q = 0; q < queue.size(); ++q) {
      const int ix = static_cast<int>(queue[q] % g.nx), iy = static_cast<int>(queue[q] / g.nx);
      for (int k = 0; k < 8; ++k) {
        const int jx = ix + kDx[k], jy = iy + kDy[k];
        if (jx < 0 || jy < 0 || jx >= g.nx || jy >= g.ny) {
          continue;
        }
        const size_t j = g.at(jx, jy);
        if (label[j] == -1 && (g.cover[j] & kCovered) == 0) {
          label[j] = mark;
          queue.push_back(j);
        }
      }
    }
  };
  for (int iy = 0; iy < g.ny; ++iy) {
    for (int ix = 0; ix < g.nx; ++ix) {
      const size_t i = g.at(ix, iy);
      const bool edge = ix == 0 || iy == 0 || ix == g.nx - 1 || iy == g.ny - 1;
      if (label[i] == -1 && (g.cover[i] & kCovered) == 0 && (edge || g.inside[i] == 0)) {
        flood(i, -2);
      }
    }
  }
  std::vector<HoleCells> holes;
  std::vector<uint8_t> in_rim(g.cover.size(), 0);
  for (size_t i = 0; i < g.cover.size(); ++i) {
    if (label[i] != -1 || (g.cover[i] & kCovered) != 0) {
      continue;
    }
    flood(i, static_cast<int>(holes.size()));
    HoleCells hole;
    hole.cells = queue;
    std::sort(hole.cells.begin(), hole.cells.end());
    for (size_t c : hole.cells) {
      const int ix = static_cast<int>(c % g.nx), iy = static_cast<int>(c / g.nx);
      for (int k = 0; k < 8; ++k) {
        const size_t j = g.at(ix + kDx[k], iy + kDy[k]);  // inside the grid: edges were flooded
        if ((g.cover[j] & kCovered) != 0 && in_rim[j] == 0) {
          in_rim[j] = 1;
          hole.rim.push_back(j);
          hole.rim_cover |= g.cover[j];
        }
      }
    }
    for (size_t j : hole.rim) {
      in_rim[j] = 0;
    }
    std::sort(hole.rim.begin(), hole.rim.end());
    holes.push_back(std::move(hole));
  }
  return holes;
}

/// Least-squares plane z = p0 + p1 x + p2 y through the rim's road surface (its mean height when
/// the rim is degenerate).
std::array<double, 3> rim_plane(const HoleGrid& g, const std::vector<size_t>& rim) {
  double n = 0, sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, syy = 0, sxz = 0, syz = 0;
  for (size_t j : rim) {
    if (!std::isfinite(g.top[j])) {
      continue;
    }
    // Relative to the grid's origin, for conditioning.
    const double x = g.cx(static_cast<int>(j % g.nx)) - g.x0;
    const double y = g.cy(static_cast<int>(j / g.nx)) - g.y0;
    const double z = g.top[j];
    n += 1;
    sx += x, sy += y, sz += z, sxx += x * x, sxy += x * y, syy += y * y, sxz += x * z, syz += y * z;
  }
  if (n == 0) {
    return {0.0, 0.0, 0.0};
  }
  // Normal equations, centred: [cxx cxy; cxy cyy] [p1 p2] = [cxz cyz].
  const double mx = sx / n, my = sy / n, mz = sz / n;
  const double cxx = sxx / n - mx * mx, cxy = sxy / n - mx * my, cyy = syy / n - my * my;
  const double cxz = sxz / n - mx * mz, cyz = syz / n - my * mz;
  const double det = cxx * cyy - cxy * cxy;
  if (std::abs(det) < 1e-9) {
    return {mz, 0.0, 0.0};
  }
  const double p1 = (cxz * cyy - cyz * cxy) / det, p2 = (cyz * cxx - cxz * cxy) / det;
  return {mz - p1 * mx - p2 * my, p1, p2};
}

/// The paving of a hole: its cells and its rim as grid squares, `drop` below the plane through
/// the rim's road surface and below every rim cell's own surface.
void pave(const HoleGrid& g, const HoleCells& h, double drop, JunctionHole& out) {
  const std::array<double, 3> plane = rim_plane(g, h.rim);
  std::vector<size_t> cells = h.cells;
  cells.insert(cells.end(), h.rim.begin(), h.rim.end());
  std::sort(cells.begin(), cells.end());
  std::map<size_t, uint32_t> vertex_of;  // grid vertex -> mesh vertex
  std::map<size_t, double> height;       // grid vertex -> lowest height its cells allow
  for (size_t c : cells) {
    const int ix = static_cast<int>(c % g.nx), iy = static_cast<int>(c / g.nx);
    for (int k = 0; k < 4; ++k) {
      const int vx = ix + (k == 1 || k == 2 ? 1 : 0), vy = iy + (k >= 2 ? 1 : 0);
      const size_t v = static_cast<size_t>(vy) * (g.nx + 1) + vx;
      const double x = g.x0 + vx * g.cell - g.x0, y = g.y0 + vy * g.cell - g.y0;
      double z = plane[0] + plane[1] * x + plane[2] * y;
      if (std::isfinite(g.top[c])) {
        z = std::min(z, static_cast<double>(g.top[c]));
      }
      const auto [it, fresh] = height.emplace(v, z);
      if (!fresh) {
        it->second = std::min(it->second, z);
      }
    }
  }
  for (const auto& [v, z] : height) {
    vertex_of[v] = static_cast<uint32_t>(out.vertices.size());
    const int vx = static_cast<int>(v % (g.nx + 1)), vy = static_cast<int>(v / (g.nx + 1));
    out.vertices.push_back({g.x0 + vx * g.cell, g.y0 + vy * g.cell, z - drop});
  }
  for (size_t c : cells) {
    const int ix = static_cast<int>(c % g.nx), iy = static_cast<int>(c / g.nx);
    const size_t row = static_cast<size_t>(g.nx) + 1;
    const uint32_t a = vertex_of[iy * row + ix], b = vertex_of[iy * row + ix + 1];
    const uint32_t d = vertex_of[(iy + 1) * row + ix], e = vertex_of[(iy + 1) * row + ix + 1];
    out.triangles.push_back({a, b, e});
    out.triangles.push_back({a, e, d});
  }
}

/// The grid over a junction's area with every lane triangle near it rasterised; false when the
/// junction has no area (no connecting road surface and no boundary).
bool sample_junction(const Map& map, const RoadMesh& mesh, const TriangleBins& bins,
                     const std::vector<std::vector<uint32_t>>& by_road, const Junction& junction,
                     const std::vector<uint32_t>& inside, const JunctionHoleOptions& options,
                     HoleGrid& g) {
  const std::set<uint32_t> own = junction_roads(map, junction, inside);
  std::vector<Vec2d> area = boundary_outline(map, junction);
  if (area.empty()) {
    std::vector<Vec2d> points;
    for (uint32_t r : inside) {
      for (uint32_t t : by_road[r]) {
        for (uint32_t v : mesh.triangles[t]) {
          points.push_back({mesh.vertices[v].x, mesh.vertices[v].y});
        }
      }
    }
    area = convex_hull(std::move(points));
  }
  if (area.size() < 3) {
    return false;
  }
  Vec2d lo{1e300, 1e300}, hi{-1e300, -1e300};
  for (const Vec2d& p : area) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  // A junction spread over hundreds of metres is sampled more coarsely, so the grid stays
  // within kMaxCells (a 200 x 200 m area at 0.1 m).
  g.cell = std::max(options.cell, std::sqrt((hi.x - lo.x) * (hi.y - lo.y) / kMaxCells));
  g.x0 = std::floor(lo.x / g.cell) * g.cell - 2 * g.cell;
  g.y0 = std::floor(lo.y / g.cell) * g.cell - 2 * g.cell;
  g.nx = static_cast<int>(std::ceil((hi.x - g.x0) / g.cell)) + 2;
  g.ny = static_cast<int>(std::ceil((hi.y - g.y0) / g.cell)) + 2;
  const size_t n = static_cast<size_t>(g.nx) * g.ny;
  g.cover.assign(n, 0);
  g.top.assign(n, -std::numeric_limits<float>::infinity());
  g.inside.assign(n, 0);
  std::vector<double> crossings;
  for (int iy = 0; iy < g.ny; ++iy) {
    fill_row(area, g.cy(iy), g.x0, g.cell, crossings, &g.inside[g.at(0, iy)], g.nx);
  }
  const std::vector<uint32_t> near = bins.near({g.x0, g.y0}, {hi.x + g.cell, hi.y + g.cell});
  // The junction's level: other roads far above or below it (bridges) do not border its holes.
  double z_min = 1e300, z_max = -1e300;
  for (uint32_t t : near) {
    if (own.count(mesh.info[t].road_index) != 0) {
      for (uint32_t v : mesh.triangles[t]) {
        z_min = std::min(z_min, mesh.vertices[v].z);
        z_max = std::max(z_max, mesh.vertices[v].z);
      }
    }
  }
  for (uint32_t t : near) {
    const TriangleInfo& info = mesh.info[t];
    if (own.count(info.road_index) != 0) {
      rasterise(mesh, t, is_kerb_lane(info.lane_type) ? kOwnKerb : kOwnRoadway, true, g);
      continue;
    }
    double t_min = 1e300, t_max = -1e300;
    for (uint32_t v : mesh.triangles[t]) {
      t_min = std::min(t_min, mesh.vertices[v].z);
      t_max = std::max(t_max, mesh.vertices[v].z);
    }
    if (t_min < z_max + kLevelBand && t_max > z_min - kLevelBand) {
      rasterise(mesh, t, kForeign, false, g);
    }
  }
  return true;
}

}  // namespace

const char* hole_kind_name(HoleKind kind) {
  switch (kind) {
    case HoleKind::kPaved:
      return "paved";
    case HoleKind::kLarge:
      return "large";
    case HoleKind::kKerbed:
      return "kerbed";
    case HoleKind::kOccupied:
      return "occupied";
  }
  return "paved";
}

std::vector<JunctionHole> find_junction_holes(const Map& map, const RoadMesh& road,
                                              const JunctionHoleOptions& options) {
  std::vector<JunctionHole> out;
  const TriangleBins bins(road);
  std::vector<std::vector<uint32_t>> by_road(map.road_count());
  for (uint32_t t = 0; t < road.triangles.size(); ++t) {
    if (road.info[t].kind == SurfaceKind::kLane) {
      by_road[road.info[t].road_index].push_back(t);
    }
  }
  const std::vector<Vec2d> standing = standing_points(map);
  std::map<std::string, std::vector<uint32_t>> roads_in;  // junction id -> its connecting roads
  for (uint32_t r = 0; r < map.road_count(); ++r) {
    if (map.road(r).in_junction()) {
      roads_in[map.road(r).junction].push_back(r);
    }
  }
  for (size_t j = 0; j < map.junction_count(); ++j) {
    HoleGrid g;
    const Junction& junction = map.junction(j);
    const auto inside = roads_in.find(junction.id);
    if (inside == roads_in.end() ||
        !sample_junction(map, road, bins, by_road, junction, inside->second, options, g)) {
      continue;
    }
    const std::vector<HoleCells> holes = enclosed_cells(g);
    if (holes.empty()) {
      continue;
    }
    std::vector<int> hole_of(g.cover.size(), -1);
    for (size_t h = 0; h < holes.size(); ++h) {
      for (size_t c : holes[h].cells) {
        hole_of[c] = static_cast<int>(h);
      }
    }
    std::vector<uint8_t> occupied(holes.size(), 0);
    for (const Vec2d& p : standing) {
      const int ix = static_cast<int>(std::floor((p.x - g.x0) / g.cell));
      const int iy = static_cast<int>(std::floor((p.y - g.y0) / g.cell));
      if (ix >= 0 && iy >= 0 && ix < g.nx && iy < g.ny && hole_of[g.at(ix, iy)] >= 0) {
        occupied[hole_of[g.at(ix, iy)]] = 1;
      }
    }
    for (size_t h = 0; h < holes.size(); ++h) {
      const HoleCells& cells = holes[h];
      JunctionHole hole;
      hole.junction = j;
      hole.area = static_cast<double>(cells.cells.size()) * g.cell * g.cell;
      if (hole.area < options.min_area) {
        continue;
      }
      const double deepest = deepest_clearance(g, cells.cells);
      double sx = 0.0, sy = 0.0;
      for (size_t c : cells.cells) {
        sx += g.cx(static_cast<int>(c % g.nx));
        sy += g.cy(static_cast<int>(c / g.nx));
      }
      // The disc around the deepest cell reaches to the covered cells' near edges.
      hole.width = std::max(0.0, 2.0 * deepest - g.cell);
      const auto count = static_cast<double>(cells.cells.size());
      const std::array<double, 3> plane = rim_plane(g, cells.rim);
      hole.centre = {sx / count, sy / count,
                     plane[0] + plane[1] * (sx / count - g.x0) + plane[2] * (sy / count - g.y0)};
      if (occupied[h] != 0) {
        hole.kind = HoleKind::kOccupied;
      } else if ((cells.rim_cover & (kOwnKerb | kForeign)) != 0) {
        hole.kind = HoleKind::kKerbed;
      } else if (hole.area >= options.max_area && hole.width >= options.max_width) {
        hole.kind = HoleKind::kLarge;
      } else {
        hole.kind = HoleKind::kPaved;
        pave(g, cells, options.drop, hole);
      }
      out.push_back(std::move(hole));
    }
  }
  return out;
}

}  // namespace corsa::xodr
