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

void filter_step(const Pass& p, const std::vector<PixelVisibility>& in,
                 std::vector<PixelVisibility>& out, int step, bool sun) {
  const int w = p.width;
  const int h = p.height;
  const std::vector<PixelGeometry>& rec = *p.geometry;
  constexpr float kernel[3] = {0.25f, 0.5f, 0.25f};
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int row = rows.begin(); row != rows.end(); ++row) {
      for (int col = 0; col < w; ++col) {
        const size_t px = static_cast<size_t>(row) * w + col;
        out[px] = in[px];
        const PixelGeometry& c = rec[px];
        if (c.surface_id == 0) {
          continue;
        }
        const float inv_tolerance = 1.0f / (0.02f + 0.004f * c.distance);
        float sum_w = 0.0f, sum_w_sun = 0.0f;
        float sky[3] = {0, 0, 0}, lights = 0.0f, sun_v = 0.0f;
        for (int j = -1; j <= 1; ++j) {
          const int r = row + j * step;
          if (r < 0 || r >= h) {
            continue;
          }
          for (int i = -1; i <= 1; ++i) {
            const int q = col + i * step;
            if (q < 0 || q >= w) {
              continue;
            }
            const size_t qx = static_cast<size_t>(r) * w + q;
            const float g = (qx == px ? 1.0f : geometry_weight(c, rec[qx], inv_tolerance)) *
                            kernel[i + 1] * kernel[j + 1];
            if (g <= 0.0f) {
              continue;
            }
            const PixelVisibility& v = in[qx];
            sum_w += g;
            sky[0] += g * v.sky[0];
            sky[1] += g * v.sky[1];
            sky[2] += g * v.sky[2];
            lights += g * v.lights;
            if (sun) {
              sum_w_sun += g;
              sun_v += g * v.sun;
            }
          }
        }
        PixelVisibility& o = out[px];
        o.sky[0] = sky[0] / sum_w;
        o.sky[1] = sky[1] / sum_w;
        o.sky[2] = sky[2] / sum_w;
        o.lights = lights / sum_w;
        if (sun) {
          o.sun = sun_v / sum_w_sun;
        }
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
