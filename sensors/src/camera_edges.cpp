// Stages 3 and 4 of a camera pass: the centre sample of every pixel is composited (terms times
// filtered visibilities, seen through the air); pixels at the edge of an object, a material or a
// fold (another surface, depth or orientation next to them; not foliage's folds) then get extra
// sub-pixel samples in a jittered grid, and their colour is the mean of all of them. Textures
// are prefiltered, so pixels inside a surface need no more. An extra sample on a surface whose
// centre sample a neighbour shows near it takes that neighbour's composited radiance: the
// samples resolve which surface covers how much of the pixel, and within a pixel's reach the
// prefiltered texture and the light change little, and shading each sample again was about
// two fifths of this stage's instructions. A sample on a surface no neighbour's centre shows (a
// thin pole) is shaded, lit with one shadow ray to the sun and the open sky. The samples of several
// pixels of a row share one 16-ray packet (a packet of 16 rays costs Embree about 1.4 times one
// of 4). Labels, depth and instance ids stay those of the centre sample.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "brdf.h"
#include "camera_frame.h"

namespace corsa::sensors::detail {
namespace {

bool differs(const PixelGeometry& a, const PixelGeometry& b) {
  if (a.surface_id != b.surface_id) {
    return true;
  }
  if (a.surface_id == 0) {
    return false;
  }
  if (std::fabs(a.distance - b.distance) > 0.04f * std::min(a.distance, b.distance)) {
    return true;
  }
  if ((a.surface_id & kFoldlessSurface) != 0) {
    return false;  // a fold in foliage (shading.h)
  }
  const float c = a.normal[0] * b.normal[0] + a.normal[1] * b.normal[1] + a.normal[2] * b.normal[2];
  return c < 0.9f;
}

/// The neighbour (3x3) whose centre sample lies on surface `surface_id` closest to `position`
/// (a sample `distance` metres away), or -1.
long long matching_neighbour(const Pass& p, int col, int row, uint32_t surface_id, Vec3 position,
                             double distance) {
  long long best = -1;
  double best_d2 = std::pow(0.05 + 0.02 * distance, 2.0);
  for (int j = -1; j <= 1; ++j) {
    for (int i = -1; i <= 1; ++i) {
      const int c = col + i, r = row + j;
      if (c < 0 || r < 0 || c >= p.width || r >= p.height) {
        continue;
      }
      const size_t q = static_cast<size_t>(r) * p.width + c;
      const PixelGeometry& rec = (*p.geometry)[q];
      if (rec.surface_id != surface_id) {
        continue;
      }
      const Vec3 d = Vec3{rec.position[0], rec.position[1], rec.position[2]} - position;
      const double d2 = dot(d, d);
      if (d2 < best_d2) {
        best_d2 = d2;
        best = static_cast<long long>(q);
      }
    }
  }
  return best;
}

/// The radiance of a sample on a surface no neighbour's centre shows (a thin pole): shaded
/// there, lit with one shadow ray to the sun and the open sky.
Color shade_unmatched(const Pass& p, const RTCRayHit16& rh, int k, Vec3 dir) {
  const ShadingContext& c = *p.shading;
  const SceneData& d = *p.scene;
  const Lighting& l = *c.lighting;
  const SurfaceHit h =
      primary_hit(p, rh, k, dir, d.label(rh.hit.instID[0][k], rh.hit.geomID[k], rh.hit.primID[k]));
  const SurfacePoint s = surface_at(c, h);
  const ShadeTerms terms = shade_terms(c, s, nullptr, nullptr);
  Visibility v;
  v.sky = {0.85, 0.85, 0.85};
  if (dot(s.normal, l.sun_direction) > 0.0 && luminance(l.sun) > 0.0) {
    RTCRay shadow{};
    const Vec3 o = s.position + s.normal * (0.01 + 1e-4 * s.distance);
    shadow.org_x = static_cast<float>(o.x);
    shadow.org_y = static_cast<float>(o.y);
    shadow.org_z = static_cast<float>(o.z);
    shadow.dir_x = static_cast<float>(l.sun_direction.x);
    shadow.dir_y = static_cast<float>(l.sun_direction.y);
    shadow.dir_z = static_cast<float>(l.sun_direction.z);
    shadow.tfar = std::numeric_limits<float>::infinity();
    shadow.mask = 0xFFFFFFFFu;
    RTCIntersectContext sc;
    rtcInitIntersectContext(&sc);
    rtcOccluded1(d.top, &sc, &shadow);
    v.sun = shadow.tfar >= 0.0f ? 1.0 : 0.0;
  }
  return through_air(c, combine(terms, v), p.origin_local, dir, h.distance);
}

/// Anti-aliases the edge pixels at columns `cols` of `row`, `count` jittered sub-pixel samples
/// each, their rays in packets of 16 (16 / count pixels a packet). A sample on a surface whose
/// centre sample a neighbour shows near it takes that neighbour's composited radiance (read from
/// `centre`, the image before this stage): within a pixel the prefiltered textures and the
/// lighting change by far less than across the edge, which the share of samples on each side
/// resolves. The pixel's colour, in `linear`, is the mean of its centre and its samples.
void resample_row(const Pass& p, int row, const std::vector<int>& cols, int count,
                  const std::vector<float>& centre, std::vector<float>& linear) {
  const ShadingContext& c = *p.shading;
  const SceneData& d = *p.scene;
  const int gx = count >= 12 ? 4 : 2;
  const int gy = (count + gx - 1) / gx;
  const size_t per_packet = 16 / static_cast<size_t>(count);
  for (size_t first = 0; first < cols.size(); first += per_packet) {
    const size_t n = std::min(per_packet, cols.size() - first);
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[16];
    Vec3 dirs[16];
    for (int k = 0; k < 16; ++k) {
      const size_t slot = static_cast<size_t>(k / count);
      const int j = k % count;
      valid[k] = slot < n ? -1 : 0;
      if (valid[k]) {
        const int col = cols[first + slot];
        const size_t px = static_cast<size_t>(row) * p.width + col;
        const uint64_t key = pixel_key(p.settings->frame_seed, px, 0xAA);
        const double x = col + ((j % gx) + hash_uniform(key, 2 * j)) / gx - 0.5;
        const double y = row + ((j / gx) + hash_uniform(key, 2 * j + 1)) / gy - 0.5;
        dirs[k] = ray_at(p, x, y);
      } else {
        dirs[k] = Vec3{0.0, 0.0, 1.0};
      }
      rh.ray.org_x[k] = static_cast<float>(p.origin_local.x);
      rh.ray.org_y[k] = static_cast<float>(p.origin_local.y);
      rh.ray.org_z[k] = static_cast<float>(p.origin_local.z);
      rh.ray.dir_x[k] = static_cast<float>(dirs[k].x);
      rh.ray.dir_y[k] = static_cast<float>(dirs[k].y);
      rh.ray.dir_z[k] = static_cast<float>(dirs[k].z);
      rh.ray.tnear[k] = p.carrier.exit(dirs[k]);
      rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
      rh.ray.mask[k] = 0xFFFFFFFFu;
      rh.ray.flags[k] = 0;
      rh.ray.time[k] = 0.0f;
      rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect16(valid, d.top, &context, &rh);

    for (size_t slot = 0; slot < n; ++slot) {
      const int col = cols[first + slot];
      Color sum;
      for (int j = 0; j < count; ++j) {
        const int k = static_cast<int>(slot) * count + j;
        if (rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) {
          sum = sum + sky_seen(c, p.origin_local, dirs[k]);
          continue;
        }
        const unsigned inst = rh.hit.instID[0][k];
        const unsigned geom = rh.hit.geomID[k];
        const uint32_t sid =
            surface_id_of(d, inst, geom, d.material_of(inst, geom, rh.hit.primID[k]));
        const double t = rh.ray.tfar[k];
        const long long q = matching_neighbour(p, col, row, sid, p.origin_local + dirs[k] * t, t);
        if (q < 0) {
          sum = sum + shade_unmatched(p, rh, k, dirs[k]);
          continue;
        }
        const float* seen = &centre[3 * static_cast<size_t>(q)];
        sum = sum + Color{seen[0], seen[1], seen[2]};
      }
      const size_t px = static_cast<size_t>(row) * p.width + col;
      const float* own = &centre[3 * px];
      float* out = &linear[3 * px];
      const double total = count + 1.0;
      out[0] = static_cast<float>((own[0] + sum.r) / total);
      out[1] = static_cast<float>((own[1] + sum.g) / total);
      out[2] = static_cast<float>((own[2] + sum.b) / total);
    }
  }
}

}  // namespace

Color composite_pixel(const Pass& p, size_t px, const ShadeTerms& terms, const PixelVisibility& vis,
                      float distance) {
  const Color lit = combine(terms, vis.get());
  return through_air(*p.shading, lit, p.origin_local, centre_ray(p, px), distance);
}

void composite(const Pass& p, std::vector<float>& linear) {
  const int w = p.width;
  tbb::parallel_for(tbb::blocked_range<int>(0, p.height), [&](const tbb::blocked_range<int>& r) {
    for (int row = r.begin(); row != r.end(); ++row) {
      for (int col = 0; col < w; ++col) {
        const size_t px = static_cast<size_t>(row) * w + col;
        const PixelRecord& rec = (*p.records)[px];
        const PixelGeometry& g = (*p.geometry)[px];
        Color c = rec.terms.base;
        if (g.surface_id != 0) {
          c = composite_pixel(p, px, rec.terms, (*p.visibility)[px], g.distance);
        }
        float* out = &linear[3 * px];
        out[0] = static_cast<float>(c.r);
        out[1] = static_cast<float>(c.g);
        out[2] = static_cast<float>(c.b);
      }
    }
  });
}

size_t antialias_edges(const Pass& p, std::vector<float>& linear, std::vector<float>& centre) {
  const int samples = std::min(p.shading->quality.edge_samples, 16);
  if (samples <= 0) {
    return 0;
  }
  const int w = p.width;
  const int h = p.height;
  const std::vector<PixelGeometry>& rec = *p.geometry;
  std::vector<uint8_t>& edge = *p.edges;
  edge.resize(rec.size());
  // Row by row: a pixel is marked by its own comparisons with the right and lower neighbour
  // and theirs with it, so each row writes only its own marks.
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& r) {
    for (int row = r.begin(); row != r.end(); ++row) {
      for (int col = 0; col < w; ++col) {
        const size_t px = static_cast<size_t>(row) * w + col;
        bool e = false;
        e = e || (col + 1 < w && differs(rec[px], rec[px + 1]));
        e = e || (col > 0 && differs(rec[px], rec[px - 1]));
        e = e || (row + 1 < h && differs(rec[px], rec[px + w]));
        e = e || (row > 0 && differs(rec[px], rec[px - w]));
        edge[px] = e ? 1 : 0;
      }
    }
  });
  // The samples read their neighbours' centre radiance as composited, before any of them is
  // averaged (whatever the order rows are done in).
  centre = linear;
  std::atomic<size_t> count{0};
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& r) {
    size_t local = 0;
    std::vector<int> cols;
    for (int row = r.begin(); row != r.end(); ++row) {
      cols.clear();
      for (int col = 0; col < w; ++col) {
        if (edge[static_cast<size_t>(row) * w + col]) {
          cols.push_back(col);
        }
      }
      local += cols.size();
      resample_row(p, row, cols, samples, centre, linear);
    }
    count += local;
  });
  return count.load();
}

}  // namespace corsa::sensors::detail
