// Stage 2 of a camera pass: the visibilities estimated with a few rays per pixel are averaged
// over neighbours that lie on the same surface (the same plane within a few centimetres and the
// same orientation): an edge-avoiding a-trous filter (Dammertz, Sewtz, Hanika and Lensch,
// "Edge-Avoiding A-Trous Wavelet Transform for fast Global Illumination Filtering", HPG 2010)
// with a 3x3 B-spline kernel, steps 1 and 2 for sky and light visibility (and 4 as well when a
// pixel has a single sky ray), step 1 for the sun (whose penumbrae are narrow). Only
// visibilities are filtered, never textures.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "camera_frame.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace corsa::sensors::detail {
namespace {

/// Similarity of neighbour q to centre p: 0 (another surface) .. 1 (the same plane), for
/// `inv_tolerance` = 1 / (0.02 + 0.004 distance of p) (m^-1: how far off p's plane q may lie).
float geometry_weight(const PixelGeometry& p, const PixelGeometry& q, float inv_tolerance) {
  if (q.surface_id == 0) {
    return 0.0f;
  }
  const float dx = q.position[0] - p.position[0];
  const float dy = q.position[1] - p.position[1];
  const float dz = q.position[2] - p.position[2];
  const float plane = std::fabs(p.normal[0] * dx + p.normal[1] * dy + p.normal[2] * dz);
  const float t = plane * inv_tolerance;
  const float along = 1.0f / (1.0f + t * t);
  float c = p.normal[0] * q.normal[0] + p.normal[1] * q.normal[1] + p.normal[2] * q.normal[2];
  c = std::max(c, 0.0f);
  const float c2 = c * c;
  const float c4 = c2 * c2;
  return along * c4 * c4;
}

/// Running sums of one pixel's filter: weights and weighted visibilities.
struct FilterSums {
  float w = 0.0f, w_sun = 0.0f;
  float sky[3] = {0, 0, 0};
  float lights = 0.0f, sun = 0.0f;

  void add(float g, const PixelVisibility& v, bool with_sun) {
    w += g;
    sky[0] += g * v.sky[0];
    sky[1] += g * v.sky[1];
    sky[2] += g * v.sky[2];
    lights += g * v.lights;
    if (with_sun) {
      w_sun += g;
      sun += g * v.sun;
    }
  }
};

constexpr float kKernel[3] = {0.25f, 0.5f, 0.25f};  // B-spline taps

/// The sums over the 3x3 taps of pixel (row, col) at `step`, in row-major tap order.
/// `interior`: every tap lies inside the image (no bounds checks). A tap of weight 0 adds
/// exactly nothing (weights and visibilities are finite and non-negative, the sums start at
/// +0), so the interior path adds it instead of branching, with the same result.
template <bool interior>
FilterSums filter_sums(const Pass& p, const std::vector<PixelVisibility>& in, int row, int col,
                       int step, bool sun) {
  const int w = p.width;
  const int h = p.height;
  const std::vector<PixelGeometry>& rec = *p.geometry;
  const size_t px = static_cast<size_t>(row) * w + col;
  const PixelGeometry& c = rec[px];
  const float inv_tolerance = 1.0f / (0.02f + 0.004f * c.distance);
  FilterSums s;
  for (int j = -1; j <= 1; ++j) {
    const int r = row + j * step;
    if (!interior && (r < 0 || r >= h)) {
      continue;
    }
    for (int i = -1; i <= 1; ++i) {
      const int q = col + i * step;
      if (!interior && (q < 0 || q >= w)) {
        continue;
      }
      const size_t qx = static_cast<size_t>(r) * w + q;
      const float g = (qx == px ? 1.0f : geometry_weight(c, rec[qx], inv_tolerance)) *
                      kKernel[i + 1] * kKernel[j + 1];
      if (!interior && g <= 0.0f) {
        continue;
      }
      s.add(g, in[qx], sun);
    }
  }
  return s;
}

#if defined(__SSE2__)
static_assert(sizeof(PixelGeometry) == 32,
              "the 4-lane filter reads a pixel's geometry as 8 floats");

/// Four pixels' geometry (consecutive in memory) as one plane per field.
struct GeometryLanes {
  __m128 x, y, z, nx, ny, nz, distance;
  __m128i id;
};

GeometryLanes load_lanes(const PixelGeometry* g) {
  const float* f = reinterpret_cast<const float*>(g);
  __m128 a0 = _mm_loadu_ps(f), a1 = _mm_loadu_ps(f + 8), a2 = _mm_loadu_ps(f + 16),
         a3 = _mm_loadu_ps(f + 24);
  __m128 b0 = _mm_loadu_ps(f + 4), b1 = _mm_loadu_ps(f + 12), b2 = _mm_loadu_ps(f + 20),
         b3 = _mm_loadu_ps(f + 28);
  _MM_TRANSPOSE4_PS(a0, a1, a2, a3);
  _MM_TRANSPOSE4_PS(b0, b1, b2, b3);
  return {a0, a1, a2, a3, b0, b1, b2, _mm_castps_si128(b3)};
}

/// geometry_weight() of four centres against four neighbours, lane by lane with the same
/// single-precision operations in the same order (no fused multiply-add), so the same bits.
__m128 geometry_weights(const GeometryLanes& p, const GeometryLanes& q, __m128 inv_tolerance) {
  const __m128 dx = _mm_sub_ps(q.x, p.x);
  const __m128 dy = _mm_sub_ps(q.y, p.y);
  const __m128 dz = _mm_sub_ps(q.z, p.z);
  __m128 plane =
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(p.nx, dx), _mm_mul_ps(p.ny, dy)), _mm_mul_ps(p.nz, dz));
  plane = _mm_andnot_ps(_mm_set1_ps(-0.0f), plane);  // fabs
  const __m128 t = _mm_mul_ps(plane, inv_tolerance);
  const __m128 one = _mm_set1_ps(1.0f);
  const __m128 along = _mm_div_ps(one, _mm_add_ps(one, _mm_mul_ps(t, t)));
  __m128 c = _mm_add_ps(_mm_add_ps(_mm_mul_ps(p.nx, q.nx), _mm_mul_ps(p.ny, q.ny)),
                        _mm_mul_ps(p.nz, q.nz));
  c = _mm_max_ps(_mm_setzero_ps(), c);  // std::max(c, 0.0f): 0 where c < 0
  const __m128 c2 = _mm_mul_ps(c, c);
  const __m128 c4 = _mm_mul_ps(c2, c2);
  const __m128 weight = _mm_mul_ps(along, _mm_mul_ps(c4, c4));
  const __m128 sky = _mm_castsi128_ps(_mm_cmpeq_epi32(q.id, _mm_setzero_si128()));
  return _mm_andnot_ps(sky, weight);  // 0 against the sky
}

/// filter_sums<true>() of the four pixels from (row, col) on, four at a time: each lane adds
/// its pixel's taps in the same order with the same operations, so the same bits.
void filter_sums4(const Pass& p, const std::vector<PixelVisibility>& in, int row, int col, int step,
                  bool sun, FilterSums* sums) {
  const int w = p.width;
  const PixelGeometry* rec = p.geometry->data();
  const size_t px = static_cast<size_t>(row) * w + col;
  const GeometryLanes c = load_lanes(rec + px);
  const __m128 inv_tolerance =
      _mm_div_ps(_mm_set1_ps(1.0f),
                 _mm_add_ps(_mm_set1_ps(0.02f), _mm_mul_ps(_mm_set1_ps(0.004f), c.distance)));
  __m128 sum_w = _mm_setzero_ps(), sum_w_sun = _mm_setzero_ps();
  __m128 sky0 = _mm_setzero_ps(), sky1 = _mm_setzero_ps(), sky2 = _mm_setzero_ps();
  __m128 lights = _mm_setzero_ps(), sun_v = _mm_setzero_ps();
  for (int j = -1; j <= 1; ++j) {
    const size_t r = static_cast<size_t>(row + j * step) * w;
    const __m128 kj = _mm_set1_ps(kKernel[j + 1]);
    for (int i = -1; i <= 1; ++i) {
      const size_t qx = r + static_cast<size_t>(col + i * step);
      const __m128 ki = _mm_set1_ps(kKernel[i + 1]);
      const __m128 weight =
          qx == px ? _mm_set1_ps(1.0f) : geometry_weights(c, load_lanes(rec + qx), inv_tolerance);
      const __m128 g = _mm_mul_ps(_mm_mul_ps(weight, ki), kj);
      const PixelVisibility* v = &in[qx];
      sum_w = _mm_add_ps(sum_w, g);
      sky0 = _mm_add_ps(
          sky0, _mm_mul_ps(g, _mm_setr_ps(v[0].sky[0], v[1].sky[0], v[2].sky[0], v[3].sky[0])));
      sky1 = _mm_add_ps(
          sky1, _mm_mul_ps(g, _mm_setr_ps(v[0].sky[1], v[1].sky[1], v[2].sky[1], v[3].sky[1])));
      sky2 = _mm_add_ps(
          sky2, _mm_mul_ps(g, _mm_setr_ps(v[0].sky[2], v[1].sky[2], v[2].sky[2], v[3].sky[2])));
      lights = _mm_add_ps(
          lights, _mm_mul_ps(g, _mm_setr_ps(v[0].lights, v[1].lights, v[2].lights, v[3].lights)));
      if (sun) {
        sum_w_sun = _mm_add_ps(sum_w_sun, g);
        sun_v =
            _mm_add_ps(sun_v, _mm_mul_ps(g, _mm_setr_ps(v[0].sun, v[1].sun, v[2].sun, v[3].sun)));
      }
    }
  }
  alignas(16) float f[7][4];
  _mm_store_ps(f[0], sum_w);
  _mm_store_ps(f[1], sum_w_sun);
  _mm_store_ps(f[2], sky0);
  _mm_store_ps(f[3], sky1);
  _mm_store_ps(f[4], sky2);
  _mm_store_ps(f[5], lights);
  _mm_store_ps(f[6], sun_v);
  for (int l = 0; l < 4; ++l) {
    sums[l] = {f[0][l], f[1][l], {f[2][l], f[3][l], f[4][l]}, f[5][l], f[6][l]};
  }
}
#endif

void filter_step(const Pass& p, const std::vector<PixelVisibility>& in,
                 std::vector<PixelVisibility>& out, int step, bool sun) {
  const int w = p.width;
  const int h = p.height;
  const std::vector<PixelGeometry>& rec = *p.geometry;
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int row = rows.begin(); row != rows.end(); ++row) {
      const bool inner_row = row - step >= 0 && row + step < h;
      auto store = [&](size_t px, const FilterSums& s) {
        PixelVisibility& o = out[px];
        o.sky[0] = s.sky[0] / s.w;
        o.sky[1] = s.sky[1] / s.w;
        o.sky[2] = s.sky[2] / s.w;
        o.lights = s.lights / s.w;
        if (sun) {
          o.sun = s.sun / s.w_sun;
        }
      };
      for (int col = 0; col < w; ++col) {
        const size_t px = static_cast<size_t>(row) * w + col;
#if defined(__SSE2__)
        // Four interior pixels at once (the sky among them only copied).
        if (inner_row && col - step >= 0 && col + 3 + step < w) {
          FilterSums sums[4];
          filter_sums4(p, in, row, col, step, sun, sums);
          for (int l = 0; l < 4; ++l) {
            out[px + l] = in[px + l];
            if (rec[px + l].surface_id != 0) {
              store(px + l, sums[l]);
            }
          }
          col += 3;
          continue;
        }
#endif
        out[px] = in[px];
        if (rec[px].surface_id == 0) {
          continue;
        }
        const bool inner = inner_row && col - step >= 0 && col + step < w;
        store(px, inner ? filter_sums<true>(p, in, row, col, step, sun)
                        : filter_sums<false>(p, in, row, col, step, sun));
      }
    }
  });
}

}  // namespace

void filter_visibility(const Pass& p) {
  std::vector<PixelVisibility>& vis = *p.visibility;
  std::vector<PixelVisibility>& tmp = *p.visibility_scratch;
  tmp.resize(vis.size());
  filter_step(p, vis, tmp, 1, true);
  filter_step(p, tmp, vis, 2, false);
  if (p.shading->quality.sky_rays == 1) {
    // One sky ray a pixel: a third, wider step for the sky and lamp visibility.
    filter_step(p, vis, tmp, 4, false);
    vis.swap(tmp);
  }
}

}  // namespace corsa::sensors::detail
